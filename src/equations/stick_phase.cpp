// Stick phase (pure rolling): equations of motion (30), (31), (32) in the state form (52)
// (written out in equations/phase_equations.hpp).
#include <cmath>

#include "equations/equations.hpp"
#include "equations/phase_equations.hpp"
#include "oscidrum/model.hpp"

namespace oscidrum {

Accelerations stick_accelerations(const Model& model, double t, const State& q) {
  return detail::stick_accelerations(model, t, q, kinematics(model.geometry(), q.delta));
}

Accelerations detail::stick_accelerations(const Model& model, double t, const State& q,
                                          const Kinematics& k, double MM) {
  // The load on M: W + F_z(t) in place of W, and F_x(t) with kd x_M (docs/model.md section 14).
  const CentreLoad L = model.centre_load(t);
  Accelerations a;
  stick_accelerations_of<double>(model, q, k, MM, L.x, L.z, a);  // (30)-(32), (52)
  return a;
}

}  // namespace oscidrum
