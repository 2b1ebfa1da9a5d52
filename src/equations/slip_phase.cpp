// Slip phase: equations of motion (34), (38), (53) and (36) in the state form (55), and the
// friction coupling (39). The friction coefficient is the law's (oscidrum/friction.hpp): a
// constant s mu solves (55) as the paper does; one that depends on v_rel takes the general system
// of src/equations/slip_general.hpp.
#include <cmath>

#include "equations/equations.hpp"
#include "equations/slip_general.hpp"
#include "oscidrum/model.hpp"

namespace oscidrum {

double slip_constraint_residual(const Model& model, const State& q, int s) {
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const double sd = k.sin_delta, cdl = k.cos_delta;
  const double smu = slip_coefficient(model.friction(), s, detail::slip_velocity(model, q, k)).m;
  const double fmu1 = cdl - smu * sd, fmu2 = sd + smu * cdl;  // (35)
  return fmu1 * (model.csh() * q.dx_A + model.ksh() * q.x_A) -
         fmu2 * (model.csv() * q.ds_A + model.ksv() * q.s_A);  // (39)
}

double detail::slip_determinant(const Model& model, const Kinematics& k, double m) {
  const double sn = k.sin_delta, cs = k.cos_delta, ratio = model.csv() / model.csh();
  return cs * cs + ratio * sn * sn + m * sn * cs * (ratio - 1.0);
}

Accelerations slip_accelerations(const Model& model, double t, const State& q, int s,
                                 double baumgarte) {
  return detail::slip_accelerations(model, t, q, s, baumgarte,
                                    kinematics(model.geometry(), q.delta));
}

Accelerations detail::slip_accelerations(const Model& model, double t, const State& q, int s,
                                         double baumgarte, const Kinematics& k, double MM) {
  const double m = model.m(), I = model.I(), r = model.r();
  const double kd = model.kd(), cd = model.cd();
  // The load on M: W + F_z(t) in place of W, and F_x(t) with kd x_M (docs/model.md section 14).
  const CentreLoad L = model.centre_load(t);
  const double W = L.z;
  const double ksh = model.ksh(), ksv = model.ksv(), csh = model.csh(), csv = model.csv();
  const SlipCoefficient mu = slip_coefficient(model.friction(), s, slip_velocity(model, q, k));
  if (mu.dm_dv != 0.0) {  // a velocity-dependent coefficient: the full 4 x 4 system
    const auto a = general_slip_accelerations(model, t, q.to_array(), kinematics_t(k), mu.m,
                                              mu.dm_dv, baumgarte);
    return {a[0], a[1], a[2], a[3]};
  }
  const double sn = k.sin_delta, cs = k.cos_delta;
  const double dd = q.ddelta, dd2 = dd * dd;
  const double smu = mu.m;                                  // s mu for Coulomb's law
  const double fmu1 = cs - smu * sn, fmu2 = sn + smu * cs;  // (35)
  const double xs = k.x_roll + q.x_A;                       // x_M
  const double zs = k.z_roll + q.s_A - model.z_ref();       // z_M from the suspension reference
  const double z_roll_s = k.z_roll - model.z_ref();

  // (34): m (f1 fmu1 - f3 fmu2) delta'' + m fmu1 x_A'' - m fmu2 s_A'' + h1s = -fmu2 W
  const double c34 = k.f1 * fmu1 - k.f3 * fmu2;
  const double h1s = (k.f2 * fmu1 - k.f4 * fmu2) * m * dd2 +
                     cd * (c34 * dd + fmu1 * q.dx_A - fmu2 * q.ds_A) +
                     kd * (fmu1 * xs - fmu2 * zs) - fmu1 * L.x;
  // (38): m f3~ delta'' + m sin x_A'' + m cos s_A'' + h3s = W cos
  const double h3s = cd * k.f3_tilde * dd + (csh + cd) * sn * q.dx_A + (csv + cd) * cs * q.ds_A +
                     m * k.f4_tilde * dd2 + (ksh + kd) * sn * q.x_A + (ksv + kd) * cs * q.s_A +
                     kd * (k.x_roll * sn + z_roll_s * cs) - L.x * sn;
  // (53): m fmu1 x_A'' - (csv/csh) m fmu2 s_A'' + h4 = 0, the time derivative of (39) times
  // m/csh; with Baumgarte stabilisation d(39)/dt + rate * (39) = 0 so that drift decays.
  const double Fh = csh * q.dx_A + ksh * q.x_A, Fv = csv * q.ds_A + ksv * q.s_A;
  double h4 = (m / csh) * (fmu1 * (ksh * q.dx_A - Fv * dd) - fmu2 * (ksv * q.ds_A + Fh * dd));
  if (baumgarte != 0.0) h4 += (m / csh) * baumgarte * (fmu1 * Fh - fmu2 * Fv);

  // 3x3 system A [delta'', x_A'', s_A'']^T = b by Cramer's rule; A31 = 0 (one division: the
  // determinant's reciprocal, a third of the time of this function went to waiting on three).
  const double A11 = m * c34, A12 = m * fmu1, A13 = -m * fmu2;
  const double A21 = m * k.f3_tilde, A22 = m * sn, A23 = m * cs;
  const double A32 = m * fmu1, A33 = -(csv / csh) * m * fmu2;
  const double b1 = -fmu2 * W - h1s, b2 = W * cs - h3s, b3 = -h4;
  const double det = A11 * (A22 * A33 - A23 * A32) - A12 * (A21 * A33) + A13 * (A21 * A32);
  const double inv_det = 1.0 / det;
  Accelerations a;
  a.delta =
      (b1 * (A22 * A33 - A23 * A32) - A12 * (b2 * A33 - A23 * b3) + A13 * (b2 * A32 - A22 * b3)) *
      inv_det;
  a.x_A = (A11 * (b2 * A33 - A23 * b3) - b1 * (A21 * A33) + A13 * (A21 * b3)) * inv_det;
  a.s_A = (A11 * (A22 * b3 - b2 * A32) - A12 * (A21 * b3) + b1 * (A21 * A32)) * inv_det;

  // (36): s mu m (f3~ delta'' + sin x_A'' + cos s_A'') + (I/r) phi'' + h2s = MM/r
  const double h2s =
      -smu * (W * cs - m * k.f4_tilde * dd2 - k.f3_tilde * cd * dd -
              cd * (sn * q.dx_A + cs * q.ds_A) - kd * (xs * sn + zs * cs) + L.x * sn);
  // phi'' = (MM - r h2s - r s mu m (...)) / I: (36) times r/I, with one division.
  a.phi = (MM - r * (h2s + smu * m * (k.f3_tilde * a.delta + sn * a.x_A + cs * a.s_A))) / I;
  return a;
}

}  // namespace oscidrum
