// Regularised Coulomb friction (oscidrum/friction.hpp, docs/model.md section 12): the sign
// function of Coulomb's law replaced by tanh(v_rel / v_eps), T = -mu tanh(v_rel / v_eps) N, one
// smooth phase for every slip velocity. A common regularisation of dry friction in dynamics
// (see docs/model.md for the references); it tends to Coulomb's law as v_eps -> 0.
#include <cmath>

#include "oscidrum/friction.hpp"

namespace oscidrum {

FrictionPhases RegularisedCoulomb::phases() const { return FrictionPhases::smooth; }
double RegularisedCoulomb::cone() const { return mu; }
SlipCoefficient RegularisedCoulomb::slip(int, double v_rel) const {
  // m = mu tanh(x), x = v_rel / v_eps; dm/dv = mu (1 - tanh^2) / v_eps;
  // d2m/dv2 = -2 mu tanh (1 - tanh^2) / v_eps^2.
  const double th = std::tanh(v_rel / v_eps);
  const double sech2 = 1.0 - th * th;
  return {mu * th, mu * sech2 / v_eps, -2.0 * mu * th * sech2 / (v_eps * v_eps)};
}
double RegularisedCoulomb::largest_coefficient() const { return mu; }
// Creep: |T| < tanh(4) mu N = 0.9993 mu N. Next to a stick phase of Coulomb's law the regularised
// drum creeps at a few v_eps with |T| just below mu N (tanh(v/v_eps) of 0.9 to 0.99), so a band of
// one v_eps would count much of what tends to stick as slip; with 4 v_eps the apparent stick
// fraction tends to the Coulomb one as v_eps -> 0.
double RegularisedCoulomb::creep_velocity() const { return 4.0 * v_eps; }

}  // namespace oscidrum
