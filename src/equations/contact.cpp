// The contact forces (24)-(26), the slip velocity (13), the drum-centre motion (14), (17), (18)
// and the accelerations of a phase (oscidrum/model.hpp): what every phase of the drum's
// equations shares.
#include <cmath>

#include "equations/equations.hpp"
#include "oscidrum/model.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {

namespace {
// Soil subsystem (24), (25), solved for N (26) and T. The soil is massless, so these hold in
// every phase and equal (21), (22). s, c: sin and cos of delta.
ContactForces soil_contact_forces(const Model& model, const State& q, double s, double c) {
  const double Fh = model.ksh() * q.x_A + model.csh() * q.dx_A;
  const double Fv = model.ksv() * q.s_A + model.csv() * q.ds_A;
  return {Fh * s + Fv * c, Fv * s - Fh * c};
}
}  // namespace

ContactForces detail::contact_forces(const Model& model, const State& q, const Kinematics& k) {
  return soil_contact_forces(model, q, k.sin_delta, k.cos_delta);
}

ContactForces contact_forces(const Model& model, const State& q) {
  const auto [s, c] = detail::sincos_small(q.delta);
  return soil_contact_forces(model, q, s, c);
}

double detail::slip_velocity(const Model& model, const State& q, const Kinematics& k) {
  return model.r() * k.f5 * q.ddelta - model.r() * q.dphi;  // (13)
}

double slip_velocity(const Model& model, const State& q) {
  return detail::slip_velocity(model, q, kinematics(model.geometry(), q.delta));
}

DrumMotion detail::drum_motion(const State& q, const Accelerations& a, const Kinematics& k) {
  DrumMotion d;
  d.x_M = k.x_roll + q.x_A;  // (14)
  d.z_M = k.z_roll + q.s_A;
  d.dx_M = k.f1 * q.ddelta + q.dx_A;  // (17)
  d.dz_M = k.f3 * q.ddelta + q.ds_A;
  d.ddx_M = k.f1 * a.delta + k.f2 * q.ddelta * q.ddelta + a.x_A;  // (18)
  d.ddz_M = k.f3 * a.delta + k.f4 * q.ddelta * q.ddelta + a.s_A;
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
