// The hybrid flow (oscidrum/flow.hpp): the options, the names of its stops and the start phase.
// The flow itself is a template on the roller type (src/flow/hybrid_flow.hpp), instantiated for
// each roller in src/roller/engine.cpp.
#include "oscidrum/flow.hpp"

namespace oscidrum {

Status status_of(FlowStop stop) {
  switch (stop) {
    case FlowStop::contact_lost:
    case FlowStop::inconsistent_state:
      return Status::contact_lost;
    case FlowStop::chattering:
      return Status::chattering;
    case FlowStop::non_finite:
      return Status::non_finite;
    case FlowStop::invalid_geometry:
      return Status::invalid_geometry;
    case FlowStop::budget_exceeded:
      return Status::budget_exceeded;
    case FlowStop::reached:
    case FlowStop::observer:
    case FlowStop::cancelled:
      break;
  }
  return Status::cancelled;
}

FlowOptions FlowOptions::from(const Model& model) {
  const Numerics& n = model.parameters().numerics;
  FlowOptions o;
  o.rtol = n.rtol;
  o.atol = n.atol;
  o.baumgarte = n.slip_constraint_rate > 0 ? n.slip_constraint_rate : 2.0 * model.nu();
  o.max_step = model.period() / 16.0;
  o.max_switches_per_period = n.max_switches_per_period;
  o.max_steps_per_period = n.max_steps_per_period;
  return o;
}

Phase initial_phase(const Model& model) { return initial_phase(model.friction()); }

}  // namespace oscidrum
