// Decisions at stick/slip events (docs/model.md section 6).
#include "equations/event_logic.hpp"

#include <cmath>

#include "util/small_angle.hpp"

namespace oscidrum {

double stick_margin_rate(const Model& model, double t, const State& q, int sign_T) {
  const Accelerations a = stick_accelerations(model, t, q);
  const auto [sn, cs] = detail::sincos_small(q.delta);
  const double dd = q.ddelta;
  const double Fh = model.ksh() * q.x_A + model.csh() * q.dx_A;  // right side of (24)
  const double Fv = model.ksv() * q.s_A + model.csv() * q.ds_A;  // right side of (25)
  const double dFh = model.ksh() * q.dx_A + model.csh() * a.x_A;
  const double dFv = model.ksv() * q.ds_A + model.csv() * a.s_A;
  const double dN = dFh * sn + Fh * cs * dd + dFv * cs - Fv * sn * dd;  // d/dt of (26)
  const double dT = dFv * sn + Fv * cs * dd - dFh * cs + Fh * sn * dd;  // d/dt of T
  return model.cone() * dN - sign_T * dT;
}

namespace {

// The law's slip coefficient m of a slip phase of sign s as slip starts or ends (v_rel = 0), for
// the stick/slip laws whose coefficient does not depend on v_rel (s mu, s mu_kinetic).
double kinetic(const Model& model, int s) { return slip_coefficient(model.friction(), s, 0.0).m; }

// The velocity jump that makes the slip coupling (39) hold with sign s and the kinetic
// coefficient: the massless soil's velocities may jump, the drum's may not, so
// (delta', x_A', s_A') += lambda (1, -f1, -f3) keeps x_M', z_M' (17) and phi' continuous. (39) is
// linear in lambda. Returns false if there is no such jump (the coupling does not depend on it).
bool slip_coupling_jump(const Model& model, const Kinematics& k, const State& q, int s,
                        State& out) {
  const double smu = kinetic(model, s);
  const double fmu1 = k.cos_delta - smu * k.sin_delta, fmu2 = k.sin_delta + smu * k.cos_delta;
  const double g0 = slip_constraint_residual(model, q, s);
  const double dg = -fmu1 * model.csh() * k.f1 + fmu2 * model.csv() * k.f3;
  if (dg == 0.0) return false;
  const double lambda = -g0 / dg;
  out = q;
  out.ddelta += lambda;
  out.dx_A -= lambda * k.f1;
  out.ds_A -= lambda * k.f3;
  return true;
}

}  // namespace

SlipStart decide_slip_start(const Model& model, const State& q, int s) {
  SlipStart out;
  out.state = q;
  if (model.cone() == std::abs(kinetic(model, s))) return out;  // T is continuous: no jump
  // The tangential force drops from mu_static N to mu N: the soil's velocities jump so that (39)
  // holds with the kinetic coefficient, and the drum starts slipping in direction s.
  State r;
  if (slip_coupling_jump(model, kinematics(model.geometry(), q.delta), q, s, r) &&
      s * slip_velocity(model, r) > 0.0) {
    out.state = r;
    return out;
  }
  out.consistent = false;  // no consistent jump: slip starts unchanged, (39) is pulled back
  return out;
}

SlipEnd decide_slip_end(const Model& model, double t, const State& q_in, int s) {
  SlipEnd out;
  State q = q_in;
  const Kinematics k = kinematics(model.geometry(), q.delta);
  // At v_rel = 0 the rolling relation phi' = f5 delta' (12) holds; make it exact.
  q.dphi = k.f5 * q.ddelta;
  out.state = q;
  // With a static coefficient above the kinetic one, |T| = mu N < mu_static N: stick holds.
  if (model.cone() > std::abs(kinetic(model, s))) return out;
  if (stick_margin_rate(model, t, q, -s) >= 0.0) return out;

  // Reversal to s_new = -s, if the jump that satisfies (39) with s_new gives v_rel that sign.
  const int s_new = -s;
  State r;
  if (slip_coupling_jump(model, k, q, s_new, r) && s_new * slip_velocity(model, r) > 0.0) {
    out.stick = false;
    out.state = r;
    return out;
  }
  out.consistent = false;  // neither is consistent: take stick, the cone event will follow
  return out;
}

}  // namespace oscidrum
