// Internal: the equations of motion with the kinematics already evaluated, so that one
// right-hand-side evaluation computes (15)-(16), (46)-(50) once.
#pragma once

#include "oscidrum/model.hpp"

namespace oscidrum::detail {

Accelerations stick_accelerations(const Model& model, double t, const State& q,
                                  const Kinematics& k);
Accelerations slip_accelerations(const Model& model, double t, const State& q, int s,
                                 double baumgarte, const Kinematics& k);

}  // namespace oscidrum::detail
