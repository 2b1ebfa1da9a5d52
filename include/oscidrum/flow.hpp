// oscidrum/flow.hpp: the hybrid flow. Integrates the drum-soil system from a state over an
// interval through its events (stick -> slip, slip -> stick or reversal, contact loss), with the
// chattering guard and a work budget. Every driver is built on it: the transient steady-state
// search and the sampling of the steady state (oscidrum/simulate.hpp), and whatever else needs
// the trajectory (shooting, a step-by-step animation, exact metrics).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "oscidrum/model.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/roller.hpp"
#include "oscidrum/state.hpp"

namespace oscidrum {

/// Numerical settings of the flow. `from(model)` takes them from the model's Numerics.
struct FlowOptions {
  double rtol = 1e-8;                  ///< relative tolerance of the Dormand-Prince steps [-]
  double atol = 1e-11;                 ///< absolute tolerance (SI units of each state) [-]
  double baumgarte = 0.0;              ///< rate pulling the slip coupling (39) back to zero [1/s]
  double max_step = 0.0;               ///< largest step [s] (events are scanned inside steps)
  long max_switches_per_period = 200;  ///< more stick/slip switches in one excitation period
                                       ///< (t in [nT, (n+1)T)) stop the flow as chattering [-]
  long max_steps_per_period = 0;       ///< more accepted steps in one excitation period stop the
                                       ///< flow as budget_exceeded (0: no limit) [-]
  /// Polled once per accepted step; returning true stops the flow (FlowStop::cancelled).
  std::function<bool()> cancelled;

  /// rtol, atol, Baumgarte rate (slip_constraint_rate, 0 meaning 2 nu), max_step = T/16, the
  /// switch and step budgets of `model.parameters().numerics`.
  static FlowOptions from(const Model& model);
};

/// Why Flow::advance returned.
enum class FlowStop {
  reached,           ///< the requested time was reached
  observer,          ///< an observer returned false
  contact_lost,      ///< N reached 0 (lift-off is outside the model)
  chattering,        ///< too many switches in a period, or 20 within a vanishing time
  non_finite,        ///< the state became NaN or infinite
  invalid_geometry,  ///< the trough's curvature radius fell to the drum radius (f5 below 1e-3 of
                     ///< its value at the bottom)
  budget_exceeded,   ///< more steps in one excitation period than FlowOptions allows
  cancelled,         ///< FlowOptions::cancelled returned true
  /// The state given to Flow::reset lies on the wrong side of a switching surface of its phase
  /// (an event function below zero: a cone violated in stick, N < 0 in contact, a gap < 0 in
  /// flight), so it is no state of that phase and its switch could never be detected. Only a
  /// state from outside the flow can be so (a shooting iterate, a neighbour's orbit, a user's);
  /// reported as Status::contact_lost (no consistent state of the model).
  inconsistent_state,
};
const char* to_string(FlowStop stop);

/// The status of a run that the flow stopped early (contact_lost, chattering, non_finite,
/// invalid_geometry, budget_exceeded; cancelled and observer give Status::cancelled).
Status status_of(FlowStop stop);

/// The part of an accepted integration step that lies in one phase and one advance() interval:
/// the dense output (Dormand-Prince 8(5,3)'s continuous extension, 7th order) between t0() and
/// t1(). Valid only inside the observer call that receives it.
template <class Roller>
class BasicStepView {
 public:
  using State = typename Roller::State;
  virtual ~BasicStepView() = default;
  virtual double t0() const = 0;  ///< [s]
  virtual double t1() const = 0;  ///< [s]
  virtual Phase phase() const = 0;
  /// The state at t in [t0(), t1()].
  virtual State state(double t) const = 0;
  /// state(t[i]) for i = 0 ... n-1 into out[i] (the flow evaluates many at once).
  virtual void states(const double* t, int n, State* out) const {
    for (int i = 0; i < n; ++i) out[i] = state(t[i]);
  }
  /// True when t1() is the end of the integrator's step (not an event or the end of an interval).
  virtual bool ends_step() const = 0;
};

/// Receives the trajectory as BasicFlow::advance produces it, in time order.
template <class Roller>
class BasicFlowObserver {
 public:
  using State = typename Roller::State;
  virtual ~BasicFlowObserver() = default;
  /// A piece of the trajectory; return false to stop the flow (FlowStop::observer).
  virtual bool on_step(const BasicStepView<Roller>& /*step*/) { return true; }
  /// An event at event.t: the state just before it and the state the flow continues from (the
  /// same but for a velocity reset at a slip end). Return false to stop the flow.
  virtual bool on_event(const Event& /*event*/, const State& /*before*/, const State& /*after*/) {
    return true;
  }
};

/// Counters of a flow since its construction.
struct FlowCounters {
  long steps = 0;                   ///< accepted integrator steps
  long rhs_evaluations = 0;         ///< right-hand-side evaluations
  long events = 0;                  ///< located events (switches and contact loss)
  long switches = 0;                ///< phase changes (stick <-> slip, reversals)
  long reversals = 0;               ///< slip -> slip reversals
  long inconsistent_slip_ends = 0;  ///< slip ends where neither stick nor a reversal is
                                    ///< consistent (docs/model.md); stick is taken
  long restarts = 0;                ///< integrator (re)starts: reset() and one per event
  long partial_steps = 0;           ///< integrator steps from a step's start to a time inside
                                    ///< it: an event, the end of an advance() interval (11
                                    ///< evaluations each)
  double min_N = 0.0;               ///< smallest normal force: step ends, events and the
                                    ///< parabola through each step's samples [N]
  double max_slip_residual = 0.0;   ///< max |(39)| / W at step ends in slip [-]
};

/// The hybrid flow of one model for the roller type `Roller` (oscidrum/roller.hpp): its state,
/// phases, equations and events are the roller's (src/roller/), the integration, the location of
/// events, the guards and the observers are this class's. Holds the integrator between calls, so
/// that consecutive advance() calls continue one trajectory exactly as a single call would (a
/// step that straddles the end of an interval is not cut; its dense output serves both sides).
template <class Roller>
class BasicFlow {
 public:
  using State = typename Roller::State;
  using Observer = BasicFlowObserver<Roller>;
  BasicFlow(const Model& model, const FlowOptions& options);
  explicit BasicFlow(const Model& model) : BasicFlow(model, FlowOptions::from(model)) {}
  ~BasicFlow();
  BasicFlow(const BasicFlow&) = delete;
  BasicFlow& operator=(const BasicFlow&) = delete;

  /// Start (or restart) at time t from state q in the given phase.
  void reset(double t, const State& q, Phase phase);

  /// Integrate to t_end (>= t()), passing every piece and event to `observer` (may be null).
  /// Events at t <= t_end are applied. On FlowStop::reached, t() == t_end and state() is the
  /// state there; on any other stop, t() and state() are where the flow stopped and message()
  /// explains it. Never throws for numerical trouble.
  FlowStop advance(double t_end, Observer* observer = nullptr);

  double t() const;     ///< [s]
  State state() const;  ///< the state at t()
  Phase phase() const;  ///< the phase at t()
  const Model& model() const;
  const FlowOptions& options() const;
  const FlowCounters& counters() const;
  const std::string& message() const;  ///< why the last advance() stopped early ("" if reached)
  /// Restart the extremes of the counters (min_N, max_slip_residual): a driver that integrates
  /// states off the trajectory it reports (Newton's iterates) keeps them to that trajectory.
  void reset_extremes();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The paper's oscillation drum: its flow, step views and observers.
using Flow = BasicFlow<OscillationDrum>;
using StepView = BasicStepView<OscillationDrum>;
using FlowObserver = BasicFlowObserver<OscillationDrum>;
extern template class BasicFlow<OscillationDrum>;

/// The drum with unilateral contact (contact.unilateral): its flow, with the flight phase.
using UnilateralFlow = BasicFlow<UnilateralDrum>;
extern template class BasicFlow<UnilateralDrum>;

/// The phase a trajectory starts in from rest: stick, except without friction (mu = 0 and not
/// pure rolling), where the drum slips from the start (the sign does not matter then).
Phase initial_phase(const Model& model);

}  // namespace oscidrum
