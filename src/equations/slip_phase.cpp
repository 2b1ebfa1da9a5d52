// Slip phase: equations of motion (34), (38), (53) and (36) in the state form (55), and the
// friction coupling (39). The friction coefficient is the law's (oscidrum/friction.hpp): a
// constant s mu solves (55) as the paper does; one that depends on v_rel takes the general system
// of src/equations/slip_general.hpp.
#include <cmath>

#include "equations/equations.hpp"
#include "equations/phase_equations.hpp"
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
  // The load on M: W + F_z(t) in place of W, and F_x(t) with kd x_M (docs/model.md section 14).
  const CentreLoad L = model.centre_load(t);
  const SlipCoefficient mu = slip_coefficient(model.friction(), s, slip_velocity(model, q, k));
  if (mu.dm_dv != 0.0) {  // a velocity-dependent coefficient: the full 4 x 4 system
    const auto a = general_slip_accelerations(model, t, q.to_array(), kinematics_t(k), mu.m,
                                              mu.dm_dv, baumgarte);
    return {a[0], a[1], a[2], a[3]};
  }
  Accelerations a;
  slip_accelerations_of<double>(model, q, k, mu.m, baumgarte, MM, L.x, L.z, a);  // (34)-(38), (53)
  return a;
}

}  // namespace oscidrum
