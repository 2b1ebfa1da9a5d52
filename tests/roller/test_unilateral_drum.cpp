// The drum with unilateral contact (src/roller/unilateral_drum.cpp, src/equations/flight_phase.hpp,
// docs/model.md section 13): the flight chart against the trough shapes' gap functions; contact
// phases that are the paper's drum; the flight Jacobian and the lift-off and landing maps against
// finite differences; the monodromy matrix of an orbit with flight against finite differences of
// its period map; and the energy balance of a steady period with flight.
#include <gtest/gtest.h>

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "drivers/shooting.hpp"
#include "flow/monodromy.hpp"
#include "oscidrum/oscidrum.hpp"
#include "roller/unilateral_checks.hpp"
#include "roller/unilateral_drum.hpp"
#include "tolerances.hpp"

namespace oscidrum::detail {
namespace {

using U = Dynamics<UnilateralDrum>;
using namespace flight_index;

// A drum that lifts off once per period and lands again (paper roller on Appendix B soil,
// G = 60 MN/m^2, f = 65 Hz with M0 following f^2, pure rolling): found by shooting.
Case flying_case() {
  Case c;
  c.soil.input = SoilInput::modulus;
  c.soil.G = 60e6;
  c.roller.f = 65.0;
  c.roller.unbalance = 0.22877;
  c.contact.pure_rolling = true;
  c.contact.unilateral = true;
  c.numerics.method = SteadyMethod::shooting;
  return c;
}

U::Vector random_flight_state(std::mt19937& rng, const Model& model) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double d0 = model.W() / (model.ksv() + model.kd());
  return {0.2 * u(rng), 1e-3 * u(rng),         d0 * (1.0 + 0.5 * u(rng)),
          u(rng),       2e-4 * (1.0 + u(rng)), 40.0 * u(rng),
          0.1 * u(rng), 0.05 * u(rng),         40.0 * u(rng),
          0.1 * u(rng)};
}

// A state in flight with the drum inside the trough (gap < 0) is no state of the flight phase:
// its landing (the gap falling through zero) could never be detected, and shooting closed such
// iterates into a spurious orbit in flight throughout (a vibratory drum's sweep, warm-started,
// reported flight fraction 1 and "permanent contact"). The flow refuses it at once.
TEST(UnilateralDrum, AFlightStateInsideTheTroughIsRefused) {
  const Model model(flying_case());
  BasicFlow<UnilateralDrum> flow(model);
  UnilateralState q = UnilateralState::from_array(U(model, 0.0).initial_state());
  q.gap = -1e-3;  // the drum 1 mm inside the trough
  flow.reset(0.0, q, Phase::flight);
  EXPECT_EQ(flow.advance(model.period()), FlowStop::inconsistent_state);
  EXPECT_NE(flow.message().find("flight"), std::string::npos) << flow.message();
  q.gap = 1e-5;  // 10 um above it: a flight that lands
  flow.reset(0.0, q, Phase::flight);
  EXPECT_EQ(flow.advance(model.period()), FlowStop::reached);
  EXPECT_GT(flow.counters().events, 0);
  // On the trough and closing (g = 0, g' < 0): it lands at once, at the start, where a gap that
  // only touched zero from above would never have fired its landing.
  struct First : BasicFlowObserver<UnilateralDrum> {
    double t = -1.0;
    EventKind kind = EventKind::lift_off;
    bool on_event(const Event& e, const UnilateralState&, const UnilateralState&) override {
      if (t < 0.0) t = e.t, kind = e.kind;
      return true;
    }
  } first;
  q.gap = 0.0;
  q.dgap = -0.01;
  flow.reset(0.0, q, Phase::flight);
  EXPECT_EQ(flow.advance(model.period(), &first), FlowStop::reached);
  EXPECT_EQ(first.kind, EventKind::landing);
  EXPECT_LT(first.t, 1e-6 * model.period());
}

// The chart M = A + roll(delta) - g n(delta) is the trough shape's gap: each shape finds delta
// and g back from the drum centre (circle in closed form, spiral by Newton's method).
TEST(UnilateralDrum, FlightChartIsTheShapesGap) {
  std::mt19937 rng(1);
  for (const TroughShape& shape : {trough_shape(0.0, 0.606), trough_shape(0.002, 0.601)}) {
    Case c = flying_case();
    c.trough.shape = shape;
    const Model model(c);
    for (int i = 0; i < 50; ++i) {
      const U::Vector y = random_flight_state(rng, model);
      const KinematicsT<double> k = kinematics_t(kinematics(model.geometry(), y[kDelta]));
      const FlightCentre<double> M = flight_centre(y, k, model.r());
      const TroughGap g = gap(shape, model.r(), M.x - y[kXA], M.z - y[kSA]);
      EXPECT_NEAR(g.delta, y[kDelta], 1e-12) << trough_name(shape);
      EXPECT_NEAR(g.gap, y[kGap], 1e-15) << trough_name(shape);
    }
  }
}

// In contact the state's gap is 0 and the drum's equations are the paper's.
TEST(UnilateralDrum, InContactItIsThePapersDrum) {
  Case c = flying_case();
  c.contact.pure_rolling = false;
  const Model model(c);
  const U u(model, 2.0 * model.nu());
  const Dynamics<OscillationDrum> drum(model, 2.0 * model.nu());
  std::mt19937 rng(2);
  for (int i = 0; i < 20; ++i) {
    U::Vector y = random_flight_state(rng, model);
    y[kGap] = y[kDGap] = 0.0;
    for (Phase phase : {Phase::stick, Phase::slip_positive, Phase::slip_negative}) {
      U::Vector f;
      u.rhs(phase, 0.01 * i, y, f);
      Dynamics<OscillationDrum>::Vector g;
      drum.rhs(phase, 0.01 * i, U::contact_part(y), g);
      EXPECT_EQ(U::contact_part(f), g) << to_string(phase);
      EXPECT_EQ(f[kGap], 0.0);
      EXPECT_EQ(f[kDGap], 0.0);
    }
  }
  // A case that never lifts off: the same steady state with either contact.
  Case paper;
  paper.MMd = 0.05 * paper.roller.M0;
  const Metrics a = compute_metrics(simulate(paper));
  paper.contact.unilateral = true;
  const Result r = simulate(paper);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  EXPECT_EQ(r.diagnostics.contact_mode, "permanent contact");
  const Metrics b = compute_metrics(r);
  EXPECT_NEAR(b.ddx_max, a.ddx_max, 1e-9 * std::abs(a.ddx_max));
  EXPECT_NEAR(b.area, a.area, 1e-9 * std::abs(a.area));
  EXPECT_EQ(b.flight_fraction, 0.0);
  EXPECT_EQ(b.gap_max, 0.0);
}

TEST(UnilateralDrum, FlightJacobianAgainstFiniteDifferences) {
  std::mt19937 rng(3);
  for (const TroughShape& shape : {trough_shape(0.0, 0.606), trough_shape(0.002, 0.601)}) {
    Case c = flying_case();
    c.trough.shape = shape;
    const Model model(c);
    const U u(model, 2.0 * model.nu());
    for (int i = 0; i < 10; ++i) {
      const U::Vector y = random_flight_state(rng, model);
      const double t = 0.002 * i;
      expect_jacobian(
          u.jacobian(Phase::flight, t, y), y,
          [&](const U::Vector& x) {
            U::Vector f;
            u.rhs(Phase::flight, t, x, f);
            return f;
          },
          std::string("flight ") + trough_name(shape));
    }
  }
}

// The monodromy matrix of a steady orbit that lifts off and lands once per period, from the
// variational equations with the saltation matrices of lift-off and landing, against central
// differences of the period map (tight tolerances make the map smooth enough to differentiate).
TEST(UnilateralDrum, MonodromyAcrossLiftOffAndLanding) {
  Case c = flying_case();
  c.numerics.rtol = 1e-11;
  c.numerics.atol = 1e-14;
  const Model model(c);
  const Result r = simulate(model);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  ASSERT_EQ(r.diagnostics.multiplicity, 1);
  ASSERT_EQ(r.diagnostics.contact_mode, "periodic lift-off");
  const FlowOptions options = FlowOptions::from(model);
  UnilateralFlow flow(model, options);
  const double t0 = r.samples.t.front(), T = model.period();
  const U u(model, options.baumgarte);
  const Phase phase = u.flow_phase(r.samples.phase.front());
  const U::Vector z0 = u.consistent(U::sampled_state(r.samples, 0), phase);
  MonodromyObserver<UnilateralDrum> mono(model, options.baumgarte, T / 64.0);
  flow.reset(t0, UnilateralState::from_array(z0), phase);
  ASSERT_EQ(flow.advance(t0 + T, &mono), FlowStop::reached);
  int lift_offs = 0, landings = 0;
  for (const Event& e : mono.switches()) {
    lift_offs += e.kind == EventKind::lift_off;
    landings += e.kind == EventKind::landing;
  }
  EXPECT_EQ(lift_offs, 1);
  EXPECT_EQ(landings, 1);
  const auto G = u.section_jacobian(z0, phase);
  const U::Matrix M = G ? U::Matrix(mono.phi() * *G) : mono.phi();
  // The scale of each component: its range over the period.
  std::array<double, 10> lo = z0, hi = z0;
  for (std::size_t j = 0; j < r.samples.size() / 2; ++j) {
    const U::Vector y = U::sampled_state(r.samples, j);
    for (int i = 0; i < 10; ++i) lo[i] = std::min(lo[i], y[i]), hi[i] = std::max(hi[i], y[i]);
  }
  const auto period_map = [&](U::Vector z) {
    flow.reset(t0, UnilateralState::from_array(u.consistent(z, phase)), phase);
    EXPECT_EQ(flow.advance(t0 + T), FlowStop::reached);
    return flow.state().to_array();
  };
  double largest = 0.0;
  U::Matrix fd, Ms;
  for (int j : U::kPeriodic) {
    const double sj = std::max(hi[j] - lo[j], 1e-12);
    const double h = 1e-4 * sj;
    U::Vector a = z0, b = z0;
    a[j] += h;
    b[j] -= h;
    const U::Vector Pa = period_map(a), Pb = period_map(b);
    for (int i : U::kPeriodic) {
      const double si = std::max(hi[i] - lo[i], 1e-12);
      fd(i, j) = (Pa[i] - Pb[i]) / (2 * h) * sj / si;
      Ms(i, j) = M(i, j) * sj / si;
      largest = std::max(largest, std::abs(fd(i, j)));
    }
  }
  for (int i : U::kPeriodic)
    for (int j : U::kPeriodic)
      EXPECT_NEAR(Ms(i, j), fd(i, j), 1e-4 * largest) << "entry " << i << ", " << j;
}

}  // namespace
}  // namespace oscidrum::detail

namespace oscidrum::detail {
namespace {

// ---- a second formulation: the contact as stiff penalty springs --------------------------------
//
// Written here independently of the event-driven model: the drum centre M = (x_M, z_M) and phi
// are free, the soil point A = (x_A, s_A) is massless (first order), and the contact is a normal
// spring kp on the overlap p = -gap (the trough shape's gap function, src/physics/trough_*.cpp)
// and, for pure rolling, a tangential spring kt on the slip u accumulated while in contact (u' =
// (M' - A').t - r phi', reset on separation): N = kp p, T = -kt u in contact, N = T = 0 apart.
// The forces enter (19), (20), (23) and the soil's (24), (25) as in the paper. As kp and kt grow
// the overlap and the slip vanish, and the trajectory tends to the event-driven one.
struct Penalty {
  const Model& model;
  double kp, kt;
  // y = (x_M, z_M, phi, x_A, s_A, x_M', z_M', phi', u)
  using Y = std::array<double, 9>;
  void operator()(const Y& y, Y& dy, double t) const {
    const double r = model.r();
    const TroughGap g = gap(model.parameters().trough.shape, r, y[0] - y[3], y[1] - y[4]);
    const double sn = std::sin(g.delta), cs = std::cos(g.delta);
    const bool touching = g.gap < 0.0;
    const double N = touching ? -kp * g.gap : 0.0;
    const double T = touching ? -kt * y[8] : 0.0;
    // (24), (25): csh x_A' = N sin - T cos - ksh x_A, csv s_A' = N cos + T sin - ksv s_A.
    const double dxA = (N * sn - T * cs - model.ksh() * y[3]) / model.csh();
    const double dsA = (N * cs + T * sn - model.ksv() * y[4]) / model.csv();
    dy[0] = y[5];
    dy[1] = y[6];
    dy[2] = y[7];
    dy[3] = dxA;
    dy[4] = dsA;
    dy[5] = (T * cs - N * sn - model.cd() * y[5] - model.kd() * y[0]) / model.m();  // (19)
    dy[6] =
        (model.W() - T * sn - N * cs - model.cd() * y[6] - model.kd() * (y[1] - model.z_ref())) /
        model.m();                                                      // (20)
    dy[7] = (model.torque(t) - T * r) / model.I();                      // (23)
    const double v = (y[5] - dxA) * cs - (y[6] - dsA) * sn - r * y[7];  // slip along t
    dy[8] = touching ? v : -y[8] * 1e6;  // the tangential spring lets go when contact opens
  }
};

// The event-driven trajectory and the penalty one over three periods from the same steady state
// of a drum that lifts off once per period: the end states approach each other as the penalty
// stiffness grows (here at first order, the overlap being N / kp), and so do the largest gap and
// the time in flight.
TEST(UnilateralDrum, PenaltyFormulationConvergesToTheEventDrivenOne) {
  Case c = flying_case();
  c.trough.shape = trough_shape(0.0, 0.606);
  c.soil.G = 80e6;
  const Model model(c);
  const Result r = simulate(model);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  ASSERT_EQ(r.diagnostics.contact_mode, "periodic lift-off");
  const FlowOptions options = FlowOptions::from(model);
  const U u(model, options.baumgarte);
  const double t0 = r.samples.t.front(), t1 = t0 + 3.0 * model.period();
  const Phase phase = u.flow_phase(r.samples.phase.front());
  ASSERT_NE(phase, Phase::flight);  // the section is in contact
  const U::Vector z0 = u.consistent(U::sampled_state(r.samples, 0), phase);

  // Event-driven: the end state, the largest gap and the time in flight.
  struct Watch : BasicFlowObserver<UnilateralDrum> {
    double gap = 0.0, flight = 0.0;
    bool on_step(const BasicStepView<UnilateralDrum>& s) override {
      for (int i = 0; i <= 8; ++i)
        gap = std::max(gap, s.state(s.t0() + i * (s.t1() - s.t0()) / 8).gap);
      if (s.phase() == Phase::flight) flight += s.t1() - s.t0();
      return true;
    }
  } watch;
  UnilateralFlow flow(model, options);
  flow.reset(t0, UnilateralState::from_array(z0), phase);
  ASSERT_EQ(flow.advance(t1, &watch), FlowStop::reached);
  const U::Vector ze = flow.state().to_array();
  const KinematicsT<double> ke = kinematics_t(kinematics(model.geometry(), ze[kDelta]));
  const FlightCentre<double> Me = flight_centre(ze, ke, model.r());
  const std::array<double, 7> event_end = {Me.x, Me.z, ze[kXA], ze[kSA], Me.dx, Me.dz, ze[kDPhi]};
  ASSERT_GT(watch.flight, 0.0);

  namespace odeint = boost::numeric::odeint;
  std::vector<double> errors;
  for (double kp : {1e9, 1e10, 1e11}) {
    const Penalty p{model, kp, kp};
    // The penalty model at the same state: the springs compressed to carry N and T.
    const ContactForces F = contact_forces(model, UnilateralState::from_array(z0).contact());
    const KinematicsT<double> k = kinematics_t(kinematics(model.geometry(), z0[kDelta]));
    const FlightCentre<double> M = flight_centre(z0, k, model.r());
    Penalty::Y y = {M.x + F.N / kp * k.sn,
                    M.z + F.N / kp * k.cs,
                    z0[kPhi],
                    z0[kXA],
                    z0[kSA],
                    M.dx,
                    M.dz,
                    kinematics(model.geometry(), z0[kDelta]).f5 * z0[kDDelta],
                    -F.T / kp};
    double gap_max = 0.0, flight = 0.0, t_last = t0;
    auto stepper = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<Penalty::Y>());
    odeint::integrate_adaptive(stepper, p, y, t0, t1, 1e-7, [&](const Penalty::Y& x, double t) {
      const TroughGap g = gap(model.parameters().trough.shape, model.r(), x[0] - x[3], x[1] - x[4]);
      gap_max = std::max(gap_max, g.gap);
      if (g.gap > 0.0) flight += t - t_last;
      t_last = t;
    });
    const std::array<double, 7> end = {y[0], y[1], y[3], y[4], y[5], y[6], y[7]};
    const std::array<double, 7> scale = {1e-4, 1e-4, 1e-4, 1e-4, 0.05, 0.05, 1.0};
    double e = 0.0;
    for (int i = 0; i < 7; ++i) e = std::max(e, std::abs(end[i] - event_end[i]) / scale[i]);
    errors.push_back(e);
    if (kp == 1e11) {
      EXPECT_NEAR(gap_max, watch.gap, 0.05 * watch.gap);
      EXPECT_NEAR(flight, watch.flight, 0.1 * watch.flight);
    }
  }
  // Each tenfold stiffer spring cuts the difference by at least a factor 3 (first order: 10).
  EXPECT_LT(errors[1], errors[0] / 3.0) << errors[0] << " " << errors[1];
  EXPECT_LT(errors[2], errors[1] / 3.0) << errors[1] << " " << errors[2];
  EXPECT_LT(errors[2], 0.05);
}

}  // namespace
}  // namespace oscidrum::detail

namespace oscidrum::detail {
namespace {

// Shooting (with the saltation matrices of lift-off and landing) and the transient method from
// rest find the same steady state with flight (G = 80 MN/m^2, 65 Hz, pure rolling).
TEST(UnilateralDrum, ShootingAndTransientAgreeWithFlight) {
  Case c = flying_case();
  c.soil.G = 80e6;
  const Result shot = simulate(c);
  c.numerics.method = SteadyMethod::transient;
  const Result trans = simulate(c);
  ASSERT_EQ(shot.status, Status::steady_state) << shot.message;
  ASSERT_EQ(trans.status, Status::steady_state) << trans.message;
  EXPECT_EQ(shot.diagnostics.method, SteadyMethod::shooting) << shot.diagnostics.fallback;
  EXPECT_EQ(shot.diagnostics.contact_mode, "periodic lift-off");
  EXPECT_EQ(trans.diagnostics.contact_mode, "periodic lift-off");
  EXPECT_EQ(shot.floquet.stability, Stability::stable);
  const Metrics a = compute_metrics(shot), b = compute_metrics(trans);
  const double tol = 2e-7;  // the transient's distance from the orbit, as for permanent contact
  EXPECT_NEAR(a.ddx_max, b.ddx_max, tol * std::abs(b.ddx_max));
  EXPECT_NEAR(a.ddz_max, b.ddz_max, tol * std::abs(b.ddz_max));
  EXPECT_NEAR(a.area, b.area, tol * std::abs(b.area));
  EXPECT_NEAR(a.flight_fraction, b.flight_fraction, tol);
  EXPECT_NEAR(a.gap_max, b.gap_max, tol * b.gap_max);
  EXPECT_NEAR(a.landing_velocity, b.landing_velocity, tol * b.landing_velocity);
  EXPECT_EQ(a.liftoffs_per_period, 1.0);
  EXPECT_GT(a.flight_fraction, 0.01);
  EXPECT_GT(a.gap_max, 1e-6);
}

// Energy over a steady period with flight: the excitation's work equals what the suspension's
// and the soil's dashpots dissipate (pure rolling: no sliding friction), integrated on the dense
// output by Gauss-Legendre quadrature on every piece. The drum's centre velocity is the chart's,
// M' = A' + (r f5 - g) delta' t - g' n (in contact g = g' = 0: (17)); landing on massless soil
// costs no energy.
TEST(UnilateralDrum, EnergyBalanceOverAPeriodWithFlight) {
  Case c = flying_case();
  c.soil.G = 80e6;
  c.numerics.rtol = 1e-10;
  const Model model(c);
  const Result r = simulate(model);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  ASSERT_GT(compute_metrics(model, r).flight_fraction, 0.01);
  const PeriodEnergy energy = energy_over_period(model, r);
  ASSERT_TRUE(energy.reached);
  EXPECT_EQ(energy.friction, 0.0);  // pure rolling: no slip
  EXPECT_GT(energy.in, 0.0);
  EXPECT_GT(energy.flight_out, 0.0);  // the soil relaxes through its dashpots in flight
  // The orbit repeats to steady_tol and the quadrature is exact to ~1e-12 on smooth pieces.
  EXPECT_NEAR(energy.out / energy.in, 1.0, 1e-6) << energy.in << " J against " << energy.out;
}

// Across the boundary of lift-off in a sweep over G (65 Hz, pure rolling, continuation from
// case to case): the period-1 orbit in permanent contact grazes (its smallest N falls to ~0 at
// G = 46.5 MN/m^2) and a period-2 orbit with flight takes over. The peak horizontal acceleration,
// the oscillation roller's main CCC value, moves on smoothly across the boundary, as it does on
// either side; the vertical metrics change with the orbit (docs/model.md section 13: without a
// friction limit the tangential force released at lift-off makes the grazing discontinuous).
// The contact mode counts the lift-offs of one repetition: at 70 Hz on G = 50 MN/m^2 the orbit
// repeats every 3 periods and lifts off twice in them (every 1.5 periods), which read "lift-off
// every 3 periods"; at 60 Hz once in 2 periods.
TEST(UnilateralDrum, ContactModeCountsTheLiftOffsOfOneRepetition) {
  Case c = flying_case();
  c.soil.G = 50e6;
  c.roller.f = 70.0;
  Result r = simulate(c);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  EXPECT_EQ(r.diagnostics.multiplicity, 3);
  EXPECT_EQ(r.diagnostics.contact_mode, "2 lift-offs every 3 periods");
  c.roller.f = 60.0;
  r = simulate(c);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  EXPECT_EQ(r.diagnostics.contact_mode, "lift-off every 2 periods");
}

// A chaotic run with intermittent flight (58 Hz on G = 50 MN/m^2, docs/bifurcations.md): its
// lift-offs need not fall in the periods sampled at the end, yet it is a run with lift-offs that
// reaches no steady state, contact_mode "aperiodic" whatever max_periods (it was empty at 1500).
TEST(UnilateralDrum, AnAperiodicRunWithLiftOffsIsSaidSoWhereverTheyFall) {
  Case c = flying_case();
  c.soil.G = 50e6;
  c.roller.f = 58.0;
  c.numerics.method = SteadyMethod::transient;
  for (const int periods : {500, 1500}) {
    c.numerics.max_periods = periods;
    const Result r = simulate(c);
    ASSERT_EQ(r.status, Status::aperiodic) << r.message;
    EXPECT_EQ(r.diagnostics.min_N, 0.0);
    EXPECT_EQ(r.diagnostics.contact_mode, "aperiodic") << periods << " periods";
  }
}

TEST(UnilateralDrum, MetricsAcrossTheBoundaryOfLiftOff) {
  std::vector<Case> cases;
  for (double G = 44.0; G <= 49.01; G += 0.5) {
    Case c = flying_case();
    c.soil.G = G * 1e6;
    cases.push_back(c);
  }
  StudyOptions options;
  options.threads = 1;
  const std::vector<CaseOutcome> out = run_study(cases, options);
  std::vector<double> ddx, flight, min_N;
  for (const CaseOutcome& o : out) {
    ASSERT_EQ(o.result.status, Status::steady_state) << o.result.message;
    ddx.push_back(o.metrics.ddx_max);
    flight.push_back(o.metrics.flight_fraction);
    min_N.push_back(o.result.diagnostics.min_N);
  }
  std::size_t first = 0;
  while (first < flight.size() && flight[first] == 0.0) ++first;
  ASSERT_GT(first, 1u) << "no case in permanent contact";
  ASSERT_LT(first, flight.size()) << "no case with flight";
  // The last orbit in contact nearly grazes: min N has fallen to ~0.1 % of W = P0.
  EXPECT_LT(min_N[first - 1], 1e-2 * cases[0].roller.P0);
  EXPECT_GT(min_N[first - 1], 0.0);
  // An orbit with flight reaches N = 0 at its lift-offs: its min N is 0 (it was the smallest N
  // at the step ends in contact, hundreds of newtons).
  for (std::size_t i = first; i < min_N.size(); ++i) EXPECT_EQ(min_N[i], 0.0) << i;
  for (std::size_t i = 1; i < ddx.size(); ++i) {
    const double step = ddx[i] - ddx[i - 1];
    // Half a MN/m^2 moves the peak by ~1.2 % on either side; across the boundary as well.
    EXPECT_GT(step, 0.0) << i;
    EXPECT_LT(step, 0.02 * ddx[i - 1]) << i;
  }
}

}  // namespace
}  // namespace oscidrum::detail

namespace oscidrum::detail {
namespace {

// The rows of delta, x_A, s_A are the unit rows of their rates, in contact and in flight alike.
TEST(UnilateralDrum, KinematicRowsAreUnitRows) {
  const Model model(flying_case());
  const U u(model, 2.0 * model.nu());
  std::mt19937 rng(9);
  for (Phase phase : {Phase::stick, Phase::flight}) {
    U::Vector y = random_flight_state(rng, model);
    if (phase != Phase::flight) y[kGap] = y[kDGap] = 0.0;
    const U::Matrix J = u.jacobian(phase, 0.003, y);
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 10; ++col) EXPECT_EQ(J(row, col), col == row + 5 ? 1.0 : 0.0);
  }
}

// The pure-rolling cases of the random scan that stop with unilateral contact
// (scripts/contact_lost_scan.py, docs/lift-off.md) are not lift-offs of a drum with a friction
// limit: without one the contact would have to carry T as N falls to zero (neither flight nor
// contact is consistent, the run stops saying so); with mu = 2 the same drum slips and keeps its
// contact throughout, the same with permanent and with unilateral contact.
TEST(UnilateralDrum, APureRollingStopIsNotALiftOffOfAFrictionLimitedDrum) {
  Case c;
  set_field_text(c, "soil.input", "modulus");
  set_field(c, "soil.G", 60044266.47906289);
  set_field(c, "roller.unbalance", 0.22877);
  set_field(c, "roller.f", 68.11199841103928);
  set_field(c, "MMd", 25756.446723514764);
  set_field(c, "trough.a", 0.6342729759975047);
  c.contact.unilateral = true;
  c.contact.pure_rolling = true;
  const Result rolling = simulate(c);
  EXPECT_EQ(rolling.status, Status::contact_lost) << rolling.message;
  EXPECT_NE(rolling.message.find("give a friction coefficient instead"), std::string::npos)
      << rolling.message;
  c.contact.pure_rolling = false;
  c.contact.mu = 2.0;
  const Result unilateral = simulate(c);
  ASSERT_EQ(unilateral.status, Status::steady_state) << unilateral.message;
  EXPECT_EQ(unilateral.diagnostics.contact_mode, "permanent contact");
  EXPECT_GT(unilateral.diagnostics.min_N, 0.0);
  EXPECT_GT(unilateral.slip_positive_time + unilateral.slip_negative_time, 0.0);  // it slips
  c.contact.unilateral = false;
  const Result permanent = simulate(c);
  ASSERT_EQ(permanent.status, Status::steady_state) << permanent.message;
  const Metrics a = compute_metrics(unilateral), b = compute_metrics(permanent);
  EXPECT_NEAR(a.ddx_max, b.ddx_max, 1e-6 * std::abs(b.ddx_max));
  EXPECT_NEAR(a.area, b.area, 1e-6 * std::abs(b.area));
}

// A landing whose contact pulls (N < 0 just after it) lifts off again at once (docs/model.md
// section 13). Where N rose back through zero before the first step's middle, the flow missed it
// and ran on in stick with the soil pulling the drum (N down to -307 N for 0.4 % of the period)
// to a steady_state with flight. In pure rolling the lift-off from stick finds the trough moving
// into the drum: contact is lost, and the run says so.
TEST(UnilateralDrum, ALandingWhoseContactPullsLiftsOffAtOnce) {
  Case c;
  set_field_text(c, "soil.input", "modulus");
  set_field(c, "soil.G", 21.5e6);
  set_field(c, "soil.nu", 0.34);
  set_field(c, "soil.rho", 2080.0);
  set_field(c, "roller.f", 55.0);
  set_field(c, "roller.unbalance", 0.22877);
  const double nu = 2.0 * std::numbers::pi * 55.0;
  set_field(c, "MMd", 0.26 * 4.0 * 0.22877 * nu * nu);  // 0.26 M0, M0 from (5)
  set_field(c, "trough.k", 0.0146);
  set_field(c, "trough.a", 0.6133);
  c.contact.unilateral = true;
  c.contact.pure_rolling = true;
  const Result rolling = simulate(c);
  ASSERT_EQ(rolling.status, Status::contact_lost) << rolling.message;
  EXPECT_NE(rolling.message.find("give a friction coefficient instead"), std::string::npos)
      << rolling.message;
  // The contact pulled where stick began: the message says so with N's value there, and the
  // smallest normal force is that value (the message said "N reached 0" and min N was 0).
  EXPECT_NE(rolling.message.find("the contact pulled where stick began after a landing (N = -"),
            std::string::npos)
      << rolling.message;
  EXPECT_LT(rolling.diagnostics.min_N, -1.0);
}

}  // namespace
}  // namespace oscidrum::detail
