// steady_metrics.cpp: metrics of a steady state from the dense output of the flow (metrics.hpp,
// compute_metrics(model, result)): one steady period is integrated again from the first sample,
// and every metric is evaluated on the trajectory itself rather than on the uniform samples, so
// that it does not depend on numerics.samples_per_period.
//   peaks: at both ends of every piece (the one-sided limits at each switch instant) and at every
//     interior extremum, located by Brent's method on the piece's dense output;
//   harmonics, phase lags, THD, friction work, phase fractions: integrals over each piece by
//     16-point Gauss-Legendre quadrature (a piece is smooth; its Dormand-Prince interpolant is a
//     polynomial in t);
//   area: of the polygon through n points per piece (the switch instants are vertices), n doubled
//     and Richardson-extrapolated until two estimates agree to 1e-9 relative.
#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "metrics/indicators.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/metrics.hpp"

namespace oscidrum {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kScan = 16;                // sub-intervals scanned per piece for interior extrema
constexpr double kAreaRtol = 1e-9;       // convergence of the area
constexpr int kAreaMaxPoints = 1 << 14;  // points per piece at most

struct Point {
  double ddx, ddz, delta, phi, mu, friction_power;
};

Point evaluate(const Model& model, double baumgarte, double t, const State& q, Phase phase) {
  const Accelerations a = accelerations(model, t, q, phase, baumgarte);
  const DrumMotion d = drum_motion(model, q, a);
  const ContactForces f = contact_forces(model, q);
  return {d.ddx_M, d.ddz_M, q.delta, q.phi, std::abs(f.T) / f.N,
          // Friction does work only while the drum slides (13, 27). In stick v_rel = 0 by the
          // rolling condition (12); the flow integrates phi' there without reading it, so
          // slip_velocity would return its round-off drift (over a long transient from rest, up
          // to ~1e-6 of the work of a slipping case).
          phase == Phase::stick ? 0.0 : std::abs(f.T * slip_velocity(model, q))};
}

// Largest (sign = +1) or smallest (-1) value of member m on the piece: ends and interior extrema.
struct Extremes {
  double hi = -std::numeric_limits<double>::infinity();
  double lo = std::numeric_limits<double>::infinity();
  void add(double v) {
    hi = std::max(hi, v);
    lo = std::min(lo, v);
  }
};

struct Node {  // a Gauss-Legendre node of one piece
  double tau, weight, ddx, ddz, phi, friction_power;
};

class Accumulator : public FlowObserver {
 public:
  Accumulator(const Model& model, double baumgarte, double t_begin, double t_end)
      : model_(model), baumgarte_(baumgarte), t_begin_(t_begin), t_end_(t_end) {}

  bool on_step(const StepView& step) override {
    const double a = std::max(step.t0(), t_begin_), b = std::min(step.t1(), t_end_);
    if (!(b > a)) return true;
    const Phase phase = step.phase();
    auto at = [&](double t) { return evaluate(model_, baumgarte_, t, step.state(t), phase); };
    // Extremes: the scan points, including both ends (one-sided limits at switches), then every
    // interior local extremum of the scan refined by Brent's method.
    std::array<Point, kScan + 1> scan;
    std::array<double, kScan + 1> ts;
    for (int k = 0; k <= kScan; ++k) {
      ts[k] = k == kScan ? b : a + (b - a) * k / kScan;
      scan[k] = at(ts[k]);
    }
    refine(scan, ts, at, &Point::ddx, ddx_);
    refine(scan, ts, at, &Point::ddz, ddz_);
    refine(scan, ts, at, &Point::delta, delta_);
    refine(scan, ts, at, &Point::mu, mu_);
    // Quadrature nodes.
    boost::math::quadrature::gauss<double, 16> rule;
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    const auto& x = rule.abscissa();
    const auto& w = rule.weights();
    for (std::size_t i = 0; i < x.size(); ++i) {
      for (double sign : {-1.0, 1.0}) {
        if (x[i] == 0.0 && sign > 0) continue;
        const double t = mid + sign * half * x[i];
        const Point p = at(t);
        nodes_.push_back({t - t_begin_, half * w[i], p.ddx, p.ddz, p.phi, p.friction_power});
      }
    }
    time_[static_cast<int>(phase) + 1] += b - a;
    if (a == t_begin_) phi_begin_ = at(a).phi;
    if (b == t_end_) phi_end_ = at(b).phi;
    return true;
  }

  template <class At>
  static void refine(const std::array<Point, kScan + 1>& scan,
                     const std::array<double, kScan + 1>& ts, const At& at, double Point::*m,
                     Extremes& out) {
    for (const Point& p : scan) out.add(p.*m);
    // A scan point not beaten by its neighbours brackets an extremum between them. At the ends
    // of the piece only one neighbour exists: an end that is not beaten by it may have the
    // extremum just inside the piece (between the last scan point and the end), which the end's
    // value alone misses by about half the curvature times the squared distance (up to ~1e-5
    // of a peak); the one-sided bracket finds it (or returns the end itself).
    for (int k = 0; k <= kScan; ++k) {
      const int lo = std::max(0, k - 1), hi = std::min(kScan, k + 1);
      const double v = scan[k].*m, l = scan[lo].*m, r = scan[hi].*m;
      for (double sign : {1.0, -1.0}) {
        if (!(sign * v >= sign * l && sign * v >= sign * r)) continue;
        // In the offset from the bracket's start: Brent's tolerance is relative to the
        // abscissa, and relative to the absolute time (seconds into a long transient) it would
        // leave the extremum ~1e-7 s off, ~1e-10 of the peak.
        const double t_lo = ts[lo];
        const auto f = [&](double u) { return -sign * (at(t_lo + u).*m); };
        const auto best = boost::math::tools::brent_find_minima(
            f, 0.0, ts[hi] - t_lo, std::numeric_limits<double>::digits);
        out.add(-sign * best.second);
      }
    }
  }

  const Model& model_;
  const double baumgarte_, t_begin_, t_end_;
  Extremes ddx_, ddz_, delta_, mu_;
  std::vector<Node> nodes_;
  std::array<double, 3> time_{};  // slip-, stick, slip+ [s]
  double phi_begin_ = 0.0, phi_end_ = 0.0;
};

// The polygon through `per_piece` + 1 points of every piece of one steady period.
class Polygon : public FlowObserver {
 public:
  Polygon(const Model& model, double baumgarte, double t_begin, double t_end, int per_piece)
      : model_(model), baumgarte_(baumgarte), t_begin_(t_begin), t_end_(t_end), n_(per_piece) {}
  bool on_step(const StepView& step) override {
    const double a = std::max(step.t0(), t_begin_), b = std::min(step.t1(), t_end_);
    if (!(b > a)) return true;
    for (int k = 0; k <= n_; ++k) {
      const double t = k == n_ ? b : a + (b - a) * k / n_;
      const Point p = evaluate(model_, baumgarte_, t, step.state(t), step.phase());
      x.push_back(p.ddx);
      z.push_back(p.ddz);
    }
    return true;
  }
  std::vector<double> x, z;

 private:
  const Model& model_;
  const double baumgarte_, t_begin_, t_end_;
  const int n_;
};

State first_state(const Samples& s) {
  return {s.delta[0], s.x_A[0], s.s_A[0], s.phi[0], s.ddelta[0], s.dx_A[0], s.ds_A[0], s.dphi[0]};
}

Spectrum spectrum(const std::vector<Node>& nodes, double Node::*m, double P, double t0, double f,
                  int cycles, int n_max) {
  Spectrum h(static_cast<std::size_t>(n_max) + 1);
  const double nu = 2.0 * kPi * f;
  double mean = 0.0;
  for (const Node& nd : nodes) mean += nd.weight * (nd.*m);
  mean /= P;
  h[0] = {std::abs(mean), mean >= 0.0 ? kPi / 2.0 : -kPi / 2.0};
  for (int n = 1; n <= n_max; ++n) {
    double a = 0.0, b = 0.0;  // y = a cos(n nu tau) + b sin(n nu tau) + ...
    for (const Node& nd : nodes) {
      a += nd.weight * (nd.*m) * std::cos(n * nu * nd.tau);
      b += nd.weight * (nd.*m) * std::sin(n * nu * nd.tau);
    }
    a *= 2.0 / P;
    b *= 2.0 / P;
    // Phase at tau = 0, then in absolute time: n nu t = n nu tau + n nu t0 (reduced in cycles).
    double cyc = n * f * t0;
    cyc -= std::round(cyc);
    h[static_cast<std::size_t>(n)] = {std::hypot(a, b),
                                      wrap_pi(std::atan2(a, b) - 2.0 * kPi * cyc)};
  }
  (void)cycles;
  return h;
}

}  // namespace

Metrics compute_metrics(const Model& model, const Result& result, int n_max) {
  const Samples& s = result.samples;
  if (s.size() == 0) throw Error("compute_metrics: the result holds no samples");
  if (!ok(result.status))
    throw Error(std::string("compute_metrics: the result has status ") + to_string(result.status) +
                ", not a steady state: no metrics");
  if (n_max < 0) throw Error("compute_metrics: n_max must be >= 0; got " + std::to_string(n_max));
  const int p = result.diagnostics.multiplicity >= 1 ? result.diagnostics.multiplicity : 1;
  const double f = result.frequency, P = p / f;
  const double t0 = s.t.front(), t1 = t0 + P;
  const State q0 = first_state(s);
  const Phase phase0 = s.phase.front();
  const FlowOptions options = FlowOptions::from(model);

  Flow flow(model, options);
  flow.reset(t0, q0, phase0);
  Accumulator acc(model, options.baumgarte, t0, t1);
  if (flow.advance(t1, &acc) != FlowStop::reached)
    throw Error("compute_metrics: the steady period did not integrate again: " + flow.message());

  Metrics m;
  m.ddx_max = acc.ddx_.hi, m.ddx_min = acc.ddx_.lo;
  m.ddz_max = acc.ddz_.hi, m.ddz_min = acc.ddz_.lo;
  m.delta_max = acc.delta_.hi, m.delta_min = acc.delta_.lo;
  m.mu_required = acc.mu_.hi;

  const int n_compute = std::max(n_max, 3);
  Spectrum hx = spectrum(acc.nodes_, &Node::ddx, P, t0, f, p, n_compute);
  Spectrum hz = spectrum(acc.nodes_, &Node::ddz, P, t0, f, p, n_compute);
  m.psi_xz = wrap_pi(hz[2].phase - 2.0 * hx[1].phase);
  {
    const double nu = 2.0 * kPi * f;
    double sum = 0.0;
    for (const Node& nd : acc.nodes_) {
      const double r = nd.ddx - hx[0].amplitude * std::sin(hx[0].phase) -
                       hx[1].amplitude * std::sin(nu * (t0 + nd.tau) + hx[1].phase);
      sum += nd.weight * r * r;
    }
    detail::set_acceleration_indicators(m, hx, hz, 2.0 * sum / P);
  }
  hx.resize(static_cast<std::size_t>(n_max) + 1);
  hz.resize(static_cast<std::size_t>(n_max) + 1);
  m.ddx_harmonics = std::move(hx);
  m.ddz_harmonics = std::move(hz);

  // phi: drift removed, the fundamental against M0 sin(nu t).
  const double rate = (acc.phi_end_ - acc.phi_begin_) / P;
  std::vector<Node> phi_nodes = acc.nodes_;
  for (Node& nd : phi_nodes) nd.phi -= rate * nd.tau;
  const Spectrum hphi = spectrum(phi_nodes, &Node::phi, P, t0, f, p, 1);
  m.phi_amplitude = hphi[1].amplitude;
  double lag = wrap_pi(hphi[1].phase);
  if (lag > 0.0) lag -= 2.0 * kPi;
  m.phi_lag = lag / kPi;

  double work = 0.0;
  for (const Node& nd : acc.nodes_) work += nd.weight * nd.friction_power;
  m.friction_work = work / p;
  const double total = acc.time_[0] + acc.time_[1] + acc.time_[2];  // P up to round-off
  m.stick_fraction = acc.time_[1] / total;
  m.slip_positive_fraction = acc.time_[2] / total;
  m.slip_negative_fraction = acc.time_[0] / total;
  m.slip_fraction = m.slip_positive_fraction + m.slip_negative_fraction;

  // Area: Richardson-extrapolated polygon areas (error ~ h^2) until two agree.
  double previous = std::numeric_limits<double>::quiet_NaN(), coarse = 0.0;
  for (int n = 4; n <= kAreaMaxPoints; n *= 2) {
    Flow again(model, options);
    again.reset(t0, q0, phase0);
    Polygon poly(model, options.baumgarte, t0, t1, n);
    again.advance(t1, &poly);
    const double fine = enclosed_area(poly.x, poly.z);
    if (n > 4) {
      const double extrapolated = (4.0 * fine - coarse) / 3.0;
      if (std::abs(extrapolated - previous) <= kAreaRtol * std::abs(extrapolated)) {
        m.area = extrapolated;
        break;
      }
      previous = extrapolated;
      m.area = extrapolated;
    }
    coarse = fine;
  }
  return m;
}

}  // namespace oscidrum
