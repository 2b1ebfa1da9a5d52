// oscidrum/roller.hpp: the roller types, each a component that owns its state layout, its phases
// and their equations (docs/architecture.md, "The roller as a component"). The flow, the events,
// the variational equations (monodromy, saltation), shooting, the steady-state search and the
// sampling are written once against a roller type R (BasicFlow<R> in oscidrum/flow.hpp and the
// drivers in src/drivers/); a roller supplies its dynamics in src/roller/ (the specialisation
// Dynamics<R>, internal) and its public face here: the state it integrates.
#pragma once

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

}  // namespace oscidrum
