// steady_metrics.cpp: metrics of a steady state from the dense output of the flow (metrics.hpp,
// compute_metrics(model, result)): one steady period is integrated again, once, from the first
// sample, and every metric is evaluated on the trajectory itself rather than on the uniform
// samples, so that it does not depend on numerics.samples_per_period. (A study's case passes the
// period its shooting orbit's sampling recorded on the way, src/drivers/period_recording.hpp:
// the same pieces, integrated once.)
// On each piece of the period (one integrator step in one phase) every quantity (x_M'', z_M''
// from (18), delta, phi, T/N, the friction power) is an analytic function of t: the
// Dormand-Prince interpolant (a polynomial) through the equations of motion. Each is replaced by
// its Chebyshev interpolant of degree kDegree (8) through 9 right-hand-side evaluations (both ends
// among them), accurate to round-off (tests/drivers/test_steady_metrics.cpp), and everything below
// reads the interpolants:
//   peaks: at both ends of every piece (the one-sided limits at each switch instant) and at every
//     interior extremum, located by Newton's method on the derivative of the interpolant (only
//     on pieces where a bound on the curvature lets an extremum beat the nodes' values);
//   harmonics, phase lags, THD, friction work, phase fractions: integrals over each piece by
//     kGaussPoints-point Gauss-Legendre quadrature;
//   area: exact for the piecewise curve (src/drivers/curve_area.cpp): Green's theorem on the
//     arcs between its self-intersections, each located by Newton on the interpolants.
#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "drivers/curve_area.hpp"
#include "drivers/period_recording.hpp"
#include "equations/equations.hpp"
#include "metrics/area.hpp"
#include "metrics/indicators.hpp"
#include "metrics/piece_interpolant.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/metrics.hpp"
#include "roller/rollers.hpp"
#include "util/format.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {
namespace {

constexpr double kPi = std::numbers::pi;

using detail::recording::Interpolant;
using detail::recording::kDegree;
using detail::recording::Piece;
using detail::recording::Quantity;
using detail::recording::Recorder;
using detail::recording::Recording;
using enum detail::recording::Quantity;

// Gauss-Legendre points per piece for the integrals over the period (harmonics, lags, friction
// work). The integrands are a piece's interpolant (degree kDegree) times cos or sin of n nu t for
// n <= 10, where n nu times a piece's half-length is a few tenths at most (some hundred pieces
// per period): the rule is exact to degree 19. Against the 16 points used before, the metrics of
// the product sweep (bench/sweep/product.toml) moved by at most 1e-11 relative (a phase lag,
// psi_xz) and 5e-13 (a tenth harmonic); tests/drivers/test_steady_metrics.cpp compares them with
// a brute-force evaluation.
constexpr int kGaussPoints = 10;
using GaussRule = boost::math::quadrature::gauss<double, kGaussPoints>;

// T_j(x_i), j = 0 ... kDegree, at the abscissas x_i >= 0 of the Gauss-Legendre rule
// (by the recurrence T_j+1 = 2 x T_j - T_j-1): the Chebyshev sums at the quadrature nodes.
const std::vector<std::array<double, kDegree + 1>>& gauss_chebyshev() {
  static const auto table = [] {
    const auto& x = GaussRule::abscissa();
    std::vector<std::array<double, kDegree + 1>> T(x.size());
    for (std::size_t i = 0; i < T.size(); ++i) {
      T[i][0] = 1.0;
      T[i][1] = x[i];
      for (int j = 1; j < kDegree; ++j) T[i][j + 1] = 2.0 * x[i] * T[i][j] - T[i][j - 1];
    }
    return T;
  }();
  return table;
}

// Largest and smallest value of a quantity: ends and interior extrema of every piece.
struct Extremes {
  double hi = -std::numeric_limits<double>::infinity();
  double lo = std::numeric_limits<double>::infinity();
  void add(double v) {
    hi = std::max(hi, v);
    lo = std::min(lo, v);
  }
};

// The interior extrema of one piece, bracketed by its interpolation nodes (exact values, scanned
// in increasing t; the caller has added the node values themselves). Maxima only if want_max,
// minima only if want_min.
void add_extremes(const Interpolant& f, const std::array<double, Interpolant::kNodes>& values,
                  bool want_max, bool want_min, Extremes& out) {
  constexpr int kScan = kDegree;
  const double a = f.a(), b = f.b();
  std::array<double, kScan + 1> ts, scan;
  for (int k = 0; k <= kScan; ++k) {
    ts[k] = k == 0 ? a : k == kScan ? b : Interpolant::node(a, b, kScan - k);
    scan[k] = values[kScan - k];
  }
  // f' and f'' only for a piece that holds an extremum or ends on the way to one (most do not).
  Interpolant df, d2f;
  bool have_derivatives = false;
  const auto derivatives = [&] {
    if (have_derivatives) return;
    df = f.derivative_interpolant();
    d2f = df.derivative_interpolant();
    have_derivatives = true;
  };
  // A scan point not beaten by its neighbours brackets an extremum between them. At the ends of
  // the piece only one neighbour exists: an end that is not beaten by it may have the extremum
  // just inside the piece (between the last scan point and the end), which the end's value alone
  // misses by about half the curvature times the squared distance (up to ~1e-5 of a peak); the
  // one-sided bracket finds it (or returns the end itself).
  for (int k = 0; k <= kScan; ++k) {
    const int lo = std::max(0, k - 1), hi = std::min(kScan, k + 1);
    const double v = scan[k], l = scan[lo], r = scan[hi];
    for (double sign : {1.0, -1.0}) {
      if (!(sign > 0.0 ? want_max : want_min)) continue;
      if (!(sign * v >= sign * l && sign * v >= sign * r)) continue;
      // An end where the quantity still rises towards the end (falls, for a minimum) is the
      // extremum of its one-sided bracket: nothing to refine.
      derivatives();
      if (k == 0 && sign * df(a) <= 0.0) continue;
      if (k == kScan && sign * df(b) >= 0.0) continue;
      out.add(detail::extremum(f, df, d2f, ts[lo], ts[hi] - ts[lo], sign));
    }
  }
}

struct Node {  // a Gauss-Legendre node of one piece
  double tau, weight, ddx, ddz, phi, friction_power, vertical_force, z;
  double cos1, sin1;  // cos(nu tau), sin(nu tau)
};

// The spectra of K quantities at the nodes, harmonics 0 ... n_max: one pass over the nodes,
// cos and sin of n nu tau by the angle-addition recurrence (error ~n ulp) shared by the K sums.
template <std::size_t K>
std::array<Spectrum, K> spectra(const std::vector<Node>& nodes,
                                const std::array<double Node::*, K>& m, double P, double t0,
                                double f, int n_max) {
  const std::size_t n_size = static_cast<std::size_t>(n_max) + 1;
  std::array<double, K> mean{};
  std::vector<double> a(K * n_size, 0.0), b(K * n_size, 0.0);  // a[k n_size + n]
  // y = a_n cos(n nu tau) + b_n sin(n nu tau) + ...: the nodes two at a time, whose recurrences
  // (each a chain of dependent products over the harmonics) are independent and overlap; every
  // sum still adds the nodes in their order, so the same bits as one node at a time.
  std::size_t i = 0;
  for (; i + 1 < nodes.size(); i += 2) {
    const Node &n0 = nodes[i], &n1 = nodes[i + 1];
    std::array<double, K> y0, y1;
    for (std::size_t k = 0; k < K; ++k) {
      y0[k] = n0.weight * (n0.*m[k]);
      y1[k] = n1.weight * (n1.*m[k]);
      mean[k] += y0[k];
      mean[k] += y1[k];
    }
    double c0 = n0.cos1, s0 = n0.sin1, c1 = n1.cos1, s1 = n1.sin1;
    for (std::size_t n = 1; n < n_size; ++n) {
      for (std::size_t k = 0; k < K; ++k) {
        a[k * n_size + n] += y0[k] * c0;
        a[k * n_size + n] += y1[k] * c1;
        b[k * n_size + n] += y0[k] * s0;
        b[k * n_size + n] += y1[k] * s1;
      }
      const double next0 = c0 * n0.cos1 - s0 * n0.sin1;
      s0 = s0 * n0.cos1 + c0 * n0.sin1;
      c0 = next0;
      const double next1 = c1 * n1.cos1 - s1 * n1.sin1;
      s1 = s1 * n1.cos1 + c1 * n1.sin1;
      c1 = next1;
    }
  }
  for (; i < nodes.size(); ++i) {
    const Node& nd = nodes[i];
    std::array<double, K> y;
    for (std::size_t k = 0; k < K; ++k) {
      y[k] = nd.weight * (nd.*m[k]);
      mean[k] += y[k];
    }
    double c = nd.cos1, s = nd.sin1;
    for (std::size_t n = 1; n < n_size; ++n) {
      for (std::size_t k = 0; k < K; ++k) {
        a[k * n_size + n] += y[k] * c;
        b[k * n_size + n] += y[k] * s;
      }
      const double next = c * nd.cos1 - s * nd.sin1;
      s = s * nd.cos1 + c * nd.sin1;
      c = next;
    }
  }
  std::array<Spectrum, K> h;
  for (std::size_t k = 0; k < K; ++k) {
    h[k].resize(n_size);
    const double mk = mean[k] / P;
    h[k][0] = {std::abs(mk), mk >= 0.0 ? kPi / 2.0 : -kPi / 2.0};
    for (std::size_t n = 1; n < n_size; ++n) {
      const double an = a[k * n_size + n] * 2.0 / P, bn = b[k * n_size + n] * 2.0 / P;
      // Phase at tau = 0, then in absolute time: n nu t = n nu tau + n nu t0 (reduced in cycles).
      double cyc = static_cast<double>(n) * f * t0;
      cyc -= std::round(cyc);
      h[k][n] = {std::hypot(an, bn), wrap_pi(std::atan2(an, bn) - 2.0 * kPi * cyc)};
    }
  }
  return h;
}

Spectrum spectrum(const std::vector<Node>& nodes, double Node::*m, double P, double t0, double f,
                  int n_max) {
  return spectra<1>(nodes, {m}, P, t0, f, n_max)[0];
}

// The subharmonics A(f/2), A(3f/2), A(5f/2) of z_M'' over the steady period P = p / f: a
// p-periodic motion has frequencies k f / p only, so none for an odd p; for an even p the
// quadrature sums of z_M'' against cos and sin of (2j + 1) nu tau / 2.
detail::HalfHarmonics half_harmonics(const std::vector<Node>& nodes, double P, double f, int p) {
  detail::HalfHarmonics h;
  if (p % 2 != 0) return h;
  const double half_nu = kPi * f;
  std::array<double, 3> a{}, b{};
  for (const Node& nd : nodes) {
    const double y = nd.weight * nd.ddz;
    double c = std::cos(half_nu * nd.tau), s = std::sin(half_nu * nd.tau);
    for (std::size_t j = 0; j < 3; ++j) {  // (2j + 1) nu tau / 2: add nu tau each time
      a[j] += y * c;
      b[j] += y * s;
      const double next = c * nd.cos1 - s * nd.sin1;
      s = s * nd.cos1 + c * nd.sin1;
      c = next;
    }
  }
  h.a05 = std::hypot(a[0], b[0]) * 2.0 / P;
  h.a15 = std::hypot(a[1], b[1]) * 2.0 / P;
  h.a25 = std::hypot(a[2], b[2]) * 2.0 / P;
  return h;
}

// One steady period integrated again from the first sample, recorded piece by piece.
template <class R>
Recording record_period(const Model& model, const Samples& s, double t0, double t1) {
  using Dyn = detail::Dynamics<R>;
  const FlowOptions options = FlowOptions::from(model);
  const Dyn dynamics(model, options.baumgarte);
  BasicFlow<R> flow(model, options);
  flow.reset(t0, R::State::from_array(Dyn::sampled_state(s, 0)),
             dynamics.flow_phase(s.phase.front()));
  Recorder<R> rec(model, options.baumgarte, t0, t1);
  if (flow.advance(t1, &rec) != FlowStop::reached)
    throw Error("compute_metrics: the steady period did not integrate again: " + flow.message());
  return std::move(rec.out);
}

// Whether `rec` is the period of `s` from t0 to t1 as record_period would record it: the same
// span, from the same state and phase at a restart of the flow (so the same pieces, bit for bit).
template <class R>
bool is_the_period(const Recording& rec, const Model& model, const Samples& s, double t0,
                   double t1) {
  using Dyn = detail::Dynamics<R>;
  const auto x = Dyn::sampled_state(s, 0);
  const Dyn dynamics(model, FlowOptions::from(model).baumgarte);
  return rec.t_begin == t0 && rec.t_end == t1 && !rec.pieces.empty() &&
         rec.start.size() == x.size() &&
         std::memcmp(rec.start.data(), x.data(), x.size() * sizeof(double)) == 0 &&
         rec.phase == dynamics.flow_phase(s.phase.front());
}

// The span of the steady period compute_metrics reads: from the first sample over p / f, p the
// multiplicity.
std::pair<double, double> period_span(const Result& result) {
  const int p = result.diagnostics.multiplicity >= 1 ? result.diagnostics.multiplicity : 1;
  const double t0 = result.samples.t.front();
  return {t0, t0 + p / result.frequency};
}

// Whether `recorded` (may be null) is the steady period of `result` (is_the_period).
bool reads_recorded(const Model& model, const Result& result, const Recording* recorded) {
  // (Not a structured binding: the lambdas below could not capture one before C++20, and
  // Emscripten's clang 14 still cannot.)
  const std::pair<double, double> span = period_span(result);
  return recorded != nullptr && detail::with_roller(model, [&]<class R>() {
           return is_the_period<R>(*recorded, model, result.samples, span.first, span.second);
         });
}

}  // namespace

Recording detail::steady_period(const Model& model, const Result& result,
                                const Recording* recorded) {
  if (reads_recorded(model, result, recorded)) return *recorded;
  const std::pair<double, double> span = period_span(result);
  return detail::with_roller(model, [&]<class R>() {
    return record_period<R>(model, result.samples, span.first, span.second);
  });
}

Metrics compute_metrics(const Model& model, const Result& result, int n_max) {
  // The model must be the one the result was simulated with: the metrics integrate its period
  // again from the first sample, and another case's (a notebook's loop variable re-bound) gave
  // another area without a word (43.78 for 22.78 at 30 Hz instead of 39 Hz).
  const Samples& s = result.samples;
  if (s.size() > 0 && ok(result.status)) {
    const double f = model.parameters().roller.f;
    if (!(std::abs(result.frequency - f) <= 1e-12 * f))
      throw Error(detail::format(
          "compute_metrics: the result was simulated at f = %.10g Hz, the case has roller.f = "
          "%.10g Hz: give the Case the result was simulated with",
          result.frequency, f));
    // Its accelerations at the first sample, from the sampled state.
    detail::with_roller(model, [&]<class R>() {
      const detail::Dynamics<R> dyn(model, FlowOptions::from(model).baumgarte);
      Samples again;
      dyn.sample(s.t[0], detail::Dynamics<R>::sampled_state(s, 0), s.phase[0], again);
      const double scale = std::max({1.0, std::abs(s.ddx_M[0]), std::abs(s.ddz_M[0])});
      const double off =
          std::max(std::abs(again.ddx_M[0] - s.ddx_M[0]), std::abs(again.ddz_M[0] - s.ddz_M[0]));
      if (!(off <= 1e-9 * scale))
        throw Error(detail::format(
            "compute_metrics: the case does not give the result's accelerations at its first "
            "sample (x_M'' %.6g m/s^2 there, %.6g from the case): give the Case the result was "
            "simulated with",
            s.ddx_M[0], again.ddx_M[0]));
    });
  }
  return detail::compute_metrics(model, result, n_max, nullptr);
}

Metrics detail::compute_metrics(const Model& model, const Result& result, int n_max,
                                const recording::Recording* recorded) {
  const Samples& s = result.samples;
  if (s.size() == 0) throw Error("compute_metrics: the result holds no samples");
  if (!ok(result.status))
    throw Error(std::string("compute_metrics: the result has status ") + to_string(result.status) +
                ", not a steady state: no metrics");
  if (n_max < 0) throw Error("compute_metrics: n_max must be >= 0; got " + std::to_string(n_max));
  // The harmonics are integrals over the trajectory, but the spectrum a user compares them with is
  // that of the samples: the same bound as for the sampled metrics (and the cost, n_max times
  // the quadrature nodes, stays bounded).
  const int spp = model.parameters().numerics.samples_per_period;
  if (n_max >= spp / 2)
    throw Error("compute_metrics: n_max must be < numerics.samples_per_period / 2 = " +
                std::to_string(spp / 2) + " (the samples' Nyquist limit); got " +
                std::to_string(n_max));
  const int p = result.diagnostics.multiplicity >= 1 ? result.diagnostics.multiplicity : 1;
  const double f = result.frequency, P = p / f;
  const double t0 = s.t.front();
  // The sampling's own recording of the period when it has one; else the period integrated again.
  const bool reuse = reads_recorded(model, result, recorded);
  Recording again;
  if (!reuse) again = steady_period(model, result, nullptr);
  const Recording& rec = reuse ? *recorded : again;
  const std::vector<Piece>& pieces = rec.pieces;

  Metrics m;
  // Peaks: first the values at every node, then the interior extrema of only those pieces whose
  // extremum could beat the values already found by more than the interpolant's round-off (most
  // cannot: ChebyshevInterpolant::overshoot_bound, roundoff_bound; a flat piece at the peak, T/N
  // = -+mu in slip or the zero gap in contact, is not searched). The peaks are those of every
  // piece searched, to that round-off (about 1e-14 relative).
  constexpr std::array<Quantity, 5> kPeakQuantities = {kDdx, kDdz, kDelta, kTraction, kGap};
  std::array<Extremes, kPeakQuantities.size()> peaks;
  for (const Piece& pc : pieces)
    for (std::size_t q = 0; q < kPeakQuantities.size(); ++q)
      for (double v : pc.values[kPeakQuantities[q]]) peaks[q].add(v);
  for (const Piece& pc : pieces) {
    for (std::size_t q = 0; q < kPeakQuantities.size(); ++q) {
      const auto& values = pc.values[kPeakQuantities[q]];
      const Interpolant& fq = pc.f[kPeakQuantities[q]];
      const double bound = fq.overshoot_bound(), resolved = 2.0 * fq.roundoff_bound();
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      const bool want_max = *hi + bound - peaks[q].hi > resolved,
                 want_min = peaks[q].lo - (*lo - bound) > resolved;
      if (want_max || want_min)
        add_extremes(pc.f[kPeakQuantities[q]], values, want_max, want_min, peaks[q]);
    }
  }
  std::vector<Node> nodes;
  nodes.reserve(pieces.size() * kGaussPoints);
  std::array<double, 4> time{};  // slip-, stick, slip+, flight [s]
  GaussRule rule;
  const double nu = 2.0 * kPi * f;
  for (const Piece& pc : pieces) {
    // Quadrature nodes (Gauss-Legendre on each piece). cos and sin of nu tau from those at the
    // piece's middle and of the offsets by angle addition (error a few ulp), the offsets' small
    // angles by their series.
    const double half = 0.5 * (pc.b - pc.a), mid = 0.5 * (pc.a + pc.b);
    const double c_mid = std::cos(nu * (mid - t0)), s_mid = std::sin(nu * (mid - t0));
    const auto& x = rule.abscissa();
    const auto& w = rule.weights();
    // The quantities at the nodes mid -+ half x_i from their Chebyshev coefficients, the even and
    // odd parts of sum_j c_j T_j(x_i) apart (T_j(-x) = (-1)^j T_j(x)): both nodes of a pair from
    // one table row (gauss_chebyshev) instead of a Clenshaw sum at each.
    constexpr std::array<Quantity, 6> kNodeQuantities = {kDdx,           kDdz,           kPhi,
                                                         kFrictionPower, kVerticalForce, kZ};
    for (std::size_t i = 0; i < x.size(); ++i) {
      const auto [s_off, c_off] = detail::sincos_small(nu * half * x[i]);
      const auto& T = gauss_chebyshev()[i];
      std::array<double, kNodeQuantities.size()> even{}, odd{};
      for (std::size_t q = 0; q < kNodeQuantities.size(); ++q) {
        const auto& c = pc.f[kNodeQuantities[q]].coefficients();
        for (int j = 0; j <= kDegree; j += 2) even[q] += c[j] * T[j];
        for (int j = 1; j <= kDegree; j += 2) odd[q] += c[j] * T[j];
      }
      for (double sign : {-1.0, 1.0}) {
        if (x[i] == 0.0 && sign > 0) continue;
        const double t = mid + sign * half * x[i];
        nodes.push_back({t - t0, half * w[i], even[0] + sign * odd[0], even[1] + sign * odd[1],
                         even[2] + sign * odd[2], std::abs(even[3] + sign * odd[3]),
                         even[4] + sign * odd[4], even[5] + sign * odd[5],
                         c_mid * c_off - sign * s_mid * s_off,
                         s_mid * c_off + sign * c_mid * s_off});
      }
    }
    // slip- 0, stick 1, slip+ 2, flight 3; a smooth law's one phase and slip without friction:
    // their apparent phases' times come from the sampling (below).
    if (!apparent_varies(model.friction(), pc.phase))
      time[static_cast<std::size_t>(static_cast<int>(pc.phase) + 1)] += pc.b - pc.a;
  }
  if (model.friction_phases() == FrictionPhases::smooth || frictionless(model.friction()))
    time = {result.slip_negative_time, result.stick_time, result.slip_positive_time,
            result.flight_time};
  const Extremes &ddx = peaks[0], &ddz = peaks[1], &delta = peaks[2], &traction = peaks[3],
                 &gap = peaks[4];
  m.ddx_max = ddx.hi, m.ddx_min = ddx.lo;
  m.ddz_max = ddz.hi, m.ddz_min = ddz.lo;
  m.delta_max = delta.hi, m.delta_min = delta.lo;
  m.mu_required = std::max(traction.hi, -traction.lo);

  const int n_compute = std::max(n_max, 3);
  auto [hx, hz] = spectra<2>(nodes, {&Node::ddx, &Node::ddz}, P, t0, f, n_compute);
  {
    // The fundamental at a node: A1 sin(nu (t0 + tau) + phase1) = A1 sin(nu tau + theta), theta
    // with nu t0 reduced in cycles, by angle addition from the node's cos and sin of nu tau.
    double cyc = f * t0;
    cyc -= std::round(cyc);
    const double theta = 2.0 * kPi * cyc + hx[1].phase;
    const double a1_cos = hx[1].amplitude * std::cos(theta),
                 a1_sin = hx[1].amplitude * std::sin(theta);
    const double mean = hx[0].amplitude * std::sin(hx[0].phase);
    double sum = 0.0;
    for (const Node& nd : nodes) {
      const double r = nd.ddx - mean - (nd.sin1 * a1_cos + nd.cos1 * a1_sin);
      sum += nd.weight * r * r;
    }
    detail::set_spectral_metrics(m, std::move(hx), std::move(hz), 2.0 * sum / P, n_max,
                                 half_harmonics(nodes, P, f, p));
  }

  // phi: drift removed, the fundamental against M0 sin(nu t).
  const double rate = (pieces.back().f[kPhi](pieces.back().b) - pieces.front().f[kPhi](t0)) / P;
  for (Node& nd : nodes) nd.phi -= rate * nd.tau;  // in place: nothing below reads phi
  const Spectrum hphi = spectrum(nodes, &Node::phi, P, t0, f, 1);
  // M0 sin(nu t) + MMd has M0 = 0 (the vibratory drum) when it is the same at the four quarters
  // of a period (M0 sin(nu t) takes one value at all four only for M0 = 0). Read from the model,
  // not from the samples' torque column as compute_metrics(result) does: a study's result may
  // hold only its section state, one sample, whose column is constant for every roller.
  // Whether a load of the model's takes another value at one of the quarters of a period.
  const auto oscillates = [&](auto load) {
    for (int q = 1; q < 4; ++q)
      if (load(t0 + 0.25 * q * model.period()) != load(t0)) return true;
    return false;
  };
  const bool torque_oscillates = oscillates([&](double t) { return model.torque(t); });
  detail::set_rotation_metrics(m, hphi[1], torque_oscillates);

  double work = 0.0;
  for (const Node& nd : nodes) work += nd.weight * nd.friction_power;
  m.friction_work = work / p;
  detail::set_phase_fractions(m, time[1], time[2], time[0], time[3]);
  detail::no_required_mu_with_flight(m);
  m.liftoffs_per_period = static_cast<double>(rec.lift_offs) / p;
  m.gap_max = std::max(gap.hi, 0.0);
  m.landing_velocity = rec.landing_speed;
  // The Kb-type stiffness: the fundamentals of F_v and z_M integrated over the period. Only where
  // a vertical force excites the drum (the vibratory drum's unbalance): without one, the drum's
  // vertical balance (20) at f gives F_v(f) = (m nu^2 - kd - i nu cd) z_M(f), so that
  // Re(F_v / z_M) is m nu^2 - kd whatever the soil (the oscillation drum: 107.1 MN/m for the
  // paper's roller at 39 Hz on every soil), a number of the machine, not of the soil. Read from
  // the model at four quarters of a period, as the torque above.
  if (oscillates([&](double t) { return model.centre_load(t).z; })) {
    const auto [h_force, h_z] = spectra<2>(nodes, {&Node::vertical_force, &Node::z}, P, t0, f, 2);
    m.kb = detail::soil_stiffness(h_force[1], h_z);
  } else {
    m.kb = std::numeric_limits<double>::quiet_NaN();
  }

  // The Evib-type modulus: the loop F_v(z_M) through kEvibPoints + 1 points of each piece, both
  // ends included (a landing's two one-sided values of F_v at the same z_M).
  m.evib = std::numeric_limits<double>::quiet_NaN();
  const Case& c = model.parameters();
  const double nu_soil = detail::evib_poisson_ratio(c);
  if (c.roller.type == RollerType::vibratory && !std::isnan(nu_soil)) {
    constexpr int kEvibPoints = 32;
    std::vector<double> z, Fv, ts;
    std::vector<std::size_t> piece_of;
    z.reserve(pieces.size() * (kEvibPoints + 1));
    Fv.reserve(z.capacity());
    ts.reserve(z.capacity());
    piece_of.reserve(z.capacity());
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const Piece& pc = pieces[i];
      for (int k = 0; k <= kEvibPoints; ++k) {
        const double t = k == kEvibPoints ? pc.b : pc.a + (pc.b - pc.a) * k / kEvibPoints;
        z.push_back(pc.f[kZ](t));
        Fv.push_back(pc.f[kVerticalForce](t));
        ts.push_back(t);
        piece_of.push_back(i);
      }
    }
    // The loop's end points are extrema: the least and the greatest z_M (the loading branch's
    // ends; the least z_M its start in continuous contact, where F_v still changes) and the
    // greatest F_v (where z_M still changes). Read at the nearest of the points above, each came
    // with an error of the first order in their spacing: evib moved by 2e-4 from one tolerance
    // to the next and did not converge. Each is located on its piece's interpolant (a
    // golden-section search between the neighbouring points of the same piece; an extremum at a
    // piece's end, a switch, stays there), and its point moved onto it.
    const std::size_t n = z.size();
    // The extremum of sign * column on [ts[k], ts[k + 1]] of piece `i` (golden-section search):
    // its time and its value of sign * column.
    const auto extremum = [&](std::size_t i, std::size_t column, double sign, double a, double b) {
      const Interpolant& g = pieces[i].f[column];
      constexpr double kGolden = 0.6180339887498949;
      double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a);
      double g1 = sign * g(x1), g2 = sign * g(x2);
      for (int k = 0; k < 100 && b - a > 1e-14 * (std::abs(a) + std::abs(b)); ++k) {
        if (g1 > g2) {  // the larger of sign * g lies in [a, x2]
          b = x2, x2 = x1, g2 = g1;
          x1 = b - kGolden * (b - a), g1 = sign * g(x1);
        } else {
          a = x1, x1 = x2, g1 = g2;
          x2 = a + kGolden * (b - a), g2 = sign * g(x2);
        }
      }
      const double t = 0.5 * (a + b);
      return std::pair{t, sign * g(t)};
    };
    // Sample j is an extremum of the points: the extremum of the curve in the intervals around it
    // (within pieces: one at a switch stays there), and the point of that piece nearest to it in
    // time moved onto it (so the points keep their order).
    const auto refine = [&](std::size_t j, std::size_t column, double sign) {
      double best_t = ts[j], best_v = sign * pieces[piece_of[j]].f[column](ts[j]);
      std::size_t best_piece = piece_of[j];
      for (std::size_t k = j >= 2 ? j - 2 : 0; k + 1 < n && k <= j + 1; ++k) {
        if (piece_of[k] != piece_of[k + 1] || !(ts[k + 1] > ts[k])) continue;
        const auto [t, v] = extremum(piece_of[k], column, sign, ts[k], ts[k + 1]);
        if (v > best_v) best_t = t, best_v = v, best_piece = piece_of[k];
      }
      std::size_t moved = n;
      for (std::size_t k = j >= 2 ? j - 2 : 0; k < n && k <= j + 2; ++k)
        if (piece_of[k] == best_piece &&
            (moved == n || std::abs(ts[k] - best_t) < std::abs(ts[moved] - best_t)))
          moved = k;
      if (moved == n) return;
      ts[moved] = best_t;
      z[moved] = pieces[best_piece].f[kZ](best_t);
      Fv[moved] = pieces[best_piece].f[kVerticalForce](best_t);
    };
    if (n >= 3) {
      refine(static_cast<std::size_t>(std::min_element(z.begin(), z.end()) - z.begin()), kZ, -1.0);
      refine(static_cast<std::size_t>(std::max_element(z.begin(), z.end()) - z.begin()), kZ, 1.0);
      // Every local maximum of F_v (the loading branch's greatest is one of them).
      for (std::size_t j = 1; j + 1 < n; ++j)
        if (Fv[j] > 0.0 && Fv[j] >= Fv[j - 1] && Fv[j] >= Fv[j + 1] &&
            (Fv[j] > Fv[j - 1] || Fv[j] > Fv[j + 1]))
          refine(j, kVerticalForce, 1.0);
    }
    m.evib = vibration_modulus(z, Fv, c.roller.r, c.roller.b, nu_soil);
  }

  // The interpolants hold the curve to about numerics.rtol: the last-resort extrapolation need not
  // resolve its area much finer (1e-11 at the default rtol 1e-8; 1e-9 for an identification's
  // model at 1e-6, where a curve at G = 150 MN/m^2 that Green's theorem and the sweep both
  // refused took (seen) 0.3 s at 1e-11 and 0.04-0.09 s at 1e-9, the same area to 10 digits).
  m.area = detail::curve_area(pieces, std::max(1e-11, 1e-3 * model.parameters().numerics.rtol));
  return m;
}

}  // namespace oscidrum
