// The event functions of the hybrid flow (src/flow/event_functions.hpp).
#include "flow/event_functions.hpp"

namespace oscidrum {

EventValues event_values(const Model& model, Phase phase, const State& q, double* N) {
  const ContactForces f = contact_forces(model, q);
  if (N != nullptr) *N = f.N;
  const double W = model.W();
  EventValues e{1.0, 1.0, f.N / W};
  // The friction law decides which switches exist: the cone in stick (none without a limit), the
  // end of slip in a slip phase (none without friction, and none in the smooth phase of a
  // regularised law, which has no stick).
  if (phase == Phase::stick) {
    if (model.friction_phases() == FrictionPhases::stick_slip) {
      e[kEventConeNegative] = (model.cone() * f.N - f.T) / W;
      e[kEventConePositive] = (model.cone() * f.N + f.T) / W;
    }
  } else if (phase != Phase::smooth && model.cone() > 0.0) {
    const double v_scale = model.r() * model.nu() * 1e-3;  // 1 mrad amplitude at nu
    e[kEventSlipVelocity] = static_cast<int>(phase) * slip_velocity(model, q) / v_scale;
  }
  return e;
}

}  // namespace oscidrum
