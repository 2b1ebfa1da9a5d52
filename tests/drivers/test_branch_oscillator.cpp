// The continuation of periodic orbits (src/drivers/branch_continuation.hpp) run on a textbook
// hybrid oscillator, the harmonically forced soft-impact oscillator (soft_impact_oscillator.hpp),
// through its resonance in the forcing frequency f, and checked against what is known of it
// without the continuation (docs/bifurcations.md, "Checks"):
//  - its non-impacting orbits are the linear oscillator's steady state in closed form, with the
//    multipliers exp((-zeta wn +- i wd) T);
//  - they graze the support where the linear amplitude equals the gap (closed form);
//  - the impacting branch bends to higher f (the support hardens the oscillator) and folds twice,
//    the middle part between the folds unstable;
//  - a quasi-static up and down sweep of transient integrations (a fixed-step Runge-Kutta written
//    here, not the engine's flow) jumps at the two folds: the hysteresis loop;
//  - with a dashpot in the support (a force that jumps at the switch), the monodromy matrix with
//    its saltation matrices is the Jacobian of the period map.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "drivers/branch_continuation.hpp"
#include "drivers/soft_impact_oscillator.hpp"
#include "flow/hybrid_flow.hpp"
#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

using Osc = SoftImpactOscillator;

constexpr double kFrom = 30.0, kTo = 56.0;  // the range of f [Hz]

// The support's damping ratios the branch is checked with: none (the force is continuous at the
// switch) and 0.2 (it jumps: saltation matrices other than the identity).
constexpr double kSupportDamping[] = {0.0, 0.2};

// The constants of the checks: the defaults of SoftImpactConstants with the support's damping.
SoftImpactConstants constants(double support_zeta) {
  SoftImpactConstants p;
  p.support_zeta = support_zeta;
  return p;
}

// The branch in f from kFrom (below the resonance, where the orbit does not reach the support),
// started from the linear steady state there.
Branch oscillator_branch(double support_zeta) {
  soft_impact = constants(support_zeta);
  const SoftImpactConstants& p = soft_impact;
  Case c;
  set_field(c, "roller.f", kFrom);
  BranchOptions o;
  o.key = "roller.f";
  o.from = kFrom;
  o.to = kTo;
  o.metrics = false;
  o.switch_depth = 0;
  const Field* field = find_field(o.key);
  detail::branching::Continuation<Osc> continuation(c, o, *field);
  detail::branching::Continuation<Osc>::Start start;
  start.section = 0.0;
  start.reference = p.linear_state(kFrom, 0.0);
  start.phase = Phase::flight;
  const double a = p.linear_amplitude(kFrom);
  start.scale = {2.0 * a, 2.0 * a * 2.0 * std::numbers::pi * kFrom};
  return continuation.run_from(start);
}

// The branch for kSupportDamping[i] (computed once); its constants are set for the test.
const Branch& branch(int i) {
  static const Branch b[] = {oscillator_branch(kSupportDamping[0]),
                             oscillator_branch(kSupportDamping[1])};
  soft_impact = constants(kSupportDamping[i]);
  return b[i];
}

// The frequencies where the linear amplitude F0 / sqrt((k - m w^2)^2 + (c w)^2) equals the gap e:
// the roots u = w^2 of m^2 u^2 + (c^2 - 2 k m) u + k^2 - (F0 / e)^2 = 0 [Hz], lower first.
std::array<double, 2> grazing_frequencies(const SoftImpactConstants& p) {
  const double a = p.m * p.m, b = p.c() * p.c() - 2.0 * p.k() * p.m,
               c = p.k() * p.k() - std::pow(p.F0() / p.gap, 2);
  const double root = std::sqrt(b * b - 4.0 * a * c);
  const double u1 = (-b - root) / (2.0 * a), u2 = (-b + root) / (2.0 * a);
  return {std::sqrt(u1) / (2.0 * std::numbers::pi), std::sqrt(u2) / (2.0 * std::numbers::pi)};
}

std::vector<Bifurcation> of_kind(const Branch& b, BifurcationKind kind) {
  std::vector<Bifurcation> out;
  for (const Bifurcation& x : b.bifurcations)
    if (x.kind == kind) out.push_back(x);
  return out;
}

TEST(BranchOscillator, FollowsTheResonanceThroughBothFolds) {
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE("support damping ratio " + std::to_string(kSupportDamping[k]));
    const Branch& b = branch(k);
    ASSERT_EQ(b.end, BranchEnd::reached_end) << b.message;
    for (const Bifurcation& x : b.bifurcations)
      std::printf("%-16s f = %.9g Hz +- %.2g  %s\n", to_string(x.kind), x.parameter, x.tolerance,
                  x.description.c_str());
    std::printf("%zu points, %ld period maps, %.3f s\n", b.points.size(), b.period_maps, b.seconds);
    const auto grazings = of_kind(b, BifurcationKind::grazing);
    const auto folds = of_kind(b, BifurcationKind::fold);
    ASSERT_EQ(grazings.size(), 2u);
    ASSERT_EQ(folds.size(), 2u);
    // Along the branch: grazing (onto the support), the upper fold, the lower fold, grazing (off
    // it); no other bifurcation.
    EXPECT_EQ(b.bifurcations.size(), 4u);
    EXPECT_LT(grazings[0].parameter, folds[1].parameter);
    EXPECT_LT(folds[1].parameter, grazings[1].parameter);
    EXPECT_LT(grazings[1].parameter, folds[0].parameter);
  }
}

// Non-impacting orbits: the closed-form steady state and multipliers of the linear oscillator.
TEST(BranchOscillator, NonImpactingOrbitsAreTheLinearSteadyState) {
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE("support damping ratio " + std::to_string(kSupportDamping[k]));
    const Branch& b = branch(k);
    const SoftImpactConstants& p = soft_impact;
    int checked = 0;
    for (const BranchPoint& pt : b.points) {
      if (pt.sequence != "flight") continue;
      SCOPED_TRACE("f = " + std::to_string(pt.parameter));
      // The section may lie anywhere in the period (it moves away from the switches of the
      // impacting orbits): the state there is on the ellipse x^2 + (x' / w)^2 = |X|^2 of the
      // steady state x = |X| cos(w t + phase).
      const double a = p.linear_amplitude(pt.parameter), w = 2.0 * std::numbers::pi * pt.parameter;
      // The shooting residual is solved to 1e-2 steady_tol = 1e-10 of the scales (~2 gap): the
      // orbit to ~1e-9 of its amplitude.
      EXPECT_NEAR(std::hypot(pt.state[0], pt.state[1] / w), a, 1e-8 * a);
      // Multipliers exp((-zeta wn +- i wd) T), T = 1 / f: the modulus exp(-zeta wn T) for both.
      const double modulus = std::exp(-p.zeta * p.omega_n() / pt.parameter);
      ASSERT_EQ(pt.floquet.multipliers.size(), 2u);
      for (const std::complex<double> m : pt.floquet.multipliers)
        EXPECT_NEAR(std::abs(m), modulus, 1e-6);
      EXPECT_TRUE(pt.stable());
      ++checked;
    }
    EXPECT_GT(checked, 10);
  }
}

// The grazings lie where the linear amplitude equals the gap.
TEST(BranchOscillator, GrazingWhereTheLinearAmplitudeIsTheGap) {
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE("support damping ratio " + std::to_string(kSupportDamping[k]));
    const Branch& b = branch(k);
    const auto grazings = of_kind(b, BifurcationKind::grazing);
    ASSERT_EQ(grazings.size(), 2u);
    const auto exact = grazing_frequencies(soft_impact);
    std::printf("grazing: closed form %.9g, %.9g Hz; continuation %.9g, %.9g Hz\n", exact[0],
                exact[1], grazings[0].parameter, grazings[1].parameter);
    // The bisection brackets the change of the orbit's phases to 1e-6 of the range, but an orbit
    // whose penetration of the support lasts less than the spacing of the flow's event samples (two
    // per step; ~80 steps per period here at rtol = 1e-8, so T/160) is seen as not impacting: a
    // penetration of up to A (pi / 160)^2 / 2 ~ 2e-4 gap goes unseen (A ~ gap the amplitude), which
    // is 1.2e-3 and 1e-3 Hz in f (dA/df = 0.16 and -0.20 gap/Hz at the grazings). Measured: 3e-5
    // and 2.5e-4 Hz.
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(grazings[i].parameter, exact[i], 1.5e-3);
  }
}

// Between the folds the orbits are unstable (one real multiplier beyond +1), elsewhere stable.
TEST(BranchOscillator, StableOutsideTheFoldsUnstableBetween) {
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE("support damping ratio " + std::to_string(kSupportDamping[k]));
    const Branch& b = branch(k);
    const auto folds = of_kind(b, BifurcationKind::fold);
    ASSERT_EQ(folds.size(), 2u);
    for (std::size_t i = 0; i < b.points.size(); ++i) {
      const BranchPoint& pt = b.points[i];
      const bool between =
          static_cast<int>(i) > folds[0].after_point && static_cast<int>(i) <= folds[1].after_point;
      EXPECT_EQ(pt.unstable, between ? 1 : 0) << "point " << i << " f = " << pt.parameter;
    }
    for (const Bifurcation& f : folds) {
      std::printf("fold at %.9g Hz: multiplier %.6g%+.2gi\n", f.parameter, f.multiplier.real(),
                  f.multiplier.imag());
      // At the located point (within ~1e-5 Hz of the fold) the multiplier is 1 + O(sqrt(distance)):
      // measured 1.0022 and 0.9970.
      EXPECT_NEAR(std::abs(f.multiplier - 1.0), 0.0, 1e-2);
    }
  }
}

// A quasi-static sweep of f by transient integration, independent of the engine: classical
// Runge-Kutta with a fixed step of T / 400 on m x'' + c x' + k x + H(x - e) k_s (x - e) =
// F0 cos(2 pi f t) (the support's force is continuous in x, so the steps that cross x = e lose
// only the order of the method there, not its convergence). Each case starts from the previous
// case's state at a period boundary (the forcing's phase 0 in both) and runs until the state at
// the period boundaries changes by less than 1e-10 of the gap over a period (at most 20000
// periods); its value is the largest x over the last period [m].
std::vector<double> sweep(const std::vector<double>& fs, std::array<double, 2> z) {
  const SoftImpactConstants& p = soft_impact;
  auto accel = [&](double t, double x, double v, double w) {
    const double support = x > p.gap ? p.k_s() * (x - p.gap) : 0.0;
    return (p.F0() * std::cos(w * t) - p.c() * v - p.k() * x - support) / p.m;
  };
  std::vector<double> out;
  for (const double f : fs) {
    const double w = 2.0 * std::numbers::pi * f, T = 1.0 / f;
    constexpr int kSteps = 400;
    const double h = T / kSteps;
    double x_max = 0.0;
    for (int period = 0; period < 20000; ++period) {
      const std::array<double, 2> z0 = z;
      x_max = -1e300;
      for (int i = 0; i < kSteps; ++i) {
        const double t = i * h, x = z[0], v = z[1];
        const double k1x = v, k1v = accel(t, x, v, w);
        const double k2x = v + 0.5 * h * k1v, k2v = accel(t + 0.5 * h, x + 0.5 * h * k1x, k2x, w);
        const double k3x = v + 0.5 * h * k2v, k3v = accel(t + 0.5 * h, x + 0.5 * h * k2x, k3x, w);
        const double k4x = v + h * k3v, k4v = accel(t + h, x + h * k3x, k4x, w);
        z[0] += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        z[1] += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        x_max = std::max(x_max, z[0]);
      }
      if (std::abs(z[0] - z0[0]) < 1e-10 * p.gap && std::abs(z[1] - z0[1]) < 1e-10 * p.gap * w)
        break;
    }
    out.push_back(x_max);
  }
  return out;
}

// Where a sweep jumps: the largest change of its value between neighbouring cases; the two
// frequencies around it (in sweep order), its size and the largest change elsewhere [m].
struct Jump {
  double before = 0.0, after = 0.0, size = 0.0, elsewhere = 0.0;
};
Jump jump_of(const std::vector<double>& fs, const std::vector<double>& values) {
  Jump j;
  std::size_t at = 0;
  for (std::size_t i = 1; i < fs.size(); ++i) {
    const double d = std::abs(values[i] - values[i - 1]);
    if (d > j.size) j = {fs[i - 1], fs[i], d, 0.0}, at = i;
  }
  for (std::size_t i = 1; i < fs.size(); ++i)
    if (i != at) j.elsewhere = std::max(j.elsewhere, std::abs(values[i] - values[i - 1]));
  return j;
}

// The up sweep stays on the resonant (upper) branch until the upper fold and drops; the down
// sweep stays on the lower branch until the lower fold and jumps up: each jump lies between two
// neighbouring cases of the sweep that bracket the fold the continuation found. The sweep's step
// (0.05 Hz, ~1e-3 of f) is the tolerance; the folds are 3 Hz (60 steps) apart, so a sweep that did
// not follow the branches (no hysteresis, or a jump elsewhere) fails. Without the support's dashpot
// only: with it (damping ratio 0.2) the upper fold, 44.69999 Hz, lies 1e-5 Hz below a case of the
// sweep, closer than a fixed-step integration of a force that jumps at x = e resolves (the sweep
// stays on the branch there), and the cases near it take up to 20000 periods to settle (a
// minute for the pair of sweeps).
TEST(BranchOscillator, FoldsAreTheJumpsOfUpAndDownSweeps) {
  const Branch& b = branch(0);
  const auto folds = of_kind(b, BifurcationKind::fold);
  ASSERT_EQ(folds.size(), 2u);
  const double upper = folds[0].parameter, lower = folds[1].parameter;
  constexpr double kStep = 0.05;  // [Hz]
  std::vector<double> up;
  for (int i = 0; kFrom + i * kStep <= kTo + 1e-9; ++i) up.push_back(kFrom + i * kStep);
  const std::vector<double> down(up.rbegin(), up.rend());
  const std::vector<double> up_values = sweep(up, soft_impact.linear_state(kFrom, 0.0));
  const std::vector<double> down_values = sweep(down, soft_impact.linear_state(kTo, 0.0));
  const Jump ju = jump_of(up, up_values), jd = jump_of(down, down_values);
  std::printf(
      "folds (continuation): %.6g, %.6g Hz; up sweep jumps between %.6g and %.6g Hz "
      "(by %.3g; %.3g elsewhere), down sweep between %.6g and %.6g Hz (by %.3g; %.3g "
      "elsewhere)\n",
      lower, upper, ju.before, ju.after, ju.size, ju.elsewhere, jd.before, jd.after, jd.size,
      jd.elsewhere);
  // A jump: one change of the largest x that dwarfs every other between neighbouring cases (the
  // smooth ones are slope times step; measured: 1.22 and 0.63 gap against 0.016 and 0.011).
  EXPECT_GT(ju.size, 10.0 * ju.elsewhere);
  EXPECT_GT(jd.size, 10.0 * jd.elsewhere);
  EXPECT_LE(ju.before, upper);
  EXPECT_GE(ju.after, upper);
  EXPECT_GE(jd.before, lower);
  EXPECT_LE(jd.after, lower);
}

// The monodromy matrix of the engine (variational equations along the flow, saltation matrices
// at the switches: src/flow/monodromy.hpp) is the Jacobian of the period map, here with a dashpot
// in the support so that the force jumps at x = e and the saltation matrices are not the
// identity: against central differences of the period map (tight tolerances, so that the
// differences are accurate to ~1e-7). Without the saltation matrices the same comparison fails
// by far (checked too, so that the comparison can tell).
TEST(BranchOscillator, MonodromyIsTheJacobianOfThePeriodMapThroughImpacts) {
  soft_impact = SoftImpactConstants{};
  soft_impact.support_zeta = 0.2;
  const double f = 40.0, w = 2.0 * std::numbers::pi * f;  // at resonance: impacts every period
  Case c;
  set_field(c, "roller.f", f);
  const Model model(c);
  FlowOptions fo = FlowOptions::from(model);
  fo.rtol = 1e-12;
  fo.atol = 1e-14;
  const double T = model.period();
  // A state on the impacting orbit (after 30 periods from the linear steady state).
  std::array<double, 2> z0;
  {
    BasicFlow<Osc> flow(model, fo);
    flow.reset(0.0, Osc::State::from_array(soft_impact.linear_state(f, 0.0)), Phase::flight);
    ASSERT_EQ(flow.advance(30.0 * T), FlowStop::reached);
    ASSERT_EQ(flow.phase(), Phase::flight);
    z0 = flow.state().to_array();
  }
  auto period_map = [&](const std::array<double, 2>& z, BasicFlowObserver<Osc>* observer) {
    BasicFlow<Osc> flow(model, fo);
    flow.reset(0.0, Osc::State::from_array(z), Phase::flight);
    EXPECT_EQ(flow.advance(T, observer), FlowStop::reached);
    EXPECT_EQ(flow.phase(), Phase::flight);
    return flow.state().to_array();
  };
  detail::MonodromyObserver<Osc> mono(model, fo.baumgarte, T / 1024.0);
  mono.reset();
  period_map(z0, &mono);
  ASSERT_EQ(mono.switches().size(), 2u);  // onto the support and off it
  // Without the saltation matrices: the same variational equations, the switches ignored.
  struct WithoutSaltation : detail::MonodromyObserver<Osc> {
    using detail::MonodromyObserver<Osc>::MonodromyObserver;
    bool on_event(const Event&, const Osc::State&, const Osc::State&) override { return true; }
  } plain(model, fo.baumgarte, T / 1024.0);
  plain.reset();
  period_map(z0, &plain);
  // Central differences in units of the orbit's ranges (x in gaps, x' in gaps times w).
  const std::array<double, 2> unit = {soft_impact.gap, soft_impact.gap * w};
  Eigen::Matrix2d fd, engine, without;
  for (int j = 0; j < 2; ++j) {
    const double h = 1e-5 * unit[j];
    std::array<double, 2> zp = z0, zm = z0;
    zp[j] += h;
    zm[j] -= h;
    const auto ep = period_map(zp, nullptr), em = period_map(zm, nullptr);
    for (int i = 0; i < 2; ++i) {
      fd(i, j) = (ep[i] - em[i]) / (2.0 * h) * unit[j] / unit[i];
      engine(i, j) = mono.phi()(i, j) * unit[j] / unit[i];
      without(i, j) = plain.phi()(i, j) * unit[j] / unit[i];
    }
  }
  std::printf(
      "finite differences %.9f %.9f %.9f %.9f\nmonodromy          %.9f %.9f %.9f %.9f\n"
      "without saltation  %.9f %.9f %.9f %.9f\n",
      fd(0, 0), fd(0, 1), fd(1, 0), fd(1, 1), engine(0, 0), engine(0, 1), engine(1, 0),
      engine(1, 1), without(0, 0), without(0, 1), without(1, 0), without(1, 1));
  // Differences: truncation ~h^2 = 1e-10, integration 1e-12 / 1e-5 = 1e-7 (scaled); the
  // variational equations by the Magnus method of order 6 on steps of at most T/1024: ~(2 pi /
  // 1024)^6, below 1e-12.
  EXPECT_LT((engine - fd).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_GT((without - fd).cwiseAbs().maxCoeff(), 1e-2);
}

}  // namespace
}  // namespace oscidrum
