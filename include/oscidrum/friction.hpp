// oscidrum/friction.hpp: the friction law at the drum/soil contact C, one small type per law,
// gathered in a closed set (a variant). A law owns its friction cone (when stick holds, (28)),
// the coefficient of the slip phase (27), (29), which enters (35), (36), (39) and (53), and what
// happens to the soil's velocities when slip starts.
#pragma once

#include <variant>

#include "oscidrum/parameters.hpp"

namespace oscidrum {

/// Stick throughout: the friction limit is ignored (mu -> infinity), the paper's "pure rolling".
struct PureRolling {};

/// Coulomb friction with one coefficient (the paper): stick while |T| <= mu N (28), slip with
/// T = -s mu N (27), (29).
struct CoulombFriction {
  double mu = 0.5;  ///< [-]
};

/// Coulomb friction with a static coefficient for the cone and a kinetic one for slip,
/// mu_static >= mu_kinetic. When slip starts, the tangential force drops from mu_static N to
/// mu_kinetic N at once: the massless soil's velocities jump (the drum's do not), see
/// docs/model.md.
struct StaticKineticFriction {
  double mu_static = 0.5;   ///< stick while |T| <= mu_static N [-]
  double mu_kinetic = 0.5;  ///< T = -s mu_kinetic N in slip [-]
};

using FrictionLaw = std::variant<PureRolling, CoulombFriction, StaticKineticFriction>;

/// The law a Contact describes: pure_rolling, else static/kinetic when contact.mu_static is set
/// (>= 0) and differs from contact.mu, else Coulomb.
FrictionLaw friction_law(const Contact& contact);

/// The coefficient of the friction cone, |T| <= cone N (infinite for pure rolling) [-].
double cone_coefficient(const FrictionLaw& law);

/// The coefficient of the slip phase, T = -s coefficient N (0 for pure rolling, never slipping).
double slip_coefficient(const FrictionLaw& law);

/// True when the law has no limit (pure rolling).
inline bool never_slips(const FrictionLaw& law) { return std::holds_alternative<PureRolling>(law); }

}  // namespace oscidrum
