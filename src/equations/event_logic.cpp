// Decisions at stick/slip events (MODEL.md section 6).
#include "equations/event_logic.hpp"

#include <cmath>

namespace oscidrum {

double stick_margin_rate(const Model& model, double t, const State& q, int sign_T) {
  const Accelerations a = stick_accelerations(model, t, q);
  const double sn = std::sin(q.delta), cs = std::cos(q.delta), dd = q.ddelta;
  const double Fh = model.ksh() * q.x_A + model.csh() * q.dx_A;  // right side of (24)
  const double Fv = model.ksv() * q.s_A + model.csv() * q.ds_A;  // right side of (25)
  const double dFh = model.ksh() * q.dx_A + model.csh() * a.x_A;
  const double dFv = model.ksv() * q.ds_A + model.csv() * a.s_A;
  const double dN = dFh * sn + Fh * cs * dd + dFv * cs - Fv * sn * dd;  // d/dt of (26)
  const double dT = dFv * sn + Fv * cs * dd - dFh * cs + Fh * sn * dd;  // d/dt of T
  return model.mu() * dN - sign_T * dT;
}

SlipEnd decide_slip_end(const Model& model, double t, const State& q_in, int s) {
  SlipEnd out;
  State q = q_in;
  const Kinematics k = kinematics(model.geometry(), q.delta);
  // At v_rel = 0 the rolling relation phi' = f5 delta' (12) holds; make it exact.
  q.dphi = k.f5 * q.ddelta;
  out.state = q;
  if (stick_margin_rate(model, t, q, -s) >= 0.0) return out;

  // Reversal to s_new = -s: solve (39) with s_new for lambda (it is linear in lambda).
  const int s_new = -s;
  const double smu = s_new * model.mu();
  const double fmu1 = k.cos_delta - smu * k.sin_delta, fmu2 = k.sin_delta + smu * k.cos_delta;
  const double g0 = slip_constraint_residual(model, q, s_new);
  const double dg = -fmu1 * model.csh() * k.f1 + fmu2 * model.csv() * k.f3;
  if (dg != 0.0) {
    const double lambda = -g0 / dg;
    State r = q;
    r.ddelta += lambda;
    r.dx_A -= lambda * k.f1;
    r.ds_A -= lambda * k.f3;
    if (s_new * slip_velocity(model, r) > 0.0) {
      out.stick = false;
      out.state = r;
      return out;
    }
  }
  out.consistent = false;  // neither is consistent: take stick, the cone event will follow
  return out;
}

}  // namespace oscidrum
