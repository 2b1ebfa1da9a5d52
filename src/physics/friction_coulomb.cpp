// Coulomb friction with one coefficient (oscidrum/friction.hpp), the paper's law: stick while
// |T| <= mu N (28); in slip T = -s mu N with s = sign(v_rel) (27), (29).
#include "oscidrum/friction.hpp"

namespace oscidrum {

FrictionPhases CoulombFriction::phases() const { return FrictionPhases::stick_slip; }
double CoulombFriction::cone() const { return mu; }
SlipCoefficient CoulombFriction::slip(int s, double) const { return {s * mu, 0.0, 0.0}; }
double CoulombFriction::largest_coefficient() const { return mu; }
double CoulombFriction::creep_velocity() const { return 0.0; }

}  // namespace oscidrum
