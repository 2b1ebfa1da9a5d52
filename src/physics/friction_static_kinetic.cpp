// Coulomb friction with a static and a kinetic coefficient (oscidrum/friction.hpp): stick while
// |T| <= mu_static N, slip with T = -s mu_kinetic N (docs/model.md section 12).
#include "oscidrum/friction.hpp"

namespace oscidrum {

FrictionPhases StaticKineticFriction::phases() const { return FrictionPhases::stick_slip; }
double StaticKineticFriction::cone() const { return mu_static; }
SlipCoefficient StaticKineticFriction::slip(int s, double) const {
  return {s * mu_kinetic, 0.0, 0.0};
}
double StaticKineticFriction::largest_coefficient() const { return mu_kinetic; }
double StaticKineticFriction::creep_velocity() const { return 0.0; }

}  // namespace oscidrum
