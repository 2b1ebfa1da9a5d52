// The motion that does not settle (oscidrum/motion.hpp): stroboscopic points, the largest
// Lyapunov exponent and recurrence, over further excitation periods.
//
// The largest Lyapunov exponent is estimated as Benettin et al. (1980) do: a tangent vector v is
// carried along the trajectory by the variational equations (the monodromy of each period, with
// the saltation matrices of every switch: src/flow/monodromy.hpp), renormalised after every
// period, and lambda = sum ln |Phi_k v_k| / (K T). Only the periodic components count (phi is
// cyclic: a perturbation of it neither grows nor decays), in units of their ranges over the
// window, and at a section in stick the perturbation is projected as shooting projects it (in
// stick phi' is f5 delta' (12): its free offset would be a spurious neutral direction).
// On a periodic orbit lambda -> ln |mu_max| / T (tested).
#include "oscidrum/motion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "drivers/motion_verdict.hpp"
#include "drivers/sampling.hpp"
#include "flow/monodromy.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/flow.hpp"
#include "roller/rollers.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

// |Lambda| = |lambda T| up to this per period counts as zero. A positive or negative verdict
// needs the exponent beyond it and of one sign within the spread of the window's two halves.
// (On periodic orbits the estimate after the burn-in is within 3e-3 per period of ln |mu_max|
// from 200 periods on: tests/drivers/test_motion.cpp.)
constexpr double kZeroPerPeriod = 0.02;
// Estimates of a zero exponent over 400 periods scatter up to about this per period (the tori of
// docs/bifurcations.md: halves from -0.005 to 0.011): an exponent whose two halves are both below
// its negative is not zero.
constexpr double kZeroScatter = 0.01;
// Stroboscopic points that agree to this fraction of the components' ranges recur.
constexpr double kRecurrence = 1e-6;
constexpr int kMaxRecurrence = 64;
// The points of an orbit of period p > 1 are p distinct points: their spread (RMS distance from
// their centre, scaled) is at least this. Points that all lie closer together are one point
// approached slowly: a spiral into a period-1 orbit (a complex pair of modulus 0.99775 turning
// once in 37 periods) recurred to kRecurrence every 37 periods at an amplitude of about 1e-5, and
// was called periodic with period 37, where the transient reaches the period-1 orbit after 7188
// periods. (An orbit of period 2 just past its doubling has its points about 1e-4 apart when the
// parameter is 1e-8 of itself past the bifurcation.)
constexpr double kDistinctPoints = 1e2 * kRecurrence;
// Samples per period of the periods sampled for the scales when the result says none.
constexpr int kScaleSamples = 64;

template <class R>
MotionAnalysis analyze(const Model& model, const Result& result, int periods,
                       const std::function<bool()>& cancelled) {
  using Dyn = detail::Dynamics<R>;
  using Vector = typename Dyn::Vector;
  constexpr int P = static_cast<int>(Dyn::kPeriodic.size());
  MotionAnalysis out;
  FlowOptions fo = FlowOptions::from(model);
  fo.cancelled = cancelled;
  BasicFlow<R> flow(model, fo);
  const Dyn dyn(model, fo.baumgarte);
  const double T = model.period();
  const double t0 = result.samples.t.front();
  Phase phase = dyn.flow_phase(result.samples.phase.front());
  Vector x = dyn.consistent(Dyn::sampled_state(result.samples, 0), phase);
  flow.reset(t0, R::State::from_array(x), phase);
  detail::MonodromyObserver<R> mono(model, fo.baumgarte, T / detail::kMonodromyStepsPerPeriod);
  out.section.push_back(std::vector<double>(x.begin(), x.end()));
  out.section_phase.push_back(phase);
  std::vector<Eigen::MatrixXd> maps;  // Phi of each period on the periodic components
  // The samples whose ranges scale the components: the result's sampled periods (their number
  // and density), sampled again on the way from the same section state, whether the result holds
  // them or only that state (a study keeps no more unless asked). Without them the scales
  // collapse to 1e-9 of the values, and the recurrence, the convergence and the exponent's
  // alignment would judge noise; taken from the result's own samples when it held them, the
  // verdict of a case depended on whether its samples were kept (sweep --hdf5, keep_samples):
  // quasi-periodic without, converging with.
  Result sampled;
  sampled.frequency = result.frequency;
  const int scale_periods = std::clamp(result.sample_periods, 1, periods);
  const int scale_density =
      result.samples_per_period > 0 ? result.samples_per_period : kScaleSamples;
  detail::sampling::Sampler<R> sampler(flow, t0, scale_periods, scale_density, true, sampled);
  detail::ObserverPair<R> both(mono, sampler);
  const Samples* ranges = &sampled.samples;
  for (int k = 1; k <= periods; ++k) {
    mono.reset();
    const FlowStop stop =
        k <= scale_periods ? flow.advance(t0 + k * T, &both) : flow.advance(t0 + k * T, &mono);
    if (stop != FlowStop::reached) {
      out.kind = "undecided";
      out.periods = k - 1;
      out.evidence =
          "the flow stopped after " + std::to_string(k - 1) + " further periods: " + flow.message();
      return out;
    }
    const auto G = dyn.section_jacobian(x, phase);
    const typename Dyn::Matrix phi = G ? typename Dyn::Matrix(mono.phi() * *G) : mono.phi();
    Eigen::MatrixXd M(P, P);
    for (int i = 0; i < P; ++i)
      for (int j = 0; j < P; ++j) M(i, j) = phi(Dyn::kPeriodic[i], Dyn::kPeriodic[j]);
    maps.push_back(M);
    x = flow.state().to_array();
    phase = flow.phase();
    out.section.push_back(std::vector<double>(x.begin(), x.end()));
    out.section_phase.push_back(phase);
  }
  out.periods = periods;
  // Scales: each periodic component's range over the sampled periods (`ranges`: the motion's
  // own size; its size if it does not move), or over the stroboscopic points where those span
  // more: the sampled periods (2 by default) are a part of an orbit of many periods. A period-11
  // orbit (pure rolling on the unilateral contact at 58 Hz, G 60 MN/m^2) repeated to 6.5e-7 of its
  // points' ranges, above kRecurrence of the two sampled periods' ranges: it was called
  // converging, with max_periods_reached and no word of its period.
  Eigen::VectorXd scale(P);
  for (int i = 0; i < P; ++i) {
    const auto c = static_cast<std::size_t>(Dyn::kPeriodic[i]);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, size = 0.0;
    for (std::size_t j = 0; j < ranges->size(); ++j) {
      const double v = Dyn::sampled_state(*ranges, j)[Dyn::kPeriodic[i]];
      lo = std::min(lo, v), hi = std::max(hi, v), size = std::max(size, std::abs(v));
    }
    double points_lo = std::numeric_limits<double>::infinity(), points_hi = -points_lo;
    for (const std::vector<double>& point : out.section)
      points_lo = std::min(points_lo, point[c]), points_hi = std::max(points_hi, point[c]);
    scale[i] = std::max({hi - lo, points_hi - points_lo, 1e-9 * size, 1e-15});
  }
  // Recurrence: the smallest p with every point of the second half within kRecurrence of the
  // point p periods earlier.
  const auto distance = [&](std::size_t a, std::size_t b) {
    double d = 0.0;
    for (int i = 0; i < P; ++i) {
      const auto c = static_cast<std::size_t>(Dyn::kPeriodic[i]);
      d = std::max(d, std::abs(out.section[a][c] - out.section[b][c]) / scale[i]);
    }
    return d;
  };
  const std::size_t n = out.section.size();
  // The points' spread: the RMS distance from their centre, in scaled components.
  const auto spread_of = [&](std::size_t from, std::size_t to) {
    Eigen::VectorXd centre = Eigen::VectorXd::Zero(P);
    for (std::size_t k = from; k < to; ++k)
      for (int i = 0; i < P; ++i)
        centre[i] += out.section[k][static_cast<std::size_t>(Dyn::kPeriodic[i])] / scale[i];
    centre /= static_cast<double>(to - from);
    double squares = 0.0;
    for (std::size_t k = from; k < to; ++k)
      for (int i = 0; i < P; ++i) {
        const double d =
            out.section[k][static_cast<std::size_t>(Dyn::kPeriodic[i])] / scale[i] - centre[i];
        squares += d * d;
      }
    return std::sqrt(squares / static_cast<double>(to - from));
  };
  for (int p = 1; p <= std::min(kMaxRecurrence, periods / 4) && out.recurrence == 0; ++p) {
    bool recurs = true;
    for (std::size_t k = n / 2; k < n && recurs; ++k) recurs = distance(k, k - p) < kRecurrence;
    if (recurs) out.recurrence = p;
  }
  if (out.recurrence > 1 && spread_of(n / 2, n) < kDistinctPoints) out.recurrence = 0;
  // Benettin's estimate, in scaled components. The first tenth of the window only aligns v with
  // the most expanding direction (its start, any vector, would otherwise bias the mean by
  // ln(its projection) / K); the exponent is the mean growth over the rest, and over its halves.
  const Eigen::MatrixXd S = scale.asDiagonal(), S_inv = scale.cwiseInverse().asDiagonal();
  Eigen::VectorXd v = Eigen::VectorXd::Ones(P).normalized();
  const int burn_in = periods / 10, used = periods - burn_in, half = burn_in + used / 2;
  double sum = 0.0, first = 0.0;
  for (int k = 0; k < periods; ++k) {
    v = S_inv * maps[static_cast<std::size_t>(k)] * S * v;
    const double growth = v.norm();
    if (!(growth > 0.0) || !std::isfinite(growth)) break;
    if (k >= burn_in) sum += std::log(growth);
    v /= growth;
    if (k + 1 == half) first = sum;
  }
  out.lyapunov = sum / (used * T);
  out.lyapunov_first = first / ((half - burn_in) * T);
  out.lyapunov_second = (sum - first) / ((periods - half) * T);
  const double per_period = out.lyapunov * T, a = out.lyapunov_first * T,
               b = out.lyapunov_second * T, spread = std::abs(a - b);
  // Estimates, to the digits they carry (the halves differ in the second or third; as
  // docs/bifurcations.md quotes them).
  const std::string numbers =
      detail::format("largest Lyapunov exponent %.4g 1/s (%.4g per period; halves %.4g, %.4g)",
                     out.lyapunov, per_period, a, b) +
      " over " + std::to_string(periods) + " periods";
  // Convergence to an orbit of period p: the distance between points p periods apart shrinks
  // geometrically, ln d_p(k) falls along a straight line (a torus or chaos makes it wander).
  // Over the second half, the least-squares line of ln d_p(k) against k for p = 1 ... 16: a
  // negative slope with R^2 >= 0.9 is convergence, to the smallest p that falls at least half
  // as steeply as the steepest: the multiples of the orbit's period all fall at its rate, and
  // the steepest of them is the noise's choice (a period-2 approach was read as period 16).
  // `contraction` is d_p's shrink factor over that half for the p found (1 if none).
  struct Fall {
    int p;
    double slope, m;  // ln d_p per period, over m points
  };
  std::vector<Fall> falling;
  double steepest = 0.0;
  for (int p = 1; p <= std::min(16, periods / 4); ++p) {
    double sk = 0, sy = 0, skk = 0, sky = 0, syy = 0, m = 0;
    for (std::size_t k = n / 2; k < n; ++k) {
      const double d = distance(k, k - static_cast<std::size_t>(p));
      if (!(d > 0.0)) continue;
      const double y = std::log(d), kk = static_cast<double>(k);
      sk += kk, sy += y, skk += kk * kk, sky += kk * y, syy += y * y, m += 1;
    }
    if (m < 10) continue;
    const double sxx = skk - sk * sk / m, sxy = sky - sk * sy / m, s_yy = syy - sy * sy / m;
    const double slope = sxy / sxx, r2 = s_yy > 0 ? sxy * sxy / (sxx * s_yy) : 0.0;
    if (slope < 0.0 && r2 >= 0.9) {  // a period-2 orbit's d_1 flattens: not among them
      falling.push_back({p, slope, m});
      steepest = std::min(steepest, slope);
    }
  }
  for (const Fall& f : falling)
    if (f.slope <= 0.5 * steepest) {
      out.converging_period = f.p;
      out.contraction = std::exp(f.slope * f.m);
      break;
    }
  // The points' spread (the RMS distance from their centre, in scaled components) in each quarter
  // of the window: on a torus (or a chaotic attractor) it stays, approaching an orbit it shrinks
  // as |mu|^k. An approach along a complex pair of multipliers of modulus 0.9988 (pure rolling
  // on the unilateral contact at 58 Hz, G 86 MN/m^2) does not fall on a line (the distances
  // oscillate with the rotation), and its exponent, -0.003 per period, is "zero": it was called a
  // torus, with status aperiodic, where the transient reaches the periodic orbit after 11 000
  // periods. A spread that shrinks from quarter to quarter, by more than a tenth from the first
  // half to the second, is that approach.
  const std::array<double, 4> quarter = {spread_of(0, n / 4), spread_of(n / 4, n / 2),
                                         spread_of(n / 2, 3 * n / 4), spread_of(3 * n / 4, n)};
  const double spread_ratio = spread_of(n / 2, n) / spread_of(0, n / 2);
  const bool shrinking = spread_ratio < 0.9 && quarter[1] < quarter[0] && quarter[2] < quarter[1] &&
                         quarter[3] < quarter[2];
  // The other way: points on p branches, each moving only a little from one visit to the next
  // (their distance p periods apart, over the second half, below kDriftStep of the spread),
  // whose spread grows from quarter to quarter, by more than a tenth, are leaving an unstable
  // orbit of period p: the vibratory drum with lift-off at 21.5 Hz, just below a flip of its
  // period-1 orbit, drifting over 400 periods towards the stable period-2 orbit (two points
  // drifting apart, exponent 1e-4 per period), was called a torus. A torus's points, which also
  // spread out while a transient spirals onto it (past a Neimark-Sacker point), turn by its
  // rotation angle each period: p periods apart they are far from each other.
  constexpr double kDriftStep = 0.05;
  const bool growing = spread_ratio > 1.0 / 0.9 && quarter[1] > quarter[0] &&
                       quarter[2] > quarter[1] && quarter[3] > quarter[2];
  int drifting = 0;  // p of the branches (0: none)
  for (int p = 1; growing && drifting == 0 && p <= std::min(16, periods / 4); ++p) {
    double sum_d = 0.0;
    for (std::size_t k = n / 2; k < n; ++k) sum_d += distance(k, k - static_cast<std::size_t>(p));
    if (sum_d / static_cast<double>(n - n / 2) < kDriftStep * spread_of(n / 2, n)) drifting = p;
  }
  if (out.recurrence > 0) {
    out.kind = "periodic";
    out.evidence = "the stroboscopic points repeat every " + std::to_string(out.recurrence) +
                   " periods (to " + detail::shortest(kRecurrence) + " of their ranges); " +
                   numbers;
  } else if (out.converging_period > 0) {
    out.kind = "converging";
    out.evidence =
        "the distance between stroboscopic points " + std::to_string(out.converging_period) +
        " periods apart shrinks geometrically (by " + detail::format("%.4g", out.contraction) +
        " over the last " + std::to_string(n / 2) +
        " periods): the motion still approaches an attractor; " + numbers;
  } else if (per_period > kZeroPerPeriod && per_period - spread > 0.0) {
    out.kind = "chaotic";
    out.evidence = "a positive " + numbers + ", and the stroboscopic points do not recur";
  } else if (std::max(a, b) < -kZeroScatter) {
    // Negative in both halves beyond the scatter of a zero exponent's estimates: an attractor
    // approached slowly and not along one line (two multipliers of about the same modulus, or
    // a complex pair), not a torus (a period-2 orbit with multiplier 0.97 per two periods gave
    // -0.014 per period, halves -0.013 and -0.014: it was called a torus).
    out.kind = "converging";
    out.evidence = "a negative " + numbers + ", in both halves below -" +
                   detail::shortest(kZeroScatter) +
                   " per period (beyond the scatter of a zero exponent's estimates): the motion "
                   "still approaches an attractor";
  } else if (shrinking) {
    out.kind = "converging";
    out.evidence = "the stroboscopic points' spread shrinks in every quarter of the window (by " +
                   detail::format("%.3g", spread_ratio) +
                   " from its first half to its second): the motion still approaches an "
                   "attractor (a multiplier near the unit circle), not a torus; " +
                   numbers;
  } else if (drifting > 0 && std::abs(per_period) <= kZeroPerPeriod) {
    out.kind = "undecided";
    out.evidence = "the stroboscopic points lie on " + std::to_string(drifting) + " branch" +
                   (drifting == 1 ? "" : "es") +
                   " that drift apart: their spread grows in every quarter of the window (by " +
                   detail::format("%.3g", spread_ratio) +
                   " from its first half to its second), each point close to the one " +
                   std::to_string(drifting) + " period" + (drifting == 1 ? "" : "s") +
                   " before: the motion is still leaving an unstable orbit, not on a torus; a "
                   "longer transient decides; " +
                   numbers;
  } else if (std::abs(per_period) <= kZeroPerPeriod) {
    out.kind = "quasi_periodic";
    out.evidence = "a zero " + numbers + " (|per period| <= " + detail::shortest(kZeroPerPeriod) +
                   "), and the stroboscopic points do not recur: a torus";
  } else if (per_period < -kZeroPerPeriod && per_period + spread < 0.0) {
    out.kind = "converging";
    out.evidence = "a negative " + numbers + ": the motion still approaches an attractor";
  } else {
    out.kind = "undecided";
    out.evidence = detail::unsettled_evidence(numbers, a, b);
  }
  return out;
}

}  // namespace

MotionAnalysis analyze_motion(const Model& model, const Result& result, int periods,
                              const std::function<bool()>& cancelled) {
  if (result.samples.size() == 0) throw Error("analyze_motion: the result holds no samples");
  if (periods < 20)
    throw Error("analyze_motion: periods must be >= 20; got " + std::to_string(periods));
  return detail::with_roller(
      model, [&]<class R>() { return analyze<R>(model, result, periods, cancelled); });
}

}  // namespace oscidrum
