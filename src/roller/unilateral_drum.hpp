// Internal: the oscillation drum with unilateral contact as a roller component
// (contact.unilateral, docs/model.md section 13; the members the engine uses are listed in
// src/roller/dynamics.hpp). In contact it is the paper's drum (its Dynamics on the first eight
// components, the gap and its rate held at 0); N reaching 0 is a lift-off into the flight phase
// (src/equations/flight_phase.hpp), and the gap closing a landing, where the friction law decides
// stick or slip.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "equations/flight_phase.hpp"
#include "roller/oscillation_drum.hpp"

namespace oscidrum::detail {

template <>
class Dynamics<UnilateralDrum> {
 public:
  using Drum = Dynamics<OscillationDrum>;
  static constexpr int kStates = UnilateralDrum::kStates;
  static constexpr int kEvents = Drum::kEvents;
  static constexpr int kContactEvent =
      Drum::kContactEvent;  ///< in contact phases (flight: a constant 1)
  /// All but phi (index 3), which is cyclic.
  static constexpr std::array<int, 9> kPeriodic = {0, 1, 2, 4, 5, 6, 7, 8, 9};
  static constexpr int kSpin = flight_index::kDPhi;
  /// Flight's event functions: the gap (landing) and the chart's limit.
  static constexpr int kEventGap = 0;
  static constexpr int kEventClearance = 1;
  using Vector = std::array<double, kStates>;
  using Matrix = Eigen::Matrix<double, kStates, kStates>;
  using EventValues = Drum::EventValues;

  struct Switch {
    EventKind kind = EventKind::stick_to_slip;
    Phase to = Phase::stick;
    Vector after{};
    std::array<bool, kEvents> fresh{};
    bool terminal = false;
    FlowStop stop = FlowStop::contact_lost;
    std::string message;
    bool consistent = true;
    bool reversal = false;
    double speed = 0.0;  ///< a landing's approach speed -g' (Event::speed) [m/s]
  };

  Dynamics(const Model& model, double baumgarte);
  const Model& model() const { return drum_.model(); }

  // ---- the flow -------------------------------------------------------------------------------
  void rhs(Phase phase, double t, const Vector& x, Vector& dxdt) const;
  EventValues events(Phase phase, const Vector& x, double* N = nullptr) const;
  Switch apply(Phase phase, int which, double t, const Vector& x) const;
  bool invalid(Phase phase, const Vector& x, double t, std::string* why, FlowStop* stop) const {
    return drum_.invalid(phase == Phase::flight ? Phase::stick : phase, contact_part(x), t, why,
                         stop);
  }
  void track(Phase phase, const Vector& x, double N, FlowCounters& counters) const {
    if (phase != Phase::flight) drum_.track(phase, contact_part(x), N, counters);
  }
  Vector initial_state() const { return embed(drum_.initial_state()); }
  Phase initial_phase() const { return drum_.initial_phase(); }
  Phase flow_phase(Phase phase) const {
    return phase == Phase::flight ? phase : drum_.flow_phase(phase);
  }

  // ---- variational equations ------------------------------------------------------------------
  Matrix jacobian(Phase phase, double t, const Vector& x) const;
  SaltationMatrix<kStates> saltation(const Event& event, const Vector& before,
                                     const Vector& after) const;

  // ---- shooting -------------------------------------------------------------------------------
  /// Contact: the drum's projection, g = g' = 0; flight: the soil's relaxation x_A' =
  /// -(ksh/csh) x_A, s_A' = -(ksv/csv) s_A.
  Vector consistent(Vector z, Phase phase) const;
  std::optional<Matrix> section_jacobian(const Vector& z, Phase phase) const;
  static double cyclic_drift(const Vector& end, const Vector& start) { return end[3] - start[3]; }

  // ---- sampling -------------------------------------------------------------------------------
  void sample(double t, const Vector& x, Phase phase, Samples& samples) const;
  Phase apparent(Phase phase, const Vector& x) const {
    return phase == Phase::flight ? phase : drum_.apparent(phase, contact_part(x));
  }
  bool apparent_varies(Phase phase) const {
    return phase != Phase::flight && drum_.apparent_varies(phase);
  }
  /// The drum's quantities in contact (gap 0); in flight x_M'', z_M'' from (19), (20) with
  /// N = T = 0, delta, phi, T/N = 0, no friction power, the gap, F_v = 0 and z_M.
  std::array<double, 9> quantities(double t, const Vector& x, Phase phase) const;
  static Vector sampled_state(const Samples& s, std::size_t j) {
    return {s.delta[j],  s.x_A[j],  s.s_A[j],  s.phi[j],  s.gap[j],
            s.ddelta[j], s.dx_A[j], s.ds_A[j], s.dphi[j], s.dgap[j]};
  }

  // ---- the steady-state search ----------------------------------------------------------------
  int pushed_slip(Phase phase, const Vector& x, double* hold) const {
    if (phase == Phase::flight) {
      *hold = 0.0;
      return 0;
    }
    return drum_.pushed_slip(phase, contact_part(x), hold);
  }
  static double spin_up(const Vector& x, const Vector& x_before, int s, int periods) {
    return -s * (x[kSpin] - x_before[kSpin]) / periods;
  }

  /// The drum's eight components of a unilateral state, and back (g = g' = 0).
  static Drum::Vector contact_part(const Vector& x) {
    return {x[0], x[1], x[2], x[3], x[5], x[6], x[7], x[8]};
  }
  static Vector embed(const Drum::Vector& q) {
    return {q[0], q[1], q[2], q[3], 0.0, q[4], q[5], q[6], q[7], 0.0};
  }
  /// How contact resumes at a landing from x (g = 0): the friction law's decision, docs/model.md
  /// section 13. `s` receives the slip's sign.
  Landing landing(const Vector& x, Phase* to, int* s, bool* consistent) const;

 private:
  void flight_rhs(double t, const Vector& x, Vector& dxdt) const;

  Drum drum_;
  double gap_scale_;  ///< the static soil deflection W / (ksv + kd), the gap event's unit [m]
};

}  // namespace oscidrum::detail
