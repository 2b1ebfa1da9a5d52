// Internal: the equations of motion with the kinematics already evaluated, so that one
// right-hand-side evaluation computes (15)-(16), (46)-(50) once.
#pragma once

#include "oscidrum/model.hpp"

namespace oscidrum::detail {

Accelerations stick_accelerations(const Model& model, double t, const State& q,
                                  const Kinematics& k);
Accelerations slip_accelerations(const Model& model, double t, const State& q, int s,
                                 double baumgarte, const Kinematics& k);

/// accelerations(), drum_motion(), contact_forces() and slip_velocity() (model.hpp) on kinematics
/// evaluated once for q.delta (the sampling of the output reads all four at every sample).
Accelerations accelerations(const Model& model, double t, const State& q, Phase phase,
                            double baumgarte, const Kinematics& k);
DrumMotion drum_motion(const State& q, const Accelerations& a, const Kinematics& k);
ContactForces contact_forces(const Model& model, const State& q, const Kinematics& k);
double slip_velocity(const Model& model, const State& q, const Kinematics& k);

}  // namespace oscidrum::detail
