// Internal: the flight phase of a drum whose contact can open (contact.unilateral, docs/model.md
// section 13), and the maps at lift-off and landing. Written once for any scalar type: double for
// the right-hand side and the maps, Dual<10> (src/util/dual.hpp) for their exact Jacobians.
//
// The state (UnilateralState, oscidrum/roller.hpp) is y = (delta, x_A, s_A, phi, g, delta', x_A',
// s_A', phi', g'). In flight the drum centre is M = A + roll(delta) - g n(delta), A = (x_A, s_A)
// the trough's point, roll = (x_roll, z_roll) (15), (16), n = (sin delta, cos delta) the normal
// from the drum towards the trough and t = (cos delta, -sin delta) the tangent: (delta, g) are the
// trough's nearest point and the gap (the roll curve is the trough's parallel at the drum radius:
// (f1, f3) = r f5 t by (33), (37)). With rho = r f5 - g,
//   M'  = A' + rho delta' t - g' n,
//   M'' = A'' + [rho delta'' + (r f6 delta' - 2 g') delta'] t - [g'' + rho delta'^2] n.
// No contact force acts: (19), (20), (23) with N = T = 0 give M'' = (-cd x_M' - kd x_M,
// W - cd z_M' - kd (z_M - z_ref)) / m and phi'' = MM(t) / I, and the massless soil relaxes by
// (24), (25) with N = T = 0: ksh x_A + csh x_A' = 0, ksv s_A + csv s_A' = 0 (integrated as
// x_A'' = -(ksh/csh) x_A', which keeps that relation). The chart holds while rho > 0 (the gap
// stays below the trough's clearance r f5).
#pragma once

#include <array>
#include <cmath>

#include "equations/slip_general.hpp"
#include "oscidrum/friction.hpp"
#include "oscidrum/model.hpp"

namespace oscidrum::detail {

/// Indices into the unilateral drum's state.
namespace flight_index {
inline constexpr int kDelta = 0, kXA = 1, kSA = 2, kPhi = 3, kGap = 4;
inline constexpr int kDDelta = 5, kDXA = 6, kDSA = 7, kDPhi = 8, kDGap = 9;
}  // namespace flight_index

/// The drum centre's position, velocity and (given A'' and the chart's accelerations)
/// acceleration in the flight chart.
template <class T>
struct FlightCentre {
  T x, z, dx, dz;
};

template <class T>
FlightCentre<T> flight_centre(const std::array<T, 10>& y, const KinematicsT<T>& k, double r) {
  using namespace flight_index;
  const T rho = r * k.f5 - y[kGap];
  return {y[kXA] + k.x_roll - y[kGap] * k.sn, y[kSA] + k.z_roll - y[kGap] * k.cs,
          y[kDXA] + rho * y[kDDelta] * k.cs - y[kDGap] * k.sn,
          y[kDSA] - rho * y[kDDelta] * k.sn - y[kDGap] * k.cs};
}

/// (delta'', x_A'', s_A'', phi'', g'') in flight.
template <class T>
std::array<T, 5> flight_accelerations(const Model& model, double t, const std::array<T, 10>& y,
                                      const KinematicsT<T>& k) {
  using namespace flight_index;
  const double m = model.m(), r = model.r(), kd = model.kd(), cd = model.cd();
  const FlightCentre<T> M = flight_centre(y, k, r);
  // The drum: (19), (20) with N = T = 0; the suspension from z_ref as in the contact phases.
  // The load on M: W + F_z(t), F_x(t) (docs/model.md section 14).
  const CentreLoad L = model.centre_load(t);
  const T ddx_M = (-cd * M.dx - kd * M.x + L.x) / m;
  const T ddz_M = (L.z - cd * M.dz - kd * (M.z - model.z_ref())) / m;
  // The soil: (24), (25) with N = T = 0, differentiated.
  const T ddx_A = -(model.ksh() / model.csh()) * y[kDXA];
  const T dds_A = -(model.ksv() / model.csv()) * y[kDSA];
  const T ax = ddx_M - ddx_A, az = ddz_M - dds_A;
  const T along = ax * k.cs - az * k.sn;   // (M'' - A'') . t
  const T across = ax * k.sn + az * k.cs;  // (M'' - A'') . n
  const T rho = r * k.f5 - y[kGap];
  const T dd = y[kDDelta];
  std::array<T, 5> a;
  a[0] = (along - (r * k.f6 * dd - 2.0 * y[kDGap]) * dd) / rho;
  a[1] = ddx_A;
  a[2] = dds_A;
  a[3] = T(model.torque(t) / model.I());  // (23) with T = 0
  a[4] = -across - rho * dd * dd;
  return a;
}

/// Lift-off at N = 0: the contact's forces vanish, so the massless soil relaxes at once from
/// where it is, x_A' = -(ksh/csh) x_A, s_A' = -(ksv/csv) s_A (its velocities jump unless the soil
/// forces were already zero, as in slip, where |T| = mu N = 0); the drum's velocities M' and phi'
/// do not jump (phi' = f5 delta' (12) when it leaves stick). delta' and g' follow from M':
/// delta' = (M' - A').t / (r f5), g' = -(M' - A').n.
template <class T>
std::array<T, 10> liftoff_map(const Model& model, const std::array<T, 10>& y,
                              const KinematicsT<T>& k, bool from_stick) {
  using namespace flight_index;
  const double r = model.r();
  std::array<T, 10> out = y;
  out[kGap] = T(0.0);
  const T dphi = from_stick ? k.f5 * y[kDDelta] : y[kDPhi];
  // M' in contact (g = g' = 0): A' + r f5 delta' t.
  const T vx = y[kDXA] + r * k.f5 * y[kDDelta] * k.cs;
  const T vz = y[kDSA] - r * k.f5 * y[kDDelta] * k.sn;
  out[kDXA] = -(model.ksh() / model.csh()) * y[kXA];
  out[kDSA] = -(model.ksv() / model.csv()) * y[kSA];
  const T wx = vx - out[kDXA], wz = vz - out[kDSA];
  out[kDDelta] = (wx * k.cs - wz * k.sn) / (r * k.f5);
  out[kDGap] = -(wx * k.sn + wz * k.cs);
  out[kDPhi] = dphi;
  return out;
}

/// How contact resumes at landing (g = 0).
enum class Landing {
  stick,   ///< rolling: phi' = f5 delta' (12)
  slip,    ///< slip with a constant coefficient m = s mu (Coulomb laws): the coupling (39)
  smooth,  ///< the smooth phase of a regularised law: (39) with m(v_rel)
};

/// Landing at g = 0: the drum's velocities M' and phi' do not jump (the soil is massless: no
/// impulse); the soil's velocities jump to what the contact needs, A' = M' - r f5 delta' t, with
/// delta' from the friction law: rolling, delta' = phi' / f5 (12); slip of coefficient m, the
/// coupling (39) fmu1 (csh x_A' + ksh x_A) = fmu2 (csv s_A' + ksv s_A), linear in delta' for a
/// constant m, solved by Newton's method for the smooth law's m(v_rel) (from the rolling value).
/// g and g' become 0.
template <class T>
std::array<T, 10> landing_map(const Model& model, const std::array<T, 10>& y,
                              const KinematicsT<T>& k, Landing how, int s) {
  using namespace flight_index;
  const double r = model.r();
  const double ksh = model.ksh(), ksv = model.ksv(), csh = model.csh(), csv = model.csv();
  std::array<T, 10> out = y;
  // M' in flight at g = 0: A' + r f5 delta' t - g' n.
  const T vx = y[kDXA] + r * k.f5 * y[kDDelta] * k.cs - y[kDGap] * k.sn;
  const T vz = y[kDSA] - r * k.f5 * y[kDDelta] * k.sn - y[kDGap] * k.cs;
  T dd = y[kDPhi] / k.f5;  // rolling (12)
  // The coupling (39) as a function of delta' (A' = M' - r f5 delta' t) with coefficient m.
  const auto coupling = [&](const T& d, const T& mu_m) {
    const T fm1 = k.cs - mu_m * k.sn, fm2 = k.sn + mu_m * k.cs;  // (35)
    const T xa = vx - r * k.f5 * d * k.cs, sa = vz + r * k.f5 * d * k.sn;
    return fm1 * (csh * xa + ksh * y[kXA]) - fm2 * (csv * sa + ksv * y[kSA]);
  };
  if (how == Landing::slip) {
    const T mu_m = T(slip_coefficient(model.friction(), s, 0.0).m);
    // Linear in delta': c0 + c1 delta' = 0.
    const T c0 = coupling(T(0.0), mu_m), c1 = coupling(T(1.0), mu_m) - c0;
    dd = -c0 / c1;
  } else if (how == Landing::smooth) {
    // Newton's method on the values, then one step on T from the converged value: a Newton
    // step from a root gives the root's exact derivatives (-F_p / F_d) when T is a Dual.
    const auto step = [&](const T& d) {
      const T v = r * k.f5 * d - r * y[kDPhi];  // (13)
      const SlipCoefficient c = slip_coefficient(model.friction(), 0, value_of(v));
      const T mu_m = c.m + c.dm_dv * (v - value_of(v));  // m(v), exact to first order
      const T fm1 = k.cs - mu_m * k.sn, fm2 = k.sn + mu_m * k.cs;
      const T xa = vx - r * k.f5 * d * k.cs, sa = vz + r * k.f5 * d * k.sn;
      const T Fh = csh * xa + ksh * y[kXA], Fv = csv * sa + ksv * y[kSA];
      const T F = fm1 * Fh - fm2 * Fv;
      // dF/d delta' at fixed m, plus the change of m through v_rel: dm/dv r f5 (-sin Fh - cos Fv).
      const T dF = fm1 * csh * (-r * k.f5 * k.cs) - fm2 * csv * (r * k.f5 * k.sn) +
                   c.dm_dv * r * k.f5 * (-k.sn * Fh - k.cs * Fv);
      return F / dF;
    };
    double d = value_of(dd);
    for (int i = 0; i < 60; ++i) {
      const double change = value_of(step(T(d)));
      d -= change;
      if (std::abs(change) <= 1e-14 * (1.0 + std::abs(d))) break;
    }
    dd = T(d) - step(T(d));
  }
  out[kDDelta] = dd;
  out[kDXA] = vx - r * k.f5 * dd * k.cs;
  out[kDSA] = vz + r * k.f5 * dd * k.sn;
  out[kGap] = T(0.0);
  out[kDGap] = T(0.0);
  return out;
}

}  // namespace oscidrum::detail
