// Internal: the paper's oscillation drum as a roller component (src/roller/dynamics.hpp lists the
// members the engine uses). Its state is (54), q = (delta, x_A, s_A, phi, delta', x_A', s_A',
// phi'); its phases stick (52), slip (55) and the smooth phase of a regularised law; its events
// the friction cone (28), the end of slip (13) and the contact (26). The equations themselves are
// in src/equations/; this class binds them to the engine.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "equations/jacobian.hpp"
#include "flow/event_functions.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/roller.hpp"
#include "roller/dynamics.hpp"

namespace oscidrum::detail {

template <>
class Dynamics<OscillationDrum> {
 public:
  static constexpr int kStates = OscillationDrum::kStates;
  static constexpr int kEvents = kEventCount;
  /// The event function N / W: below zero the soil pulls the drum.
  static constexpr int kContactEvent = kEventContact;
  /// The components that repeat on a periodic orbit: all but phi (index 3), which is cyclic (no
  /// right-hand side depends on it; it may drift by the net slip per period).
  static constexpr std::array<int, 7> kPeriodic = {0, 1, 2, 4, 5, 6, 7};
  /// The component whose growth is a spin (gross slip): phi'.
  static constexpr int kSpin = 7;
  /// The slip determinant (slip_determinant) below which a slip state counts as singular.
  static constexpr double kSingularSlip = 1e-3;
  /// f5 (50), relative to its value at the trough's bottom, below which rolling counts as
  /// undefined (the trough's curvature radius has come within that of the drum radius).
  static constexpr double kSingularRolling = 1e-3;
  using Vector = std::array<double, kStates>;
  using Matrix = Mat8;
  using EventValues = oscidrum::EventValues;

  /// What an event does.
  struct Switch {
    EventKind kind = EventKind::stick_to_slip;
    Phase to = Phase::stick;
    Vector after{};                          ///< the state the flow continues from
    std::array<bool, kEvents> fresh{};       ///< functions that start at zero and must grow
    bool terminal = false;                   ///< the flow stops (contact lost)
    FlowStop stop = FlowStop::contact_lost;  ///< why, when terminal
    std::string message;                     ///< why, when terminal
    bool consistent = true;                  ///< false: an inconsistent slip end or start (counted)
    bool reversal = false;
    double speed = 0.0;  ///< a landing's approach speed -g' (Event::speed) [m/s] ///< a slip ->
                         ///< slip reversal (counted)
  };

  Dynamics(const Model& model, double baumgarte);
  const Model& model() const { return model_; }

  // ---- the flow -------------------------------------------------------------------------------
  /// y' = f(t, y) of `phase`: (52) in stick, (55) in slip and in the smooth phase.
  void rhs(Phase phase, double t, const Vector& x, Vector& dxdt) const;
  /// The event functions (src/flow/event_functions.hpp); N receives the normal force [N].
  EventValues events(Phase phase, const Vector& x, double* N = nullptr) const {
    return event_values(model_, phase, State::from_array(x), N);
  }
  /// events() at the n states x[i] into e[i] and N[i], evaluated in lanes.
  void events_many(Phase phase, const Vector* x, int n, EventValues* e, double* N) const {
    event_values(model_, phase, x, n, e, N);
  }
  /// Event `which` of `phase` at time t, x the state just before it.
  Switch apply(Phase phase, int which, double t, const Vector& x) const;
  /// A state the equations are undefined at, with the stop it ends the run in: the trough's
  /// curvature radius fell to the drum radius (f5 below 1e-3 of its bottom's, invalid_geometry), or
  /// in slip the slip system became singular (contact_lost).
  bool invalid(Phase phase, const Vector& x, double t, std::string* why, FlowStop* stop) const;
  /// min N and the largest slip residual (39) at a step's end.
  void track(Phase phase, const Vector& x, double N, FlowCounters& counters) const;
  Vector initial_state() const { return model_.initial_state().to_array(); }
  Phase initial_phase() const { return oscidrum::initial_phase(model_.friction()); }
  /// The phase to continue a neighbour's state in: its phase if this case has it, else the
  /// initial phase (oscidrum::flow_phase).
  Phase flow_phase(Phase phase) const { return oscidrum::flow_phase(model_.friction(), phase); }

  // ---- variational equations ------------------------------------------------------------------
  Matrix jacobian(Phase phase, double t, const Vector& x) const {
    return phase_jacobian(model_, t, State::from_array(x), phase, baumgarte_);
  }
  SaltationMatrix<kStates> saltation(const Event& event, const Vector& before,
                                     const Vector& after) const;

  // ---- shooting -------------------------------------------------------------------------------
  /// In stick phi' = f5 delta' (12): a Newton update must not break it.
  Vector consistent(Vector z, Phase phase) const;
  /// d consistent(z) / dz; empty where consistent is the identity (off stick).
  std::optional<Matrix> section_jacobian(const Vector& z, Phase phase) const;
  /// The drift of the cyclic coordinate phi from `start` to `end` [rad].
  static double cyclic_drift(const Vector& end, const Vector& start) { return end[3] - start[3]; }

  // ---- sampling -------------------------------------------------------------------------------
  void sample(double t, const Vector& x, Phase phase, Samples& samples) const;
  /// The samples at t[0 ... count-1] of the states x, all in `phase`: the same values as sample()
  /// at each, evaluated kSampleLanes at a time (util/lanes.hpp).
  void sample_many(const double* t, const Vector* x, int count, Phase phase,
                   Samples& samples) const;
  static constexpr int kSampleLanes = 8;
  /// The phase a state is shown in (the smooth phase of a regularised law and slip without
  /// friction show their apparent phase, oscidrum/friction.hpp; every other phase itself).
  Phase apparent(Phase phase, const Vector& x) const {
    if (!apparent_varies(phase)) return phase;
    return apparent_phase(model_.friction(), phase, slip_velocity(model_, State::from_array(x)));
  }
  /// True when the phase shown can change inside a piece of the flow in `phase` (the smooth
  /// phase; slip without friction: oscidrum/friction.hpp).
  bool apparent_varies(Phase phase) const {
    return oscidrum::apparent_varies(model_.friction(), phase);
  }
  /// What the steady metrics read at a point of the trajectory (src/drivers/steady_metrics.cpp):
  /// x_M'', z_M'' (18), delta, phi, T/N, the friction power |T v_rel| (0 in stick), the gap (0),
  /// the soil's vertical force on the drum F_v = N cos(delta) + T sin(delta) (25) and z_M (14).
  std::array<double, 9> quantities(double t, const Vector& x, Phase phase) const;
  static Vector sampled_state(const Samples& s, std::size_t j) {
    return {s.delta[j], s.x_A[j], s.s_A[j], s.phi[j], s.ddelta[j], s.dx_A[j], s.ds_A[j], s.dphi[j]};
  }

  // ---- the steady-state search ----------------------------------------------------------------
  /// Gross slip (see src/drivers/steady_state.hpp): the sign s of a slip in the direction the
  /// driving torque pushes (-s MMd > 0), else 0; `hold` receives mu W r, what friction holds
  /// with the mean normal force W (the largest slip coefficient times W r) [N m].
  int pushed_slip(Phase phase, const Vector& x, double* hold) const;
  /// How fast such a slip spins the drum up: -s (phi'(x) - phi'(x_before)) / periods, > 0 when
  /// phi' grows in the direction that makes the slip of sign s faster (13) [rad/s per period].
  static double spin_up(const Vector& x, const Vector& x_before, int s, int periods) {
    return -s * (x[kSpin] - x_before[kSpin]) / periods;
  }

 private:
  const Model& model_;
  double baumgarte_;
  double f5_bottom_;  // f5 (50) at delta = 0 [-]
};

}  // namespace oscidrum::detail
