// Internal: the slip phase with a friction coefficient that depends on the slip velocity,
// T = -m(v_rel) N (a regularised or velocity-dependent law, oscidrum/friction.hpp). Written once
// for any scalar type: double for the right-hand side, Dual<8> (src/util/dual.hpp) for its exact
// Jacobian.
//
// (34), (36) and (38) are instantaneous balances and hold with s mu replaced by m(t). The
// coupling (39), fmu1 Fh - fmu2 Fv = 0 with fmu1 = cos - m sin, fmu2 = sin + m cos (35), is
// differentiated as in (53), but now fmu1' = -fmu2 delta' - m' sin and fmu2' = fmu1 delta' +
// m' cos, so d(39)/dt gains -m' (Fh sin + Fv cos) = -m' N (26), with
// m' = dm/dv v_rel' and v_rel' = r f6 delta'^2 + r f5 delta'' - r phi'' (13), (50).
// The (53) row therefore holds delta'' and phi'' too, and (34), (38), (53), (36) form a full 4 x 4
// system for (delta'', x_A'', s_A'', phi''). With dm/dv = 0 it is the paper's system (55).
#pragma once

#include <array>
#include <cmath>
#include <utility>

#include "oscidrum/model.hpp"
#include "util/dual.hpp"

namespace oscidrum::detail {

/// What the slip equations need of the kinematics (15)-(16), (46)-(50) at delta, as scalars T.
template <class T>
struct KinematicsT {
  T x_roll, z_roll, f1, f2, f3, f4, f5, f6, sn, cs;
};

inline KinematicsT<double> kinematics_t(const Kinematics& k) {
  return {k.x_roll, k.z_roll, k.f1, k.f2, k.f3, k.f4, k.f5, k.f6, k.sin_delta, k.cos_delta};
}

/// The same with derivatives along delta (a Dual seeded in the direction of delta): each
/// quantity's derivative is the next one of (46)-(50), and the rates give df2, df4, df6.
template <int N>
KinematicsT<Dual<N>> kinematics_t(const Kinematics& k, const KinematicsRates& kr,
                                  const Dual<N>& delta) {
  using D = Dual<N>;
  return {D::chain(delta, k.x_roll, k.f1),
          D::chain(delta, k.z_roll, k.f3),
          D::chain(delta, k.f1, k.f2),
          D::chain(delta, k.f2, kr.df2),
          D::chain(delta, k.f3, k.f4),
          D::chain(delta, k.f4, kr.df4),
          D::chain(delta, k.f5, k.f6),
          D::chain(delta, k.f6, kr.df6),
          D::chain(delta, k.sin_delta, k.cos_delta),
          D::chain(delta, k.cos_delta, -k.sin_delta)};
}

/// (delta'', x_A'', s_A'', phi'') of the slip phase with the friction coefficient m and its
/// derivative m_v = dm/dv_rel at the state y = (delta, x_A, s_A, phi, delta', x_A', s_A', phi').
template <class T>
std::array<T, 4> general_slip_accelerations(const Model& model, double t, const std::array<T, 8>& y,
                                            const KinematicsT<T>& k, const T& m, const T& m_v,
                                            double baumgarte) {
  const double M = model.m(), I = model.I(), r = model.r();
  const double kd = model.kd(), cd = model.cd();
  // The load on M: W + F_z(t) in place of W, and F_x(t) with kd x_M (docs/model.md section 14).
  const CentreLoad L = model.centre_load(t);
  const double W = L.z;
  const double ksh = model.ksh(), ksv = model.ksv(), csh = model.csh(), csv = model.csv();
  const T &XA = y[1], &SA = y[2], &dd = y[4], &DXA = y[5], &DSA = y[6];
  const T dd2 = dd * dd;
  const T &sn = k.sn, &cs = k.cs;
  const T f3t = k.f1 * sn + k.f3 * cs;  // (37)
  const T f4t = k.f2 * sn + k.f4 * cs;
  const T fm1 = cs - m * sn, fm2 = sn + m * cs;  // (35)
  const T xs = k.x_roll + XA;                    // x_M
  const T zs = k.z_roll + SA - model.z_ref();    // z_M from the suspension reference
  const T zrs = k.z_roll - model.z_ref();

  std::array<std::array<T, 4>, 4> A;
  std::array<T, 4> b;
  // (34): m (f1 fmu1 - f3 fmu2) delta'' + m fmu1 x_A'' - m fmu2 s_A'' + h1s = -fmu2 W
  const T c34 = k.f1 * fm1 - k.f3 * fm2;
  const T h1s = (k.f2 * fm1 - k.f4 * fm2) * M * dd2 + cd * (c34 * dd + fm1 * DXA - fm2 * DSA) +
                kd * (fm1 * xs - fm2 * zs) - fm1 * L.x;
  A[0] = {M * c34, M * fm1, -M * fm2, T(0.0)};
  b[0] = -fm2 * W - h1s;
  // (38): m f3~ delta'' + m sin x_A'' + m cos s_A'' + h3s = W cos
  const T h3s = cd * f3t * dd + (csh + cd) * sn * DXA + (csv + cd) * cs * DSA + M * f4t * dd2 +
                (ksh + kd) * sn * XA + (ksv + kd) * cs * SA + kd * (k.x_roll * sn + zrs * cs) -
                L.x * sn;
  A[1] = {M * f3t, M * sn, M * cs, T(0.0)};
  b[1] = W * cs - h3s;
  // (53) with the friction coefficient's rate: times m/csh, plus the Baumgarte term.
  const double c = M / csh;
  const T Fh = csh * DXA + ksh * XA, Fv = csv * DSA + ksv * SA;
  const T N = Fh * sn + Fv * cs;  // (26)
  T h4 = c * (fm1 * (ksh * DXA - Fv * dd) - fm2 * (ksv * DSA + Fh * dd));
  if (baumgarte != 0.0) h4 += c * baumgarte * (fm1 * Fh - fm2 * Fv);
  const T g = c * m_v * N * r;  // d(39)/dt (m/csh) = ... - g (f6 delta'^2 + f5 delta'' - phi'')
  A[2] = {-g * k.f5, M * fm1, -(csv / csh) * M * fm2, g};
  b[2] = -h4 + g * k.f6 * dd2;
  // (36): m M (f3~ delta'' + sin x_A'' + cos s_A'') + (I/r) phi'' + h2s = MM/r
  const T h2s = -m * (W * cs - M * f4t * dd2 - f3t * cd * dd - cd * (sn * DXA + cs * DSA) -
                      kd * (xs * sn + zs * cs) + L.x * sn);
  A[3] = {m * M * f3t, m * M * sn, m * M * cs, T(I / r)};
  b[3] = model.torque(t) / r - h2s;

  // Gaussian elimination with partial pivoting (the pivots chosen on the values).
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int row = col + 1; row < 4; ++row)
      if (std::abs(value_of(A[row][col])) > std::abs(value_of(A[pivot][col]))) pivot = row;
    std::swap(A[col], A[pivot]);
    std::swap(b[col], b[pivot]);
    for (int row = col + 1; row < 4; ++row) {
      const T f = A[row][col] / A[col][col];
      for (int j = col; j < 4; ++j) A[row][j] -= f * A[col][j];
      b[row] -= f * b[col];
    }
  }
  std::array<T, 4> a;
  for (int row = 3; row >= 0; --row) {
    T sum = b[row];
    for (int j = row + 1; j < 4; ++j) sum -= A[row][j] * a[j];
    a[row] = sum / A[row][row];
  }
  return a;
}

}  // namespace oscidrum::detail
