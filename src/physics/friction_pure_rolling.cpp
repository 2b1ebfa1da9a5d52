// Pure rolling (oscidrum/friction.hpp): the friction limit is ignored, mu -> infinity; the drum
// sticks throughout (the paper's "pure rolling" studies).
#include <limits>

#include "oscidrum/friction.hpp"

namespace oscidrum {

FrictionPhases PureRolling::phases() const { return FrictionPhases::stick_only; }
double PureRolling::cone() const { return std::numeric_limits<double>::infinity(); }
SlipCoefficient PureRolling::slip(int, double) const { return {}; }
double PureRolling::largest_coefficient() const { return std::numeric_limits<double>::infinity(); }
double PureRolling::creep_velocity() const { return 0.0; }

}  // namespace oscidrum
