// Internal: the equations of motion with the kinematics already evaluated, so that one
// right-hand-side evaluation computes (15)-(16), (46)-(50) once.
#pragma once

#include "oscidrum/model.hpp"

namespace oscidrum::detail {

/// The accelerations of stick (30)-(32) and slip (34), (36), (38), (53) with the moment
/// MM = Model::torque(t), (5)-(6), already evaluated (the sampling reports it in its own column).
Accelerations stick_accelerations(const Model& model, double t, const State& q, const Kinematics& k,
                                  double MM);
Accelerations slip_accelerations(const Model& model, double t, const State& q, int s,
                                 double baumgarte, const Kinematics& k, double MM);
inline Accelerations stick_accelerations(const Model& model, double t, const State& q,
                                         const Kinematics& k) {
  return stick_accelerations(model, t, q, k, model.torque(t));
}
inline Accelerations slip_accelerations(const Model& model, double t, const State& q, int s,
                                        double baumgarte, const Kinematics& k) {
  return slip_accelerations(model, t, q, s, baumgarte, k, model.torque(t));
}

/// The slip system's determinant over its value at delta = 0, for the slip coefficient m:
/// D = cos^2 + (csv/csh) sin^2 + m sin cos (csv/csh - 1). The system (34), (38), (53) has the
/// determinant -m^3 r f5 D (with f3~ = 0, (37), and f1 fmu1 - f3 fmu2 = r f5, (33), (35)), so
/// the slip accelerations grow as 1/D and do not exist at D = 0 (docs/model.md section 6).
double slip_determinant(const Model& model, const Kinematics& k, double m);

/// accelerations(), drum_motion(), contact_forces() and slip_velocity() (model.hpp) on kinematics
/// evaluated once for q.delta (the sampling of the output reads all four at every sample).
Accelerations accelerations(const Model& model, double t, const State& q, Phase phase,
                            double baumgarte, const Kinematics& k, double MM);
inline Accelerations accelerations(const Model& model, double t, const State& q, Phase phase,
                                   double baumgarte, const Kinematics& k) {
  return accelerations(model, t, q, phase, baumgarte, k, model.torque(t));
}
DrumMotion drum_motion(const State& q, const Accelerations& a, const Kinematics& k);
ContactForces contact_forces(const Model& model, const State& q, const Kinematics& k);
double slip_velocity(const Model& model, const State& q, const Kinematics& k);

}  // namespace oscidrum::detail
