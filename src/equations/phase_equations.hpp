// Internal: the equations of motion of stick and of Coulomb slip, the contact forces, the slip
// velocity and the drum-centre motion, written once for any scalar type T: double for the flow's
// right-hand side and one sample, detail::Lanes<N> (util/lanes.hpp) for N samples at once. The
// state q, the kinematics k and the results are any structs with the paper's member names
// (State, Kinematics, Accelerations, DrumMotion for double; the *Of<T> structs below for lanes).
// The scalar functions of stick_phase.cpp, slip_phase.cpp and contact.cpp call these, so a lane's
// result has the scalar function's bits (always inlined: a call with a dozen arguments, some
// passed in memory, cost the slip phase's right-hand side 6 %).
#pragma once

#include <array>

#include "oscidrum/model.hpp"
#include "physics/kinematics_lanes.hpp"

namespace oscidrum::detail {

/// The state (54), the accelerations and the drum-centre motion (14), (17), (18) as T: for lanes
/// of samples (the kinematics: physics/kinematics_lanes.hpp).
template <class T>
struct StateOf {
  T delta, x_A, s_A, phi, ddelta, dx_A, ds_A, dphi;
};
/// Lane j of q from the state vector x = (delta, x_A, s_A, phi, delta', x_A', s_A', phi').
template <class L>
inline void set_lane(StateOf<L>& q, int j, const std::array<double, 8>& x) {
  q.delta[j] = x[0];
  q.x_A[j] = x[1];
  q.s_A[j] = x[2];
  q.phi[j] = x[3];
  q.ddelta[j] = x[4];
  q.dx_A[j] = x[5];
  q.ds_A[j] = x[6];
  q.dphi[j] = x[7];
}
template <class T>
struct AccelerationsOf {
  T delta, x_A, s_A, phi;
};
template <class T>
struct DrumMotionOf {
  T x_M, z_M, dx_M, dz_M, ddx_M, ddz_M;
};

/// Soil subsystem (24), (25), solved for N (26) and T. The soil is massless, so these hold in
/// every phase and equal (21), (22). s, c: sin and cos of delta.
template <class T, class Q>
[[gnu::always_inline]] inline void soil_contact_forces(const Model& model, const Q& q, const T& s,
                                                       const T& c, T& N, T& Tf) {
  const T Fh = model.ksh() * q.x_A + model.csh() * q.dx_A;
  const T Fv = model.ksv() * q.s_A + model.csv() * q.ds_A;
  N = Fh * s + Fv * c;
  Tf = Fv * s - Fh * c;
}

/// Slip velocity (13): v_rel = r f5 delta' - r phi'.
template <class T, class Q, class K>
[[gnu::always_inline]] inline T slip_velocity_of(const Model& model, const Q& q, const K& k) {
  return model.r() * k.f5 * q.ddelta - model.r() * q.dphi;
}

/// The drum-centre motion (14), (17), (18).
template <class Q, class A, class K, class D>
[[gnu::always_inline]] inline void drum_motion_of(const Q& q, const A& a, const K& k, D& d) {
  d.x_M = k.x_roll + q.x_A;  // (14)
  d.z_M = k.z_roll + q.s_A;
  d.dx_M = k.f1 * q.ddelta + q.dx_A;  // (17)
  d.dz_M = k.f3 * q.ddelta + q.ds_A;
  d.ddx_M = k.f1 * a.delta + k.f2 * q.ddelta * q.ddelta + a.x_A;  // (18)
  d.ddz_M = k.f3 * a.delta + k.f4 * q.ddelta * q.ddelta + a.s_A;
}

/// Stick phase (pure rolling): equations of motion (30), (31), (32) in the state form (52), with
/// the moment MM = M(t) (5), (6) and the load on M (Lx, W) = Model::centre_load(t).
template <class T, class Q, class K, class A>
[[gnu::always_inline]] inline void stick_accelerations_of(const Model& model, const Q& q,
                                                          const K& k, const T& MM, const T& Lx,
                                                          const T& W, A& a) {
  const double m = model.m(), I = model.I(), r = model.r();
  const double kd = model.kd(), cd = model.cd();
  const T s = k.sin_delta, c = k.cos_delta;
  const T dd2 = q.ddelta * q.ddelta;
  const T z_susp = k.z_roll - model.z_ref();  // suspension measured from z_ref (0: paper)

  // (30): m f1 delta'' + m x_A'' + h1 = 0
  const T h1 = m * k.f2 * dd2 + cd * k.f1 * q.ddelta + (model.csh() + cd) * q.dx_A +
               (model.ksh() + kd) * q.x_A + kd * k.x_roll - Lx;
  // (31): m f3 delta'' + m s_A'' + h2 = W
  const T h2 = m * k.f4 * dd2 + cd * k.f3 * q.ddelta + (model.csv() + cd) * q.ds_A +
               (model.ksv() + kd) * q.s_A + kd * z_susp;
  // (32): m (f5 I/(m r) + f1_bar) delta'' + m cos x_A'' - m sin s_A'' + h3 = MM/r - W sin
  const T h3 = (k.f6 * I / (m * r) + k.f2_bar) * m * dd2 +
               cd * (k.f1_bar * q.ddelta + q.dx_A * c - q.ds_A * s) +
               kd * ((k.x_roll + q.x_A) * c - (z_susp + q.s_A) * s) - Lx * c;
  const T rhs3 = MM / r - W * s - h3;

  // Solve (52) by elimination: (30) and (31) give x_A'' and s_A'' in terms of delta''; put into
  // (32). The delta'' coefficient becomes m (f5 I/(m r) + f1_bar - f1 cos + f3 sin) = f5 I / r
  // by (33), exactly.
  a.delta = (rhs3 + h1 * c + (W - h2) * s) * r / (k.f5 * I);
  a.x_A = -h1 / m - k.f1 * a.delta;
  a.s_A = (W - h2) / m - k.f3 * a.delta;
  a.phi = k.f5 * a.delta + k.f6 * dd2;  // (12)
}

/// Slip phase with a constant slip coefficient smu = s mu (Coulomb's law): equations of motion
/// (34), (38), (53) and (36) in the state form (55), with Baumgarte's stabilisation of the
/// friction coupling (39) at `baumgarte` [1/s]; MM, Lx and W as for stick.
template <class T, class Q, class K, class A>
[[gnu::always_inline]] inline void slip_accelerations_of(const Model& model, const Q& q, const K& k,
                                                         double smu, double baumgarte, const T& MM,
                                                         const T& Lx, const T& W, A& a) {
  const double m = model.m(), I = model.I(), r = model.r();
  const double kd = model.kd(), cd = model.cd();
  const double ksh = model.ksh(), ksv = model.ksv(), csh = model.csh(), csv = model.csv();
  const T sn = k.sin_delta, cs = k.cos_delta;
  const T dd = q.ddelta, dd2 = dd * dd;
  const T fmu1 = cs - smu * sn, fmu2 = sn + smu * cs;  // (35)
  const T xs = k.x_roll + q.x_A;                       // x_M
  const T zs = k.z_roll + q.s_A - model.z_ref();       // z_M from the suspension reference
  const T z_roll_s = k.z_roll - model.z_ref();

  // (34): m (f1 fmu1 - f3 fmu2) delta'' + m fmu1 x_A'' - m fmu2 s_A'' + h1s = -fmu2 W
  const T c34 = k.f1 * fmu1 - k.f3 * fmu2;
  const T h1s = (k.f2 * fmu1 - k.f4 * fmu2) * m * dd2 +
                cd * (c34 * dd + fmu1 * q.dx_A - fmu2 * q.ds_A) + kd * (fmu1 * xs - fmu2 * zs) -
                fmu1 * Lx;
  // (38): m f3~ delta'' + m sin x_A'' + m cos s_A'' + h3s = W cos
  const T h3s = cd * k.f3_tilde * dd + (csh + cd) * sn * q.dx_A + (csv + cd) * cs * q.ds_A +
                m * k.f4_tilde * dd2 + (ksh + kd) * sn * q.x_A + (ksv + kd) * cs * q.s_A +
                kd * (k.x_roll * sn + z_roll_s * cs) - Lx * sn;
  // (53): m fmu1 x_A'' - (csv/csh) m fmu2 s_A'' + h4 = 0, the time derivative of (39) times
  // m/csh; with Baumgarte stabilisation d(39)/dt + rate * (39) = 0 so that drift decays.
  const T Fh = csh * q.dx_A + ksh * q.x_A, Fv = csv * q.ds_A + ksv * q.s_A;
  T h4 = (m / csh) * (fmu1 * (ksh * q.dx_A - Fv * dd) - fmu2 * (ksv * q.ds_A + Fh * dd));
  if (baumgarte != 0.0) h4 += (m / csh) * baumgarte * (fmu1 * Fh - fmu2 * Fv);

  // 3x3 system A [delta'', x_A'', s_A'']^T = b by Cramer's rule; A31 = 0 (one division: the
  // determinant's reciprocal, a third of the time of this function went to waiting on three).
  const T A11 = m * c34, A12 = m * fmu1, A13 = -m * fmu2;
  const T A21 = m * k.f3_tilde, A22 = m * sn, A23 = m * cs;
  const T A32 = m * fmu1, A33 = -(csv / csh) * m * fmu2;
  const T b1 = -fmu2 * W - h1s, b2 = W * cs - h3s, b3 = -h4;
  const T det = A11 * (A22 * A33 - A23 * A32) - A12 * (A21 * A33) + A13 * (A21 * A32);
  const T inv_det = 1.0 / det;
  a.delta =
      (b1 * (A22 * A33 - A23 * A32) - A12 * (b2 * A33 - A23 * b3) + A13 * (b2 * A32 - A22 * b3)) *
      inv_det;
  a.x_A = (A11 * (b2 * A33 - A23 * b3) - b1 * (A21 * A33) + A13 * (A21 * b3)) * inv_det;
  a.s_A = (A11 * (A22 * b3 - b2 * A32) - A12 * (A21 * b3) + b1 * (A21 * A32)) * inv_det;

  // (36): s mu m (f3~ delta'' + sin x_A'' + cos s_A'') + (I/r) phi'' + h2s = MM/r
  const T h2s = -smu * (W * cs - m * k.f4_tilde * dd2 - k.f3_tilde * cd * dd -
                        cd * (sn * q.dx_A + cs * q.ds_A) - kd * (xs * sn + zs * cs) + Lx * sn);
  // phi'' = (MM - r h2s - r s mu m (...)) / I: (36) times r/I, with one division.
  a.phi = (MM - r * (h2s + smu * m * (k.f3_tilde * a.delta + sn * a.x_A + cs * a.s_A))) / I;
}

}  // namespace oscidrum::detail
