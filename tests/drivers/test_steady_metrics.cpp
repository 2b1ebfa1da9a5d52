// test_steady_metrics.cpp: metrics from the dense output (compute_metrics(model, result)) do not
// depend on the output sampling and agree with a brute-force evaluation of the same trajectory.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "drivers/continuation.hpp"
#include "drivers/period_recording.hpp"
#include "metrics/piece_interpolant.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

Case default_with(int samples_per_period, double MMd_fraction = 0.0) {
  Case c;
  c.numerics.samples_per_period = samples_per_period;
  c.numerics.output_periods = 1;
  c.MMd = MMd_fraction * c.roller.M0;
  return c;
}

// |a - b| <= rtol * scale for every scalar metric and every harmonic amplitude (scale: the
// metric's magnitude, for a harmonic the largest amplitude of its signal).
void expect_same_metrics(const Metrics& a, const Metrics& b, double rtol) {
  for (const MetricOutput& o : metric_outputs()) {
    SCOPED_TRACE(o.name);
    if (is_scalar(o)) {
      const double va = scalar_value(a, o), vb = scalar_value(b, o);
      if (std::isnan(va) || std::isnan(vb)) {
        EXPECT_EQ(std::isnan(va), std::isnan(vb));
        continue;
      }
      // Scale: the value, floored for dimensionless numbers and angles at 1 (a ratio that is
      // zero by symmetry is noise on the scale of 1), for accelerations at the largest peak.
      const std::string unit = o.unit;
      double floor = 0.0;
      if (unit == "-" || unit == "rad" || unit == "pi rad") floor = 1.0;
      if (unit == "m/s^2")
        floor = std::max(
            {std::abs(a.ddx_max), std::abs(a.ddx_min), std::abs(a.ddz_max), std::abs(a.ddz_min)});
      EXPECT_LE(std::abs(va - vb), rtol * std::max(std::abs(va), floor)) << va << " vs " << vb;
      continue;
    }
    const Spectrum& ha = a.*std::get<Spectrum Metrics::*>(o.member);
    const Spectrum& hb = b.*std::get<Spectrum Metrics::*>(o.member);
    ASSERT_EQ(ha.size(), hb.size());
    double scale = 0.0;
    for (const Harmonic& h : ha) scale = std::max(scale, h.amplitude);
    for (std::size_t n = 0; n < ha.size(); ++n)
      EXPECT_LE(std::abs(ha[n].amplitude - hb[n].amplitude), rtol * scale) << "n = " << n;
  }
}

// The same metrics whether the steady state is sampled with 64 or 65536 points per period: the
// dense-output metrics read the trajectory, not the samples.
TEST(SteadyMetrics, IndependentOfTheOutputSampling) {
  for (double MMd : {0.0, 0.05}) {
    SCOPED_TRACE("MMd_fraction = " + std::to_string(MMd));
    const Model coarse_model(default_with(64, MMd)), fine_model(default_with(65536, MMd));
    const Result coarse = simulate(coarse_model), fine = simulate(fine_model);
    ASSERT_EQ(coarse.status, Status::steady_state) << coarse.message;
    ASSERT_EQ(fine.status, Status::steady_state) << fine.message;
    expect_same_metrics(compute_metrics(coarse_model, coarse), compute_metrics(fine_model, fine),
                        1e-9);
  }
}

// The metrics integrate the period again from the first sample with the model given: another
// case's model (a notebook's loop variable re-bound) gave another area without a word (43.78 for
// 22.78 with f = 30 Hz for a result at 39 Hz; 370 with G = 70 MN/m^2). Both are refused.
TEST(SteadyMetrics, AModelTheResultWasNotSimulatedWithIsRefused) {
  const Case c;
  const Result r = simulate(c);
  ASSERT_EQ(r.status, Status::steady_state);
  EXPECT_NO_THROW(compute_metrics(Model(c), r));
  Case other_f = c;
  other_f.roller.f = 30.0;
  Case other_G = c;
  other_G.soil = table2_soil(70e6);
  for (const Case& other : {other_f, other_G}) {
    try {
      compute_metrics(Model(other), r);
      ADD_FAILURE() << "another case's model accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("give the Case the result was simulated with"),
                std::string::npos)
          << e.what();
    }
  }
}

// The RMV- and CCV-type values read z_M'''s subharmonics A(f/2), A(3f/2), A(5f/2): none in a
// period-1 state (RMV exactly 0, CCV from A_1, A_2, A_3 alone); in the stable period-2 orbit
// after a period doubling the dense-output integrals and a DFT of fine samples agree.
TEST(SteadyMetrics, SubharmonicIndicatorsOfAPeriodTwoOrbit) {
  {
    const Model model(default_with(256, 0.05));
    const Result r = simulate(model);
    ASSERT_EQ(r.diagnostics.multiplicity, 1);
    const Metrics m = compute_metrics(model, r);
    EXPECT_EQ(m.rmv, 0.0);
    const Spectrum& h = m.ddz_harmonics;
    EXPECT_NEAR(m.ccv, 100.0 * (h[2].amplitude + h[3].amplitude) / h[1].amplitude, 1e-12 * m.ccv);
  }
  Case c;
  c.soil.input = SoilInput::modulus;
  c.soil.G = 150e6;
  c.roller.unbalance = 0.22877;
  c.roller.f = 25.0;
  c.trough.shape = trough_shape(0.002, 0.601);
  c.contact.mu = 0.7;
  c.numerics.method = SteadyMethod::shooting;
  c.numerics.samples_per_period = 8192;
  const Model model(c);
  const Result r = simulate(model);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  ASSERT_EQ(r.diagnostics.multiplicity, 2);
  const Metrics dense = compute_metrics(model, r), sampled = compute_metrics(r);
  EXPECT_GT(dense.rmv, 0.1);  // a period-2 motion: a sizeable f/2 component
  EXPECT_NEAR(sampled.rmv / dense.rmv, 1.0, 1e-6);
  EXPECT_NEAR(sampled.ccv / dense.ccv, 1.0, 1e-6);
  EXPECT_GT(dense.ccv,
            100.0 * dense.ddz_A2_A1 * dense.ddz_harmonics[1].amplitude /
                (dense.ddz_harmonics[1].amplitude + dense.rmv * dense.ddz_harmonics[1].amplitude));
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_bits(const Spectrum& a, const Spectrum& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t n = 0; n < a.size(); ++n)
    if (!same_bits(a[n].amplitude, b[n].amplitude) || !same_bits(a[n].phase, b[n].phase))
      return false;
  return true;
}

void expect_same_bits(const Metrics& a, const Metrics& b) {
#define OSCIDRUM_SAME(type, name, unit, label, description) \
  EXPECT_TRUE(same_bits(a.name, b.name)) << #name;
  OSCIDRUM_METRICS(OSCIDRUM_SAME)
#undef OSCIDRUM_SAME
}

// A shooting orbit's sampling records its first period for the metrics on the way (a study's
// cases then integrate it only once): the metrics from that recording are those of the period
// integrated again, bit for bit; a recording of another trajectory is not used.
TEST(SteadyMetrics, TheSamplingsRecordingGivesTheSameBits) {
  Case stick_slip;  // Appendix B soil, MMd 0.05 M0
  stick_slip.soil.input = SoilInput::modulus;
  stick_slip.soil.G = 25e6;
  stick_slip.MMd = 0.05 * stick_slip.roller.M0;
  Case pure = stick_slip;
  pure.contact.pure_rolling = true;
  pure.MMd = 0.0;
  for (const Case& c : {stick_slip, pure}) {
    SCOPED_TRACE(c.contact.pure_rolling ? "pure rolling" : "stick-slip");
    const Model model(c);
    detail::recording::Recording period;
    const Result r = detail::simulate_from(model, {}, {}, nullptr, true, &period);
    ASSERT_EQ(r.status, Status::steady_state) << r.message;
    ASSERT_EQ(r.diagnostics.method, SteadyMethod::shooting);
    ASSERT_FALSE(period.pieces.empty());
    EXPECT_EQ(period.t_begin, r.samples.t.front());
    expect_same_bits(detail::compute_metrics(model, r, 10, &period), compute_metrics(model, r));
    // The recording is what the metrics read: a landing speed put into it comes out.
    detail::recording::Recording marked = period;
    marked.landing_speed = 123.0;
    EXPECT_EQ(detail::compute_metrics(model, r, 10, &marked).landing_velocity, 123.0);
    // Recorded from another start (the state a little off), it is not used.
    marked.start[0] += 1e-9;
    expect_same_bits(detail::compute_metrics(model, r, 10, &marked), compute_metrics(model, r));
  }
  // The transient method samples where its search stopped, without a restart: no recording.
  Case transient = stick_slip;
  transient.numerics.method = SteadyMethod::transient;
  const Model model(transient);
  detail::recording::Recording period;
  const Result r = detail::simulate_from(model, {}, {}, nullptr, true, &period);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  EXPECT_TRUE(period.pieces.empty());
}

// Brute force: the re-integrated steady period sampled at 2^18 points; DFT harmonics and the
// polygon area of those samples against the dense-output metrics; the sampled peaks can only
// fall short of the exact ones, by at most the sampling's reach.
class Brute : public FlowObserver {
 public:
  Brute(const Model& model, double t0, int n) : model_(model), t0_(t0), n_(n) {}
  bool on_step(const StepView& step) override {
    while (next_ < n_) {
      const double t = t0_ + static_cast<double>(next_) * model_.period() / n_;
      if (t > step.t1()) break;
      const State q = step.state(t);
      const Accelerations a =
          accelerations(model_, t, q, step.phase(), FlowOptions::from(model_).baumgarte);
      const DrumMotion d = drum_motion(model_, q, a);
      r.samples.t.push_back(t);
      r.samples.ddx_M.push_back(d.ddx_M);
      r.samples.ddz_M.push_back(d.ddz_M);
      r.samples.delta.push_back(q.delta);
      r.samples.phi.push_back(q.phi);
      r.samples.dphi.push_back(q.dphi);
      r.samples.phase.push_back(step.phase());
      ++next_;
    }
    return true;
  }
  Result r;

 private:
  const Model& model_;
  const double t0_;
  const int n_;
  int next_ = 0;
};

// Put `flow` at the first sample of a steady state (to integrate its first period again).
void start_at_first_sample(Flow& flow, const Samples& s) {
  flow.reset(
      s.t[0],
      {s.delta[0], s.x_A[0], s.s_A[0], s.phi[0], s.ddelta[0], s.dx_A[0], s.ds_A[0], s.dphi[0]},
      s.phase[0]);
}

// n uniform samples of the first steady period of `res`, integrated again from its first sample.
Result brute_force_period(const Model& model, const Result& res, int n) {
  const Samples& s = res.samples;
  Flow flow(model);
  start_at_first_sample(flow, s);
  Brute brute(model, s.t[0], n);
  EXPECT_EQ(flow.advance(s.t[0] + model.period(), &brute), FlowStop::reached);
  return brute.r;
}

TEST(SteadyMetrics, AgreeWithABruteForceEvaluation) {
  const Model model(default_with(64, 0.05));
  const Result res = simulate(model);
  ASSERT_EQ(res.status, Status::steady_state) << res.message;
  ASSERT_EQ(res.diagnostics.multiplicity, 1);
  const Metrics exact = compute_metrics(model, res);
  const int n = 1 << 18;
  Result b = brute_force_period(model, res, n);
  ASSERT_EQ(b.samples.size(), static_cast<std::size_t>(n));
  b.frequency = res.frequency;
  b.sample_periods = 1;
  b.samples_per_period = n;
  b.diagnostics.multiplicity = 1;
  b.stick_time = 1.0;  // fractions are not compared here
  const Metrics sampled = compute_metrics(b);
  for (int k = 0; k <= 10; ++k) {
    EXPECT_NEAR(exact.ddx_harmonics[k].amplitude, sampled.ddx_harmonics[k].amplitude,
                1e-9 * exact.ddx_harmonics[1].amplitude)
        << k;
    EXPECT_NEAR(exact.ddz_harmonics[k].amplitude, sampled.ddz_harmonics[k].amplitude,
                1e-9 * exact.ddz_harmonics[1].amplitude)
        << k;
  }
  EXPECT_NEAR(exact.psi_xz, sampled.psi_xz, 1e-9);
  EXPECT_NEAR(exact.phi_lag, sampled.phi_lag, 1e-9);
  EXPECT_NEAR(exact.ddx_thd, sampled.ddx_thd, 1e-9 * exact.ddx_thd);
  EXPECT_NEAR(exact.area, sampled.area, 1e-9 * exact.area);
  // Peaks: every sample lies below the exact maximum; the samples come within their spacing.
  for (auto [e, smp] : {std::pair{exact.ddx_max, sampled.ddx_max},
                        {exact.ddz_max, sampled.ddz_max},
                        {-exact.ddx_min, -sampled.ddx_min},
                        {-exact.ddz_min, -sampled.ddz_min}}) {
    EXPECT_GE(e, smp - 1e-12 * std::abs(e));
    EXPECT_LE(e - smp, 1e-4 * std::abs(e));
  }
}

// A peak just inside the end of an integrator step (between the last scan point of the step and
// its end) is found as well: the brute-force samples of the same trajectory never exceed the
// exact peaks. Pure-rolling cases where the peak finder, bracketing only at interior scan points,
// took the step's end value instead and fell short by up to 1.2e-6 of x_M'' max and 6.5e-7 of
// delta min (enough to make the two steady-state methods, whose step sequences differ, disagree
// by 2e-6; docs/periodic.md).
TEST(SteadyMetrics, PeaksNearTheEndsOfStepsAreFound) {
  for (const auto& [G, R] : {std::pair{35e6, 0.606}, {25e6, 0.606}, {50e6, 0.603}}) {
    SCOPED_TRACE("G = " + std::to_string(G) + ", R = " + std::to_string(R));
    Case c = default_with(64);
    c.soil = table2_soil(G);
    c.trough.shape = CircleTrough{R};
    c.contact.pure_rolling = true;
    const Model model(c);
    const Result res = simulate(model);
    ASSERT_EQ(res.status, Status::steady_state) << res.message;
    const Metrics exact = compute_metrics(model, res);
    const int n = 1 << 16;
    const Result brute = brute_force_period(model, res, n);
    const Samples& b = brute.samples;
    ASSERT_EQ(b.size(), static_cast<std::size_t>(n));
    const auto [x_lo, x_hi] = std::minmax_element(b.ddx_M.begin(), b.ddx_M.end());
    const auto [z_lo, z_hi] = std::minmax_element(b.ddz_M.begin(), b.ddz_M.end());
    const auto [d_lo, d_hi] = std::minmax_element(b.delta.begin(), b.delta.end());
    // Samples T / 65536 apart come within ~(2 pi / 65536)^2 / 2 = 5e-9 of a peak of a signal
    // dominated by its fundamental (within 1e-7 here, with the overtones); they must never
    // exceed it beyond round-off.
    for (auto [e, smp] : {std::pair{exact.ddx_max, *x_hi},
                          {exact.ddz_max, *z_hi},
                          {exact.delta_max, *d_hi},
                          {-exact.ddx_min, -*x_lo},
                          {-exact.ddz_min, -*z_lo},
                          {-exact.delta_min, -*d_lo}}) {
      EXPECT_GE(e, smp - 1e-12 * std::abs(e)) << (smp - e) / std::abs(e);
      EXPECT_LE(e - smp, 1e-7 * std::abs(e));
    }
  }
}

// The metrics read every quantity off a degree-10 Chebyshev interpolant per piece of the
// trajectory (src/metrics/piece_interpolant.hpp). On every step of a steady period, stick-slip and
// pure rolling, the interpolant of x_M'', z_M'' and T/N agrees with the direct evaluation at 40
// points per step to round-off (1e-12 of the largest value; measured 4e-14 ... 1.4e-13, as for
// degrees 8 and 16; degree 4, for contrast, is off by 3e-10 ... 4e-9).
template <int N>
class InterpolantCheck : public FlowObserver {
 public:
  explicit InterpolantCheck(const Model& model) : model_(model) {}
  bool on_step(const StepView& step) override {
    using I = detail::ChebyshevInterpolant<N>;
    const double a = step.t0(), b = step.t1();
    const auto direct = [&](double t) {
      const State q = step.state(t);
      const Accelerations acc = accelerations(model_, t, q, step.phase(), baumgarte_);
      const DrumMotion d = drum_motion(model_, q, acc);
      const ContactForces f = contact_forces(model_, q);
      return std::array<double, 3>{d.ddx_M, d.ddz_M, f.T / f.N};
    };
    std::array<std::array<double, I::kNodes>, 3> v;
    for (int k = 0; k < I::kNodes; ++k) {
      const auto y = direct(I::node(a, b, k));
      for (int m = 0; m < 3; ++m) v[m][k] = y[m];
    }
    for (int m = 0; m < 3; ++m) {
      const I f(a, b, v[m]);
      for (int j = 0; j <= 40; ++j) {
        const double t = a + (b - a) * j / 40.0;
        const double y = direct(t)[m];
        error[m] = std::max(error[m], std::abs(f(t) - y));
        scale[m] = std::max(scale[m], std::abs(y));
      }
      // The peaks skip the pieces whose overshoot_bound cannot reach the peak: the interpolant
      // must never leave [min, max] of its node values by more than the bound.
      const auto [lo, hi] = std::minmax_element(v[m].begin(), v[m].end());
      double above = 0.0, below = 0.0;
      for (int j = 0; j <= 400; ++j) {
        const double y = f(a + (b - a) * j / 400.0);
        above = std::max(above, y - *hi);
        below = std::max(below, *lo - y);
      }
      const double bound = f.overshoot_bound();
      worst_overshoot = std::max({worst_overshoot, above / bound, below / bound});
      if (above > 1e-9 * std::abs(*hi) || below > 1e-9 * std::abs(*lo)) ++overshooting_pieces;
    }
    return true;
  }
  std::array<double, 3> error{}, scale{};
  double worst_overshoot = 0.0;  // largest overshoot / bound
  int overshooting_pieces = 0;   // pieces with an extremum beyond their nodes' values

 private:
  const Model& model_;
  const double baumgarte_ = FlowOptions::from(model_).baumgarte;
};

template <int N>
std::array<double, 3> interpolant_error(const Model& model, const Result& res) {
  const Samples& s = res.samples;
  Flow flow(model);
  start_at_first_sample(flow, s);
  InterpolantCheck<N> check(model);
  EXPECT_EQ(flow.advance(s.t[0] + model.period(), &check), FlowStop::reached);
  std::array<double, 3> relative{};
  for (int m = 0; m < 3; ++m) relative[m] = check.error[m] / check.scale[m];
  // The bound holds on every piece, and it is tested: some pieces do hold an extremum between
  // their nodes.
  EXPECT_LE(check.worst_overshoot, 1.0);
  EXPECT_GT(check.overshooting_pieces, 0);
  return relative;
}

// extremum() on polynomials that the degree-10 interpolant represents exactly: a maximum and a
// minimum by Newton's method (the value exact to round-off), a bracket with two maxima and a
// minimum between them (Newton with bisection ends at one of the maxima, never at the minimum),
// and a bracket that starts beyond a maximum (Brent's method).
// A flat piece (T/N = -+mu through a slip, the zero gap in contact): its interpolant stays within
// its round-off bound of the value, so the peaks do not search it (steady_metrics.cpp skips a
// piece that cannot beat the peak by more than twice roundoff_bound); a piece with a true turn
// beyond its nodes is still searched.
TEST(SteadyMetrics, AFlatPieceCannotBeatItsValuesBeyondRoundOff) {
  using I = detail::ChebyshevInterpolant<10>;
  for (const double level : {0.0, 0.5, -0.5, 12.3}) {
    SCOPED_TRACE(level);
    std::array<double, I::kNodes> v;
    v.fill(level);
    const I flat(2.0, 2.001, v);
    // The curvature of the coefficients' round-off noise stays below the round-off bound: the
    // piece's possible gain is within 2 roundoff_bound, so it is not searched.
    EXPECT_LE(flat.overshoot_bound(), 2.0 * flat.roundoff_bound());
    EXPECT_LE(flat.roundoff_bound(), 1e-13 * std::max(1.0, std::abs(level)));
    // What a search would find: the interpolant between the nodes.
    double worst = 0.0;
    for (int i = 0; i <= 1000; ++i)
      worst = std::max(worst, std::abs(flat(2.0 + 0.001 * i / 1000) - level));
    EXPECT_LE(worst, 2.0 * flat.roundoff_bound());
  }
  // A turn between the nodes: its possible gain is far above the round-off.
  std::array<double, I::kNodes> v;
  for (int k = 0; k < I::kNodes; ++k) {
    const double t = I::node(0.0, 1.0, k);
    v[k] = std::sin(10.0 * t);
  }
  const I turning(0.0, 1.0, v);
  EXPECT_GT(turning.overshoot_bound(), 1e6 * turning.roundoff_bound());
}

// The interpolant's coefficients (the folded transform) against the discrete cosine transform
// summed plainly in long double, c_j = (2/N) w_j sum_k w_k cos(pi j k / N) f_k, for even and odd
// N on values with no symmetry: equal to a few ulp of the values' size; and the interpolant
// returns its values at the nodes.
template <int N>
void expect_plain_transform() {
  using I = detail::ChebyshevInterpolant<N>;
  std::array<double, I::kNodes> v;
  for (int k = 0; k < I::kNodes; ++k) v[k] = std::exp(0.3 * k) * std::cos(1.7 * k + 0.4) + 0.1 * k;
  const I f(2.0, 2.5, v);
  double size = 0.0;
  for (double y : v) size = std::max(size, std::abs(y));
  for (int j = 0; j <= N; ++j) {
    long double sum = 0.0L;
    for (int k = 0; k <= N; ++k) {
      const long double w = (k == 0 || k == N) ? 0.5L : 1.0L;
      sum += w * std::cos(3.14159265358979323846264338327950288L * j * k / N) * v[k];
    }
    const long double c = 2.0L / N * ((j == 0 || j == N) ? 0.5L : 1.0L) * sum;
    EXPECT_NEAR(f.coefficients()[j], static_cast<double>(c), 8.0 * N * 2.2e-16 * size)
        << "N = " << N << ", j = " << j;
  }
  for (int k = 0; k < I::kNodes; ++k)
    EXPECT_NEAR(f(I::node(2.0, 2.5, k)), v[k], 16.0 * N * 2.2e-16 * size) << "N = " << N;
}

TEST(SteadyMetrics, InterpolantCoefficientsAreTheCosineTransform) {
  expect_plain_transform<7>();
  expect_plain_transform<8>();
  expect_plain_transform<10>();
}

TEST(SteadyMetrics, ExtremumOfAnInterpolant) {
  using I = detail::ChebyshevInterpolant<10>;
  const auto interpolant = [](auto f, double a, double b) {
    std::array<double, I::kNodes> v;
    for (int k = 0; k < I::kNodes; ++k) v[k] = f(I::node(a, b, k));
    return I(a, b, v);
  };
  const auto extremum = [](const I& f, double lo, double hi, double sign) {
    const I df = f.derivative_interpolant(), d2f = df.derivative_interpolant();
    return detail::extremum(f, df, d2f, lo, hi - lo, sign);
  };
  // A maximum 0 at t = 0.37 (the cubic term moves no root inside [0, 1]), on [10, 11] s too: the
  // bracket in absolute time, as after a long transient.
  for (double t0 : {0.0, 10.0}) {
    const I peak = interpolant(
        [t0](double t) {
          const double d = t - t0 - 0.37;
          return 2.0 - d * d + 0.1 * d * d * d;
        },
        t0, t0 + 1.0);
    EXPECT_NEAR(extremum(peak, t0 + 0.2, t0 + 0.5, 1.0), 2.0, 1e-14);
    const I trough = interpolant(
        [t0](double t) {
          const double d = t - t0 - 0.61;
          return -3.0 + d * d - 0.05 * d * d * d;
        },
        t0, t0 + 1.0);
    EXPECT_NEAR(extremum(trough, t0 + 0.5, t0 + 0.8, -1.0), -3.0, 1e-14);
  }
  // -(t - 0.2)^2 (t - 0.8)^2: maxima 0 at 0.2 and 0.8, a minimum -0.0081 at 0.5.
  const I twin = interpolant(
      [](double t) { return -(t - 0.2) * (t - 0.2) * (t - 0.8) * (t - 0.8); }, 0.0, 1.0);
  EXPECT_NEAR(extremum(twin, 0.0, 1.0, 1.0), 0.0, 1e-15);
  EXPECT_NEAR(extremum(twin, 0.3, 1.0, 1.0), 0.0, 1e-15);  // f' < 0 at 0.3: Brent
  EXPECT_NEAR(extremum(twin, 0.3, 0.7, -1.0), -0.0081, 1e-15);
}

// overshoot_bound on known functions: sin(omega t + 0.3) on [0, 1], one to several turns between
// the nodes. The interpolant's largest excursion beyond its node values stays within the bound,
// and the bound is not vacuous (within a factor 1000 of the excursion where there is one; 205
// for omega = 11, where the Markov bound weighs the high coefficients heavily).
TEST(SteadyMetrics, OvershootBoundHoldsBetweenTheNodes) {
  using I = detail::ChebyshevInterpolant<10>;
  int tested = 0;
  for (double omega : {1.0, 2.5, 3.3, 5.7, 8.0, 11.0}) {
    SCOPED_TRACE("omega = " + std::to_string(omega));
    std::array<double, I::kNodes> v;
    for (int k = 0; k < I::kNodes; ++k) v[k] = std::sin(omega * I::node(0.0, 1.0, k) + 0.3);
    const I f(0.0, 1.0, v);
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    double excursion = 0.0;
    for (int j = 0; j <= 100000; ++j) {
      const double y = f(j / 100000.0);
      excursion = std::max({excursion, y - *hi, *lo - y});
    }
    const double bound = f.overshoot_bound();
    EXPECT_LE(excursion, bound);
    if (excursion > 1e-12) {
      ++tested;
      EXPECT_LE(bound, 1000.0 * excursion);
    }
  }
  EXPECT_GE(tested, 3);
}

TEST(SteadyMetrics, StepInterpolantsAgreeWithDirectEvaluation) {
  for (bool rolling : {false, true}) {
    SCOPED_TRACE(rolling ? "pure rolling" : "stick-slip");
    Case c = default_with(64, 0.05);
    c.contact.pure_rolling = rolling;
    const Model model(c);
    const Result res = simulate(model);
    ASSERT_EQ(res.status, Status::steady_state) << res.message;
    for (double e : interpolant_error<detail::recording::kDegree>(model, res)) EXPECT_LE(e, 1e-12);
    double coarse = 0.0;
    for (double e : interpolant_error<4>(model, res)) coarse = std::max(coarse, e);
    EXPECT_GT(coarse, 1e-10);
  }
}

// The default run's metrics are those of the trajectory to about the integration tolerance: an
// rtol 1e-12 run agrees to 1e-8 relative.
TEST(SteadyMetrics, DefaultRunAgreesWithATightRun) {
  Case tight = default_with(64);
  tight.numerics.rtol = 1e-12;
  tight.numerics.atol = 1e-15;
  const Model m_default(default_with(1024)), m_tight(tight);
  const Result r_default = simulate(m_default), r_tight = simulate(m_tight);
  ASSERT_EQ(r_default.status, Status::steady_state) << r_default.message;
  ASSERT_EQ(r_tight.status, Status::steady_state) << r_tight.message;
  expect_same_metrics(compute_metrics(m_default, r_default), compute_metrics(m_tight, r_tight),
                      1e-8);
}

// At 0.1 Hz a period has about 10 000 pieces and its curve rings around the origin after every
// switch; the exact area gives up on some crossings and the refined polygons of the fallback stop
// at a bounded size (cost). The result must still be the curve's area: uniform samples of the
// period (2^16, then 2^17 points) converge towards it, slowly (the accelerations jump at the
// switches), so it lies beyond the finer polygon's area, in the direction of the change from the
// coarser one, by no more than that change.
TEST(SteadyMetrics, LowFrequencyAreaAgreesWithRefinedSamples) {
  Case c = default_with(64);
  c.roller.f = 0.1;
  const Model model(c);
  const Result res = simulate(model);
  ASSERT_EQ(res.status, Status::steady_state) << res.message;
  ASSERT_EQ(res.diagnostics.multiplicity, 1);
  const Metrics exact = compute_metrics(model, res);
  double area[2] = {0.0, 0.0};
  for (int level = 0; level < 2; ++level) {
    const Result b = brute_force_period(model, res, 1 << (16 + level));
    area[level] = enclosed_area(b.samples.ddx_M, b.samples.ddz_M);
  }
  const double change = area[1] - area[0], beyond = exact.area - area[1];
  EXPECT_GT(beyond * change, 0.0) << exact.area << " " << area[0] << " " << area[1];
  EXPECT_LE(std::abs(beyond), std::abs(change)) << exact.area << " " << area[0] << " " << area[1];
}

}  // namespace
}  // namespace oscidrum
