// The hybrid flow (src/flow/flow.cpp): a trajectory does not depend on how it is cut into
// intervals, observers see it whole and in order, events are reported with both one-sided
// states, and the stops (budget, cancellation, observer) end it where they say.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "oscidrum/oscidrum.hpp"
#include "tolerances.hpp"

namespace oscidrum {
namespace {

Case stick_slip(double G_MN, double MMd_fraction) {
  Case c;
  c.soil = table2_soil(G_MN * 1e6);
  c.MMd = MMd_fraction * c.roller.M0;
  return c;
}

// Records the pieces and events it is shown.
struct Recorder : FlowObserver {
  struct Piece {
    double t0, t1;
    Phase phase;
    bool ends_step;
    State start, end;
  };
  std::vector<Piece> pieces;
  std::vector<Event> events;
  std::vector<std::pair<State, State>> jumps;
  bool on_step(const StepView& s) override {
    pieces.push_back({s.t0(), s.t1(), s.phase(), s.ends_step(), s.state(s.t0()), s.state(s.t1())});
    return true;
  }
  bool on_event(const Event& e, const State& before, const State& after) override {
    events.push_back(e);
    jumps.emplace_back(before, after);
    return true;
  }
};

TEST(Flow, TrajectoryDoesNotDependOnHowItIsCut) {
  const Model model(stick_slip(25, 0.05));
  const double T = model.period();
  Flow whole(model), cut(model);
  whole.reset(0.0, model.initial_state(), initial_phase(model));
  cut.reset(0.0, model.initial_state(), initial_phase(model));
  ASSERT_EQ(whole.advance(10 * T), FlowStop::reached);
  for (int k = 1; k <= 370; ++k) ASSERT_EQ(cut.advance(k * T / 37.0), FlowStop::reached);
  // The same steps, the same events: the end states agree to the last bit of the dense output.
  EXPECT_EQ(whole.counters().steps, cut.counters().steps);
  EXPECT_EQ(whole.counters().events, cut.counters().events);
  const auto a = whole.state().to_array(), b = cut.state().to_array();
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(a[i], b[i], 1e-12 * (1.0 + std::abs(a[i]))) << i;
  EXPECT_EQ(whole.phase(), cut.phase());
}

TEST(Flow, ObserverSeesTheWholeTrajectoryInOrder) {
  const Model model(stick_slip(25, 0.05));
  const double T = model.period();
  Flow flow(model);
  flow.reset(0.0, model.initial_state(), initial_phase(model));
  Recorder rec;
  ASSERT_EQ(flow.advance(3 * T, &rec), FlowStop::reached);
  ASSERT_FALSE(rec.pieces.empty());
  EXPECT_EQ(rec.pieces.front().t0, 0.0);
  EXPECT_EQ(rec.pieces.back().t1, 3 * T);
  for (std::size_t i = 1; i < rec.pieces.size(); ++i) {
    EXPECT_EQ(rec.pieces[i].t0, rec.pieces[i - 1].t1) << i;  // contiguous
    EXPECT_GT(rec.pieces[i].t1, rec.pieces[i].t0) << i;
  }
  // Stick-slip at G = 25 with a driving torque switches 4 times per period once settled.
  EXPECT_GE(rec.events.size(), 8u);
  std::size_t e = 0;
  for (std::size_t i = 0; i + 1 < rec.pieces.size() && e < rec.events.size(); ++i) {
    if (rec.pieces[i].t1 != rec.events[e].t) continue;
    // An event ends a piece; the next piece starts in the new phase from the state after it.
    EXPECT_FALSE(rec.pieces[i].ends_step);
    EXPECT_EQ(rec.pieces[i].phase, rec.events[e].from);
    EXPECT_EQ(rec.pieces[i + 1].phase, rec.events[e].to);
    const auto after = rec.jumps[e].second.to_array(), next = rec.pieces[i + 1].start.to_array();
    for (int k = 0; k < 8; ++k) EXPECT_NEAR(after[k], next[k], 1e-12 * (1 + std::abs(after[k])));
    ++e;
  }
  EXPECT_EQ(e, rec.events.size()) << "every event ends a piece";
}

TEST(Flow, AtAStickToSlipSwitchTheFrictionLimitIsReached) {
  const Model model(stick_slip(25, 0.0));
  Flow flow(model);
  flow.reset(0.0, model.initial_state(), initial_phase(model));
  Recorder rec;
  ASSERT_EQ(flow.advance(5 * model.period(), &rec), FlowStop::reached);
  int checked = 0;
  for (std::size_t i = 0; i < rec.events.size(); ++i) {
    if (rec.events[i].kind != EventKind::stick_to_slip) continue;
    const ContactForces f = contact_forces(model, rec.jumps[i].first);
    EXPECT_NEAR(std::abs(f.T), model.cone() * f.N, 1e-9 * model.W());
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

// Near the grazing of the slip+ phase (MMd = 6885 N m on the paper's roller) the slip+ phase lasts
// 0.4 % of the period, inside one step of about 1 %: the cone function was positive at the
// step's start, middle and end, the dip between them was missed, and the stick phase carried
// |T| > mu N through it (mu_required 0.50013, 2 switches a period instead of 4, the slip+
// fraction 0). The parabola through the samples finds it (kDipFraction): the default tolerances
// now give what rtol = 1e-10 gives.
TEST(Flow, ASlipPhaseShorterThanAStepIsNotMissed) {
  Case c;
  c.MMd = 6885.0;
  c.numerics.method = SteadyMethod::shooting;
  const Result r = simulate(c);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  const Metrics m = compute_metrics(Model(c), r);
  Case fine = c;
  fine.numerics.rtol = 1e-10;
  const Result rf = simulate(fine);
  ASSERT_EQ(rf.status, Status::steady_state) << rf.message;
  const Metrics mf = compute_metrics(Model(fine), rf);
  EXPECT_LE(m.mu_required, c.contact.mu * (1.0 + 1e-8));
  EXPECT_DOUBLE_EQ(r.diagnostics.switches_per_period, 4.0);
  EXPECT_GT(mf.slip_positive_fraction, 3e-3);
  EXPECT_NEAR(m.slip_positive_fraction, mf.slip_positive_fraction,
              1e-3 * mf.slip_positive_fraction);
}

// min_N counts N at the events: its corner minimum at a stick-to-slip switch lay 83 N below every
// step end (mu 1.27, MMd -0.15 M0, 53 Hz), and min_N was above the sampled periods' own minimum.
// And Newton's iterates, integrated before the longer transient a failed Newton retries after,
// are off the run's trajectory: their slip residual (1e-3) was reported as max_slip_residual.
TEST(Flow, TheExtremesAreTheTrajectorysOwn) {
  Case c;
  c.soil = table2_soil(40e6);
  set_field(c, "contact.mu", 1.27);
  set_field(c, "roller.unbalance", 0.22877);
  set_field(c, "roller.f", 53.0);
  c.MMd = -15221.652339200951;  // -0.15 of M0 by the unbalance at 53 Hz
  c.numerics.method = SteadyMethod::shooting;
  const Result r = simulate(c);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  double lowest = r.samples.N.front();
  for (const double N : r.samples.N) lowest = std::min(lowest, N);
  EXPECT_LE(r.diagnostics.min_N, lowest + 1e-9 * Model(c).W());
  Case d;
  d.soil = table2_soil(45e6);
  set_field(d, "contact.mu", 0.76);
  set_field(d, "roller.unbalance", 0.22877);
  set_field(d, "roller.f", 44.7);
  set_field(d, "trough.a", 0.629);
  d.MMd = 18045.705068490588;  // 0.25 of M0 by the unbalance at 44.7 Hz
  d.numerics.method = SteadyMethod::shooting;
  const Result s = simulate(d);
  ASSERT_EQ(s.status, Status::steady_state) << s.message;
  EXPECT_LT(s.diagnostics.max_slip_residual, 1e-8) << s.message;
}

// The extremes of a trajectory do not depend on what the flow integrated before its reset: the
// first step's parabola through N (min_N) started from the last step of the trajectory before.
TEST(Flow, TheExtremesDoNotDependOnTheFlowsHistory) {
  const Model model(stick_slip(25, 0.05));
  const double T = model.period();
  // N over the third period: its largest (where the flow used before stops) and its smallest
  // (where both flows start: a step from there has N rising, no minimum inside).
  Flow probe(model);
  probe.reset(0.0, model.initial_state(), initial_phase(model));
  double t_hi = 0.0, t_lo = 0.0, N_hi = -1e300, N_lo = 1e300;
  for (int k = 0; k < 400; ++k) {
    const double t = (2.0 + k / 400.0) * T;
    ASSERT_EQ(probe.advance(t), FlowStop::reached);
    const double N = contact_forces(model, probe.state()).N;
    if (N > N_hi) N_hi = N, t_hi = t;
    if (N < N_lo) N_lo = N, t_lo = t;
  }
  Flow at_lo(model);
  at_lo.reset(0.0, model.initial_state(), initial_phase(model));
  ASSERT_EQ(at_lo.advance(t_lo), FlowStop::reached);
  Flow used(model);
  used.reset(0.0, model.initial_state(), initial_phase(model));
  ASSERT_EQ(used.advance(t_hi), FlowStop::reached);
  used.reset(t_lo, at_lo.state(), at_lo.phase());
  used.reset_extremes();
  Flow fresh(model);
  fresh.reset(t_lo, at_lo.state(), at_lo.phase());
  ASSERT_EQ(used.advance(t_lo + 0.3 * T), FlowStop::reached);
  ASSERT_EQ(fresh.advance(t_lo + 0.3 * T), FlowStop::reached);
  EXPECT_EQ(used.counters().min_N, fresh.counters().min_N) << N_lo << " " << N_hi;
}

// A state on the wrong side of a switching surface of its phase is refused at once
// (FlowStop::inconsistent_state): an event fires only when its function falls through zero, so
// from such a state the flow would follow equations that do not hold without ever switching
// (in stick beyond the friction cone; in contact with N < 0). The same state in its right phase,
// and a state on the surface itself, run.
TEST(Flow, RefusesAStateOnTheWrongSideOfItsSwitches) {
  const Model model(stick_slip(25, 0.05));
  const double T = model.period();
  // The soil under the drum pushed 1 mm sideways: its spring's T = ksh x_A (24) is far beyond
  // mu N, and the drum turning.
  State q = model.initial_state();
  q.x_A = 1e-3;
  q.dphi = 50.0;
  const ContactForces f = contact_forces(model, q);
  ASSERT_LT(model.cone() * f.N - std::abs(f.T), 0.0);
  {
    Flow flow(model);
    flow.reset(0.0, q, Phase::stick);
    EXPECT_EQ(flow.advance(T), FlowStop::inconsistent_state);
    EXPECT_EQ(flow.counters().steps, 0);
    EXPECT_EQ(flow.t(), 0.0);
    EXPECT_NE(flow.message().find("not one of its phase"), std::string::npos) << flow.message();
    EXPECT_EQ(status_of(FlowStop::inconsistent_state), Status::contact_lost);
    // It stays refused until the next reset.
    EXPECT_EQ(flow.advance(T), FlowStop::inconsistent_state);
  }
  {  // The same state slipping: consistent.
    Flow flow(model);
    flow.reset(0.0, q, slip_velocity(model, q) > 0 ? Phase::slip_positive : Phase::slip_negative);
    EXPECT_EQ(flow.advance(0.1 * T), FlowStop::reached);
  }
  {  // The drum pulled off the soil (s_A far above its rest): N < 0 in contact.
    State up = model.initial_state();
    up.s_A = -0.05;
    ASSERT_LT(contact_forces(model, up).N, 0.0);
    Flow flow(model);
    flow.reset(0.0, up, Phase::stick);
    EXPECT_EQ(flow.advance(T), FlowStop::inconsistent_state);
  }
}

TEST(Flow, StopsWhereItSays) {
  const Model model(stick_slip(25, 0.05));
  const double T = model.period();
  {  // an observer that stops at once
    struct Stop : FlowObserver {
      bool on_step(const StepView&) override { return false; }
    } stop;
    Flow flow(model);
    flow.reset(0.0, model.initial_state(), initial_phase(model));
    EXPECT_EQ(flow.advance(T, &stop), FlowStop::observer);
    EXPECT_LT(flow.t(), T);
  }
  {  // cancellation
    FlowOptions o = FlowOptions::from(model);
    int polls = 0;
    o.cancelled = [&] { return ++polls > 3; };
    Flow flow(model, o);
    flow.reset(0.0, model.initial_state(), initial_phase(model));
    EXPECT_EQ(flow.advance(100 * T), FlowStop::cancelled);
    EXPECT_EQ(flow.counters().steps, 3);
    EXPECT_NE(flow.message().find("cancelled"), std::string::npos);
  }
  {  // the step budget
    FlowOptions o = FlowOptions::from(model);
    o.max_steps_per_period = 10;
    Flow flow(model, o);
    flow.reset(0.0, model.initial_state(), initial_phase(model));
    EXPECT_EQ(flow.advance(100 * T), FlowStop::budget_exceeded);
    EXPECT_LT(flow.t(), T);
  }
  {  // t_end at or before t(): nothing happens
    Flow flow(model);
    flow.reset(0.25, model.initial_state(), initial_phase(model));
    EXPECT_EQ(flow.advance(0.25), FlowStop::reached);
    EXPECT_EQ(flow.counters().steps, 0);
  }
}

}  // namespace
}  // namespace oscidrum
