// Stick phase (pure rolling): equations of motion (30), (31), (32) in the state form (52).
#include <cmath>

#include "equations/equations.hpp"
#include "oscidrum/model.hpp"

namespace oscidrum {

Accelerations stick_accelerations(const Model& model, double t, const State& q) {
  return detail::stick_accelerations(model, t, q, kinematics(model.geometry(), q.delta));
}

Accelerations detail::stick_accelerations(const Model& model, double t, const State& q,
                                          const Kinematics& k, double MM) {
  const double m = model.m(), I = model.I(), r = model.r();
  const double kd = model.kd(), cd = model.cd();
  // The load on M: W + F_z(t) in place of W, and F_x(t) with kd x_M (docs/model.md section 14).
  const CentreLoad L = model.centre_load(t);
  const double W = L.z;
  const double s = k.sin_delta, c = k.cos_delta;
  const double dd2 = q.ddelta * q.ddelta;
  const double z_susp = k.z_roll - model.z_ref();  // suspension measured from z_ref (0: paper)

  // (30): m f1 delta'' + m x_A'' + h1 = 0
  const double h1 = m * k.f2 * dd2 + cd * k.f1 * q.ddelta + (model.csh() + cd) * q.dx_A +
                    (model.ksh() + kd) * q.x_A + kd * k.x_roll - L.x;
  // (31): m f3 delta'' + m s_A'' + h2 = W
  const double h2 = m * k.f4 * dd2 + cd * k.f3 * q.ddelta + (model.csv() + cd) * q.ds_A +
                    (model.ksv() + kd) * q.s_A + kd * z_susp;
  // (32): m (f5 I/(m r) + f1_bar) delta'' + m cos x_A'' - m sin s_A'' + h3 = MM/r - W sin
  const double h3 = (k.f6 * I / (m * r) + k.f2_bar) * m * dd2 +
                    cd * (k.f1_bar * q.ddelta + q.dx_A * c - q.ds_A * s) +
                    kd * ((k.x_roll + q.x_A) * c - (z_susp + q.s_A) * s) - L.x * c;
  const double rhs3 = MM / r - W * s - h3;

  // Solve (52) by elimination: (30) and (31) give x_A'' and s_A'' in terms of delta''; put into
  // (32). The delta'' coefficient becomes m (f5 I/(m r) + f1_bar - f1 cos + f3 sin) = f5 I / r
  // by (33), exactly.
  Accelerations a;
  a.delta = (rhs3 + h1 * c + (W - h2) * s) * r / (k.f5 * I);
  a.x_A = -h1 / m - k.f1 * a.delta;
  a.s_A = (W - h2) / m - k.f3 * a.delta;
  a.phi = k.f5 * a.delta + k.f6 * dd2;  // (12)
  return a;
}

}  // namespace oscidrum
