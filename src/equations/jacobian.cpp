// Analytic Jacobians of the stick (52) and slip (55) right-hand sides, gradients of the event
// functions, jump maps at slip ends and saltation matrices (docs/periodic.md).
#include "equations/jacobian.hpp"

#include <Eigen/LU>  // inverse() of fixed-size matrices
#include <cmath>

#include "equations/equations.hpp"
#include "equations/slip_general.hpp"
#include "util/small_angle.hpp"

namespace oscidrum::detail {

Vec8 to_vec8(const State& q) {
  Vec8 y;
  y << q.delta, q.x_A, q.s_A, q.phi, q.ddelta, q.dx_A, q.ds_A, q.dphi;
  return y;
}

State to_state(const Vec8& y) { return {y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7]}; }

Vec8 phase_rhs(const Model& model, double t, const State& q, Phase phase, double baumgarte) {
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const Accelerations a = phase == Phase::stick
                              ? stick_accelerations(model, t, q, k)
                              : slip_accelerations(model, t, q, slip_sign(phase), baumgarte, k);
  Vec8 f;
  // In stick phi follows the rolling condition (12): phi' = f5 delta'.
  f << q.ddelta, q.dx_A, q.ds_A, phase == Phase::stick ? k.f5 * q.ddelta : q.dphi, a.delta, a.x_A,
      a.s_A, a.phi;
  return f;
}

namespace {

// Indices into y.
enum : int { D = 0, XA = 1, SA = 2, PHI = 3, DD = 4, DXA = 5, DSA = 6, DPHI = 7 };

Mat8 stick_jacobian(const Model& model, double t, const State& q) {
  const double m = model.m(), I = model.I(), r = model.r();
  const double kd = model.kd(), cd = model.cd();
  const CentreLoad L = model.centre_load(t);  // W + F_z(t), F_x(t) (docs/model.md section 14)
  const double W = L.z;
  const double ksh = model.ksh(), ksv = model.ksv(), csh = model.csh(), csv = model.csv();
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const KinematicsRates kr = kinematics_rates(model.geometry(), q.delta);
  const Accelerations a = stick_accelerations(model, t, q, k);
  const double sn = k.sin_delta, cs = k.cos_delta, dd = q.ddelta, dd2 = dd * dd;
  const double zs = k.z_roll - model.z_ref();
  const double df6 = kr.df6;
  const double df1_bar = k.f2_bar - k.f3_tilde;
  const double df2_bar = kr.df2 * cs - kr.df4 * sn - k.f4_tilde;

  // A: coefficients of (delta'', x_A'', s_A'') in (30), (31), (32).
  Eigen::Matrix3d A;
  A << m * k.f1, m, 0.0,  //
      m * k.f3, 0.0, m,   //
      k.f5 * I / r + m * k.f1_bar, m * cs, -m * sn;
  // dR: partial derivatives of the residuals A a - b with respect to y at fixed a.
  Eigen::Matrix<double, 3, 8> dR = Eigen::Matrix<double, 3, 8>::Zero();
  // (30)
  dR(0, D) = m * k.f2 * a.delta + m * kr.df2 * dd2 + cd * k.f2 * dd + kd * k.f1;
  dR(0, XA) = ksh + kd;
  dR(0, DD) = 2.0 * m * k.f2 * dd + cd * k.f1;
  dR(0, DXA) = csh + cd;
  // (31)
  dR(1, D) = m * k.f4 * a.delta + m * kr.df4 * dd2 + cd * k.f4 * dd + kd * k.f3;
  dR(1, SA) = ksv + kd;
  dR(1, DD) = 2.0 * m * k.f4 * dd + cd * k.f3;
  dR(1, DSA) = csv + cd;
  // (32)
  dR(2, D) = (k.f6 * I / r + m * df1_bar) * a.delta - m * sn * a.x_A - m * cs * a.s_A +
             (df6 * I / (m * r) + df2_bar) * m * dd2 +
             cd * (df1_bar * dd - q.dx_A * sn - q.ds_A * cs) +
             kd * (k.f1 * cs - (k.x_roll + q.x_A) * sn - k.f3 * sn - (zs + q.s_A) * cs) + W * cs +
             L.x * sn;
  dR(2, XA) = kd * cs;
  dR(2, SA) = -kd * sn;
  dR(2, DD) = 2.0 * (k.f6 * I / (m * r) + k.f2_bar) * m * dd + cd * k.f1_bar;
  dR(2, DXA) = cd * cs;
  dR(2, DSA) = -cd * sn;

  // Fixed-size closed-form inverse (the system is well conditioned, cond(A) <~ 1e4): Eigen's
  // LU solve with 8 right-hand sides takes its general blocked path, several times slower.
  const Eigen::Matrix<double, 3, 8> da = -A.inverse().lazyProduct(dR);
  Mat8 J = Mat8::Zero();
  J(D, DD) = 1.0;
  J(XA, DXA) = 1.0;
  J(SA, DSA) = 1.0;
  J(PHI, D) = k.f6 * dd;  // phi' = f5 delta' (12)
  J(PHI, DD) = k.f5;
  J.row(DD) = da.row(0);
  J.row(DXA) = da.row(1);
  J.row(DSA) = da.row(2);
  // phi'' = f5 delta'' + f6 delta'^2 (12)
  J.row(DPHI) = k.f5 * da.row(0);
  J(DPHI, D) += k.f6 * a.delta + df6 * dd2;
  J(DPHI, DD) += 2.0 * k.f6 * dd;
  return J;
}

Mat8 slip_jacobian(const Model& model, double t, const State& q, int s, double beta) {
  const double m = model.m(), I = model.I(), r = model.r();
  const double kd = model.kd(), cd = model.cd();
  const CentreLoad L = model.centre_load(t);  // W + F_z(t), F_x(t) (docs/model.md section 14)
  const double W = L.z;
  const double ksh = model.ksh(), ksv = model.ksv(), csh = model.csh(), csv = model.csv();
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const KinematicsRates kr = kinematics_rates(model.geometry(), q.delta);
  const Accelerations a = slip_accelerations(model, t, q, s, beta, k);
  const double sn = k.sin_delta, cs = k.cos_delta, dd = q.ddelta, dd2 = dd * dd;
  // The law's coefficient at this state (s mu for Coulomb's law; its derivative is zero here).
  const double smu = slip_coefficient(model.friction(), s, detail::slip_velocity(model, q, k)).m;
  const double fmu1 = cs - smu * sn, fmu2 = sn + smu * cs;  // (35)
  const double dfmu1 = -fmu2, dfmu2 = fmu1;
  const double xs = k.x_roll + q.x_A, zs = k.z_roll + q.s_A - model.z_ref();
  const double zrs = k.z_roll - model.z_ref();
  const double df3_tilde = k.f4_tilde + k.f1_bar;
  const double df4_tilde = kr.df2 * sn + kr.df4 * cs + k.f2_bar;
  const double c34 = k.f1 * fmu1 - k.f3 * fmu2;
  const double dc34 = k.f2 * fmu1 + k.f1 * dfmu1 - k.f4 * fmu2 - k.f3 * dfmu2;
  const double e34 = k.f2 * fmu1 - k.f4 * fmu2;
  const double de34 = kr.df2 * fmu1 + k.f2 * dfmu1 - kr.df4 * fmu2 - k.f4 * dfmu2;
  const double Fh = csh * q.dx_A + ksh * q.x_A, Fv = csv * q.ds_A + ksv * q.s_A;
  const double mc = m / csh;

  // A: coefficients of (delta'', x_A'', s_A'', phi'') in (34), (38), (53), (36). Only (36) holds
  // phi'': A is block lower triangular, [A3 0; a4^T I/r].
  Eigen::Matrix3d A3;
  A3 << m * c34, m * fmu1, -m * fmu2,  //
      m * k.f3_tilde, m * sn, m * cs,  //
      0.0, m * fmu1, -(csv / csh) * m * fmu2;
  const Eigen::RowVector3d a4(smu * m * k.f3_tilde, smu * m * sn, smu * m * cs);
  Eigen::Matrix<double, 4, 8> dR = Eigen::Matrix<double, 4, 8>::Zero();
  // (34)
  dR(0, D) = m * dc34 * a.delta + m * dfmu1 * a.x_A - m * dfmu2 * a.s_A + de34 * m * dd2 +
             cd * (dc34 * dd + dfmu1 * q.dx_A - dfmu2 * q.ds_A) +
             kd * (dfmu1 * xs + fmu1 * k.f1 - dfmu2 * zs - fmu2 * k.f3) + dfmu2 * W - dfmu1 * L.x;
  dR(0, XA) = kd * fmu1;
  dR(0, SA) = -kd * fmu2;
  dR(0, DD) = 2.0 * e34 * m * dd + cd * c34;
  dR(0, DXA) = cd * fmu1;
  dR(0, DSA) = -cd * fmu2;
  // (38)
  dR(1, D) = m * df3_tilde * a.delta + m * cs * a.x_A - m * sn * a.s_A + cd * df3_tilde * dd +
             (csh + cd) * cs * q.dx_A - (csv + cd) * sn * q.ds_A + m * df4_tilde * dd2 +
             (ksh + kd) * cs * q.x_A - (ksv + kd) * sn * q.s_A +
             kd * (k.f1 * sn + k.x_roll * cs + k.f3 * cs - zrs * sn) + W * sn - L.x * cs;
  dR(1, XA) = (ksh + kd) * sn;
  dR(1, SA) = (ksv + kd) * cs;
  dR(1, DD) = cd * k.f3_tilde + 2.0 * m * k.f4_tilde * dd;
  dR(1, DXA) = (csh + cd) * sn;
  dR(1, DSA) = (csv + cd) * cs;
  // (53) with the Baumgarte term beta (m/csh) (39)
  dR(2, D) = m * dfmu1 * a.x_A - (csv / csh) * m * dfmu2 * a.s_A +
             mc * (dfmu1 * (ksh * q.dx_A - Fv * dd) - dfmu2 * (ksv * q.ds_A + Fh * dd)) +
             beta * mc * (dfmu1 * Fh - dfmu2 * Fv);
  dR(2, XA) = mc * (-fmu2 * ksh * dd) + beta * mc * fmu1 * ksh;
  dR(2, SA) = mc * (-fmu1 * ksv * dd) - beta * mc * fmu2 * ksv;
  dR(2, DD) = mc * (-fmu1 * Fv - fmu2 * Fh);
  dR(2, DXA) = mc * (fmu1 * ksh - fmu2 * csh * dd) + beta * mc * fmu1 * csh;
  dR(2, DSA) = mc * (-fmu1 * csv * dd - fmu2 * ksv) - beta * mc * fmu2 * csv;
  // (36)
  dR(3, D) = smu * m * (df3_tilde * a.delta + cs * a.x_A - sn * a.s_A) -
             smu * (-W * sn - m * df4_tilde * dd2 - df3_tilde * cd * dd -
                    cd * (cs * q.dx_A - sn * q.ds_A) -
                    kd * (k.f1 * sn + xs * cs + k.f3 * cs - zs * sn) + L.x * cs);
  dR(3, XA) = smu * kd * sn;
  dR(3, SA) = smu * kd * cs;
  dR(3, DD) = smu * (2.0 * m * k.f4_tilde * dd + k.f3_tilde * cd);
  dR(3, DXA) = smu * cd * sn;
  dR(3, DSA) = smu * cd * cs;

  // A da = -dR by blocks: A3 da_top = -dR_top (the closed-form inverse, as in the stick
  // Jacobian), then (36)'s row, a4^T da_top + (I/r) da_phi = -dR_phi.
  const Eigen::Matrix<double, 3, 8> da = -A3.inverse().lazyProduct(dR.topRows<3>());
  Mat8 J = Mat8::Zero();
  J(D, DD) = 1.0;
  J(XA, DXA) = 1.0;
  J(SA, DSA) = 1.0;
  J(PHI, DPHI) = 1.0;
  J.middleRows<3>(DD) = da;
  J.row(DPHI) = -(r / I) * (dR.row(3) + a4.lazyProduct(da));
  return J;
}

// The slip phase with a velocity-dependent friction coefficient (src/equations/slip_general.hpp):
// the accelerations evaluated on dual numbers seeded with the eight state components give the
// exact Jacobian (checked against finite differences in tests/equations/test_jacobian.cpp).
Mat8 general_slip_jacobian(const Model& model, double t, const State& q, int s, double beta) {
  using Dn = Dual<8>;
  const std::array<double, 8> x = q.to_array();
  std::array<Dn, 8> y;
  for (int i = 0; i < 8; ++i) y[i] = Dn::variable(x[i], i);
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const KinematicsRates kr = kinematics_rates(model.geometry(), q.delta);
  const KinematicsT<Dn> kin = kinematics_t(k, kr, y[D]);
  const Dn v = model.r() * kin.f5 * y[DD] - model.r() * y[DPHI];  // (13)
  const SlipCoefficient c = slip_coefficient(model.friction(), s, v.v);
  const Dn m = Dn::chain(v, c.m, c.dm_dv), m_v = Dn::chain(v, c.dm_dv, c.d2m_dv2);
  const std::array<Dn, 4> a = general_slip_accelerations(model, t, y, kin, m, m_v, beta);
  Mat8 J = Mat8::Zero();
  J(D, DD) = 1.0;
  J(XA, DXA) = 1.0;
  J(SA, DSA) = 1.0;
  J(PHI, DPHI) = 1.0;
  for (int r = 0; r < 4; ++r)
    for (int col = 0; col < 8; ++col) J(DD + r, col) = a[r].d[col];
  return J;
}

}  // namespace

Mat8 phase_jacobian(const Model& model, double t, const State& q, Phase phase, double baumgarte) {
  if (phase == Phase::stick) return stick_jacobian(model, t, q);
  const int s = slip_sign(phase);
  // A friction coefficient that depends on v_rel (the smooth phase, or a slip phase of a law
  // whose coefficient changes here): the general slip equations, differentiated automatically;
  // a constant one (Coulomb): the terms coded by hand below.
  if (phase == Phase::smooth ||
      slip_coefficient(model.friction(), s, slip_velocity(model, q)).dm_dv != 0.0)
    return general_slip_jacobian(model, t, q, s, baumgarte);
  return slip_jacobian(model, t, q, s, baumgarte);
}

double event_value(const Model& model, const State& q, EventFunction h) {
  switch (h) {
    case EventFunction::stick_limit_negative: {
      const ContactForces f = contact_forces(model, q);
      return model.cone() * f.N - f.T;
    }
    case EventFunction::stick_limit_positive: {
      const ContactForces f = contact_forces(model, q);
      return model.cone() * f.N + f.T;
    }
    case EventFunction::slip_velocity:
      return slip_velocity(model, q);
    case EventFunction::normal_force:
      return contact_forces(model, q).N;
  }
  return 0.0;
}

Vec8 event_gradient(const Model& model, const State& q, EventFunction h) {
  const auto [sn, cs] = detail::sincos_small(q.delta);
  const double ksh = model.ksh(), ksv = model.ksv(), csh = model.csh(), csv = model.csv();
  const double Fh = ksh * q.x_A + csh * q.dx_A, Fv = ksv * q.s_A + csv * q.ds_A;
  // N = Fh sin + Fv cos (26), T = Fv sin - Fh cos (24)-(25).
  Vec8 dN = Vec8::Zero(), dT = Vec8::Zero();
  dN[D] = Fh * cs - Fv * sn;
  dN[XA] = ksh * sn;
  dN[SA] = ksv * cs;
  dN[DXA] = csh * sn;
  dN[DSA] = csv * cs;
  dT[D] = Fv * cs + Fh * sn;
  dT[XA] = -ksh * cs;
  dT[SA] = ksv * sn;
  dT[DXA] = -csh * cs;
  dT[DSA] = csv * sn;
  switch (h) {
    case EventFunction::stick_limit_negative:
      return model.cone() * dN - dT;
    case EventFunction::stick_limit_positive:
      return model.cone() * dN + dT;
    case EventFunction::slip_velocity: {
      // v_rel = r f5 delta' - r phi' (13)
      const Kinematics k = kinematics(model.geometry(), q.delta);
      Vec8 g = Vec8::Zero();
      g[D] = model.r() * k.f6 * q.ddelta;
      g[DD] = model.r() * k.f5;
      g[DPHI] = -model.r();
      return g;
    }
    case EventFunction::normal_force:
      return dN;
  }
  return Vec8::Zero();
}

namespace {

// The velocity jump lambda of a reversal or a slip start (event_logic.cpp) and its gradient:
// lambda = -g0 / dg with g0 the residual of (39) under s_new (kinetic mu) and dg = d g0 / d lambda
// along (1, -f1, -f3).
struct Lambda {
  double value = 0.0;
  Vec8 gradient = Vec8::Zero();
  bool defined = false;
};

Lambda reversal_lambda(const Model& model, const State& q, int s_new) {
  const Kinematics k = kinematics(model.geometry(), q.delta);
  const double sn = k.sin_delta, cs = k.cos_delta;
  const double ksh = model.ksh(), ksv = model.ksv(), csh = model.csh(), csv = model.csv();
  const double smu = slip_coefficient(model.friction(), s_new, 0.0).m;  // s_new mu (kinetic)
  const double fmu1 = cs - smu * sn, fmu2 = sn + smu * cs;
  const double Fh = csh * q.dx_A + ksh * q.x_A, Fv = csv * q.ds_A + ksv * q.s_A;
  const double g0 = fmu1 * Fh - fmu2 * Fv;  // (39)
  const double dg = -fmu1 * csh * k.f1 + fmu2 * csv * k.f3;
  Lambda out;
  if (dg == 0.0) return out;
  Vec8 dg0 = Vec8::Zero();
  dg0[D] = -fmu2 * Fh - fmu1 * Fv;
  dg0[XA] = fmu1 * ksh;
  dg0[SA] = -fmu2 * ksv;
  dg0[DXA] = fmu1 * csh;
  dg0[DSA] = -fmu2 * csv;
  const double ddg = fmu2 * csh * k.f1 - fmu1 * csh * k.f2 + fmu1 * csv * k.f3 + fmu2 * csv * k.f4;
  out.value = -g0 / dg;
  out.gradient = -dg0 / dg;
  out.gradient[D] += g0 * ddg / (dg * dg);
  out.defined = true;
  return out;
}

}  // namespace

State jump_map(const Model& model, const State& q_in, bool reset_phi, int coupling_sign) {
  State q = q_in;
  const Kinematics k = kinematics(model.geometry(), q.delta);
  if (reset_phi) q.dphi = k.f5 * q.ddelta;  // (12) at v_rel = 0
  if (coupling_sign == 0) return q;
  const Lambda l = reversal_lambda(model, q, coupling_sign);
  q.ddelta += l.value;
  q.dx_A -= l.value * k.f1;
  q.ds_A -= l.value * k.f3;
  return q;
}

Mat8 jump_jacobian(const Model& model, const State& q, bool reset_phi, int coupling_sign) {
  const Kinematics k = kinematics(model.geometry(), q.delta);
  Mat8 G = Mat8::Identity();
  if (reset_phi) {
    G(DPHI, DPHI) = 0.0;
    G(DPHI, D) = k.f6 * q.ddelta;
    G(DPHI, DD) = k.f5;
  }
  if (coupling_sign == 0) return G;
  const Lambda l = reversal_lambda(model, q, coupling_sign);  // independent of phi'
  G.row(DD) += l.gradient.transpose();
  G.row(DXA) -= k.f1 * l.gradient.transpose();
  G(DXA, D) -= l.value * k.f2;
  G.row(DSA) -= k.f3 * l.gradient.transpose();
  G(DSA, D) -= l.value * k.f4;
  return G;
}

Saltation switch_saltation(const Model& model, double t, const State& q, Phase from, Phase to,
                           double baumgarte, bool jumped, double grazing_tol) {
  const Vec8 f_minus = phase_rhs(model, t, q, from, baumgarte);
  // Stick -> slip: the surface is |T| = mu_static N on the side of the new slip; the state
  // carries over unless the soil's velocities jump (mu_static > mu). Slip end at v_rel = 0:
  // phi' = f5 delta', and for a reversal the jump to the coupling (39) of the new sign.
  const bool slip_start = from == Phase::stick;
  const EventFunction h = !slip_start                  ? EventFunction::slip_velocity
                          : to == Phase::slip_negative ? EventFunction::stick_limit_negative
                                                       : EventFunction::stick_limit_positive;
  const bool reset_phi = !slip_start;
  const int coupling = (jumped && to != Phase::stick) ? static_cast<int>(to) : 0;
  const State qp = jump_map(model, q, reset_phi, coupling);
  const Vec8 f_plus = phase_rhs(model, t, qp, to, baumgarte);
  return saltation(jump_jacobian(model, q, reset_phi, coupling), f_minus, f_plus,
                   event_gradient(model, q, h), 0.0, grazing_tol);
}

}  // namespace oscidrum::detail
