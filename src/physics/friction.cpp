// Friction laws (oscidrum/friction.hpp): which law a Contact describes, and the dispatchers that
// visit the variant. Each law's own answers are in src/physics/friction_<law>.cpp.
#include "oscidrum/friction.hpp"

#include <cmath>

namespace oscidrum {

FrictionLaw friction_law(const Contact& contact) {
  if (contact.pure_rolling) return PureRolling{};
  if (contact.law == FrictionChoice::regularised)
    return RegularisedCoulomb{contact.mu, contact.v_eps};
  if (contact.mu_static >= 0.0 && contact.mu_static != contact.mu)
    return StaticKineticFriction{contact.mu_static, contact.mu};
  return CoulombFriction{contact.mu};
}

FrictionPhases friction_phases(const FrictionLaw& law) {
  return std::visit([](const auto& l) { return l.phases(); }, law);
}

double cone_coefficient(const FrictionLaw& law) {
  return std::visit([](const auto& l) { return l.cone(); }, law);
}

SlipCoefficient slip_coefficient(const FrictionLaw& law, int s, double v_rel) {
  return std::visit([s, v_rel](const auto& l) { return l.slip(s, v_rel); }, law);
}

double largest_slip_coefficient(const FrictionLaw& law) {
  return std::visit([](const auto& l) { return l.largest_coefficient(); }, law);
}

Phase initial_phase(const FrictionLaw& law) {
  switch (friction_phases(law)) {
    case FrictionPhases::stick_only:
      return Phase::stick;
    case FrictionPhases::smooth:
      return Phase::smooth;
    case FrictionPhases::stick_slip:
      // Without friction the cone is a point: the drum slips from the start.
      return cone_coefficient(law) == 0.0 ? Phase::slip_positive : Phase::stick;
  }
  return Phase::stick;
}

bool has_phase(const FrictionLaw& law, Phase phase) {
  switch (friction_phases(law)) {
    case FrictionPhases::stick_only:
      return phase == Phase::stick;
    case FrictionPhases::smooth:
      return phase == Phase::smooth;
    case FrictionPhases::stick_slip:
      return phase != Phase::smooth && (phase != Phase::stick || cone_coefficient(law) > 0.0);
  }
  return false;
}

bool frictionless(const FrictionLaw& law) {
  return friction_phases(law) == FrictionPhases::stick_slip && cone_coefficient(law) == 0.0;
}

bool apparent_varies(const FrictionLaw& law, Phase phase) {
  return phase == Phase::smooth ||
         ((phase == Phase::slip_positive || phase == Phase::slip_negative) && frictionless(law));
}

Phase apparent_phase(const FrictionLaw& law, Phase phase, double v_rel) {
  if (!apparent_varies(law, phase)) return phase;
  if (phase != Phase::smooth) {
    // mu = 0: no force tells the directions apart; the sample shows the way the drum slips.
    if (v_rel == 0.0) return phase;
    return v_rel > 0.0 ? Phase::slip_positive : Phase::slip_negative;
  }
  const double creep = std::visit([](const auto& l) { return l.creep_velocity(); }, law);
  if (std::abs(v_rel) <= creep) return Phase::stick;
  return v_rel > 0.0 ? Phase::slip_positive : Phase::slip_negative;
}

}  // namespace oscidrum
