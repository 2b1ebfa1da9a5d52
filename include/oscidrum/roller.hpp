// oscidrum/roller.hpp: the roller types, each a component that owns its state layout, its phases
// and their equations (docs/architecture.md, "The roller as a component"). The flow, the events,
// the variational equations (monodromy, saltation), shooting, the steady-state search and the
// sampling are written once against a roller type R (BasicFlow<R> in oscidrum/flow.hpp and the
// drivers in src/drivers/); a roller supplies its dynamics in src/roller/ (the specialisation
// Dynamics<R>, internal) and its public face here: the state it integrates.
#pragma once

#include <array>

#include "oscidrum/state.hpp"

namespace oscidrum {

/// The paper's oscillation drum: a rigid drum excited by a sinusoidal torque plus a driving
/// torque, rolling (stick) or slipping in its trough on Kelvin-Voigt soil; state (54)
/// q = (delta, x_A, s_A, phi, delta', x_A', s_A', phi'), phases stick, slip+, slip- (and the
/// smooth phase of a regularised friction law).
struct OscillationDrum {
  using State = oscidrum::State;
  static constexpr int kStates = 8;  ///< the components of State::to_array()
  static constexpr const char* name = "oscillation";
};

/// The state of the oscillation drum whose contact can open (contact.unilateral): the drum's (54)
/// plus the gap g between drum and trough along the normal at the trough's nearest point, and its
/// rate. In contact g = g' = 0 and the rest is the drum's state; in flight (docs/model.md
/// section 13) delta is the angle of the trough's point nearest to the drum, x_A and s_A relax
/// (x_A' = -(ksh/csh) x_A, s_A' = -(ksv/csv) s_A) and g > 0.
struct UnilateralState {
  double delta = 0.0;   ///< position angle of the drum (of its nearest trough point) [rad]
  double x_A = 0.0;     ///< horizontal displacement of the trough (soil point A) [m]
  double s_A = 0.0;     ///< vertical displacement of the trough, down positive [m]
  double phi = 0.0;     ///< total drum rotation [rad]
  double gap = 0.0;     ///< gap between drum and trough (0 in contact) [m]
  double ddelta = 0.0;  ///< delta' [rad/s]
  double dx_A = 0.0;    ///< x_A' [m/s]
  double ds_A = 0.0;    ///< s_A' [m/s]
  double dphi = 0.0;    ///< phi' [rad/s]
  double dgap = 0.0;    ///< g' [m/s]

  std::array<double, 10> to_array() const {
    return {delta, x_A, s_A, phi, gap, ddelta, dx_A, ds_A, dphi, dgap};
  }
  static UnilateralState from_array(const std::array<double, 10>& q) {
    return {q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9]};
  }
  /// The drum's state (54) in contact (gap and its rate left out).
  State contact() const { return {delta, x_A, s_A, phi, ddelta, dx_A, ds_A, dphi}; }
};

/// The oscillation drum with unilateral contact (contact.unilateral = true): the drum may lift
/// off the trough (Phase::flight) and land again; in contact it is the paper's drum.
struct UnilateralDrum {
  using State = UnilateralState;
  static constexpr int kStates = 10;  ///< the components of State::to_array()
  static constexpr const char* name = "oscillation, unilateral contact";
};

}  // namespace oscidrum
