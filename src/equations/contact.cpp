// The contact forces (24)-(26), the slip velocity (13), the drum-centre motion (14), (17), (18)
// and the accelerations of a phase (oscidrum/model.hpp): what every phase of the drum's
// equations shares.
#include <cmath>

#include "equations/equations.hpp"
#include "equations/phase_equations.hpp"
#include "oscidrum/model.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {

namespace {
// Soil subsystem (24), (25), solved for N (26) and T (equations/phase_equations.hpp).
ContactForces contact_forces_at(const Model& model, const State& q, double s, double c) {
  ContactForces f;
  detail::soil_contact_forces(model, q, s, c, f.N, f.T);
  return f;
}
}  // namespace

ContactForces detail::contact_forces(const Model& model, const State& q, const Kinematics& k) {
  return contact_forces_at(model, q, k.sin_delta, k.cos_delta);
}

ContactForces contact_forces(const Model& model, const State& q) {
  const auto [s, c] = detail::sincos_small(q.delta);
  return contact_forces_at(model, q, s, c);
}

double detail::slip_velocity(const Model& model, const State& q, const Kinematics& k) {
  return slip_velocity_of<double>(model, q, k);  // (13)
}

double slip_velocity(const Model& model, const State& q) {
  return detail::slip_velocity(model, q, kinematics(model.geometry(), q.delta));
}

DrumMotion detail::drum_motion(const State& q, const Accelerations& a, const Kinematics& k) {
  DrumMotion d;
  drum_motion_of(q, a, k, d);  // (14), (17), (18)
  return d;
}

DrumMotion drum_motion(const Model& model, const State& q, const Accelerations& a) {
  return detail::drum_motion(q, a, kinematics(model.geometry(), q.delta));
}

Accelerations detail::accelerations(const Model& model, double t, const State& q, Phase phase,
                                    double baumgarte, const Kinematics& k, double MM) {
  if (phase == Phase::stick) return stick_accelerations(model, t, q, k, MM);
  return slip_accelerations(model, t, q, slip_sign(phase), baumgarte, k, MM);
}

Accelerations accelerations(const Model& model, double t, const State& q, Phase phase,
                            double baumgarte) {
  return detail::accelerations(model, t, q, phase, baumgarte,
                               kinematics(model.geometry(), q.delta));
}

}  // namespace oscidrum
