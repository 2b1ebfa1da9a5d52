// oscidrum/friction.hpp: the friction law at the drum/soil contact C, one small type per law,
// gathered in a closed set (a variant). A law answers these questions, and the equations, the
// event functions, the event decisions, the Jacobians and the steady-state search ask only
// these (through the dispatchers below, which visit the variant):
//   - which phases it has (stick and slip, stick only, or one smooth phase),
//   - its friction cone: stick holds while |T| <= cone N (28),
//   - its slip coefficient at a slip velocity v_rel: T = -m N in slip (27), (29), which enters
//     (34)-(36), (39) and (53), with the derivatives of m for the smooth laws,
//   - below which slip velocity its slip looks like stick (the creep of a smooth law).
// Each law's answers are in its own file (src/physics/friction_<law>.cpp). Adding a law: its
// struct here with the five members, its file, its entry in FrictionLaw and in friction_law(),
// and its tests; a law that misses a member does not compile.
#pragma once

#include <variant>

#include "oscidrum/parameters.hpp"
#include "oscidrum/state.hpp"

namespace oscidrum {

/// The phases a law produces.
enum class FrictionPhases {
  stick_only,  ///< stick throughout (pure rolling)
  stick_slip,  ///< stick, slip+ and slip-, switched by events (Coulomb laws)
  smooth,      ///< one smooth phase for every v_rel (regularised laws): no stick, no switches
};

/// The slip coefficient of a law at a slip velocity: T = -m N [-] (m has the sign of v_rel), with
/// its first and second derivatives with respect to v_rel (zero for the Coulomb laws).
struct SlipCoefficient {
  double m = 0.0;        ///< [-]
  double dm_dv = 0.0;    ///< [s/m]
  double d2m_dv2 = 0.0;  ///< [s^2/m^2]
};

/// Stick throughout: the friction limit is ignored (mu -> infinity), the paper's "pure rolling".
struct PureRolling {
  FrictionPhases phases() const;
  double cone() const;                              ///< +infinity
  SlipCoefficient slip(int s, double v_rel) const;  ///< never used (0)
  double largest_coefficient() const;               ///< +infinity: it holds any torque
  double creep_velocity() const;                    ///< 0 (never used)
};

/// Coulomb friction with one coefficient (the paper): stick while |T| <= mu N (28), slip with
/// T = -s mu N (27), (29).
struct CoulombFriction {
  double mu = 0.5;  ///< [-]
  FrictionPhases phases() const;
  double cone() const;                              ///< mu
  SlipCoefficient slip(int s, double v_rel) const;  ///< s mu
  double largest_coefficient() const;               ///< mu
  double creep_velocity() const;                    ///< 0: slip is slip
};

/// Coulomb friction with a static coefficient for the cone and a kinetic one for slip,
/// mu_static >= mu_kinetic. When slip starts, the tangential force drops from mu_static N to
/// mu_kinetic N at once: the massless soil's velocities jump (the drum's do not), see
/// docs/model.md.
struct StaticKineticFriction {
  double mu_static = 0.5;   ///< stick while |T| <= mu_static N [-]
  double mu_kinetic = 0.5;  ///< T = -s mu_kinetic N in slip [-]
  FrictionPhases phases() const;
  double cone() const;                              ///< mu_static
  SlipCoefficient slip(int s, double v_rel) const;  ///< s mu_kinetic
  double largest_coefficient() const;               ///< mu_kinetic (what holds a driving torque)
  double creep_velocity() const;                    ///< 0: slip is slip
};

/// Regularised Coulomb friction: T = -mu tanh(v_rel / v_eps) N for every v_rel, one smooth
/// phase without stick (docs/model.md section 12). As v_eps -> 0 it tends to the Coulomb law
/// with the same mu; the stick phase becomes creep at |v_rel| of order v_eps.
struct RegularisedCoulomb {
  double mu = 0.5;      ///< [-]
  double v_eps = 0.01;  ///< regularisation velocity [m/s], > 0
  FrictionPhases phases() const;
  double cone() const;                              ///< mu (the bound |T| < mu N)
  SlipCoefficient slip(int s, double v_rel) const;  ///< mu tanh(v_rel / v_eps); s is ignored
  double largest_coefficient() const;               ///< mu
  double creep_velocity() const;                    ///< 4 v_eps (|T| < 0.9993 mu N)
};

using FrictionLaw =
    std::variant<PureRolling, CoulombFriction, StaticKineticFriction, RegularisedCoulomb>;

/// The law a Contact describes: pure_rolling; else contact.law = regularised; else
/// static/kinetic when contact.mu_static is set (>= 0) and differs from contact.mu; else Coulomb.
FrictionLaw friction_law(const Contact& contact);

/// The phases of the law.
FrictionPhases friction_phases(const FrictionLaw& law);

/// The coefficient of the friction cone, |T| <= cone N (infinite for pure rolling) [-].
double cone_coefficient(const FrictionLaw& law);

/// The slip coefficient at slip velocity v_rel in a slip phase of sign s (s = 0 for the smooth
/// phase): T = -m N.
SlipCoefficient slip_coefficient(const FrictionLaw& law, int s, double v_rel);

/// The largest |m| of slip: a drum slipping one way can hold a driving torque up to this times
/// W r (+infinity for pure rolling) [-].
double largest_slip_coefficient(const FrictionLaw& law);

/// True when the law has no limit (pure rolling).
inline bool never_slips(const FrictionLaw& law) {
  return friction_phases(law) == FrictionPhases::stick_only;
}

/// The phase a trajectory of this law starts in from rest: stick, except without friction (a
/// Coulomb law with mu = 0, where the drum slips from the start; the sign does not matter then)
/// and for the smooth laws (Phase::smooth).
Phase initial_phase(const FrictionLaw& law);

/// True when a trajectory of this law can be in `phase` (continuation maps a neighbour's phase
/// that the new case cannot be in to initial_phase).
bool has_phase(const FrictionLaw& law, Phase phase);

/// The flow phase to continue a sampled state in: the sample's phase when the law has it, else
/// the law's initial phase (a smooth law's samples show apparent phases, oscidrum/friction.hpp).
inline Phase flow_phase(const FrictionLaw& law, Phase sample_phase) {
  return has_phase(law, sample_phase) ? sample_phase : initial_phase(law);
}

/// True for a Coulomb law without friction (mu = 0): its cone is a point, slip exerts no force
/// either way, and the flow has no event at v_rel = 0 (src/flow/event_functions.cpp), so the
/// flow's slip direction is arbitrary (initial_phase).
bool frictionless(const FrictionLaw& law);
/// The phase a sample is shown in: the flow's phase, except in the smooth phase, where it is stick
/// (creep) while |v_rel| <= the law's creep velocity (v_eps), else slip with the sign of v_rel, and
/// in slip without friction (frictionless), where it is slip with the sign of v_rel (the flow's
/// phase where v_rel = 0).
Phase apparent_phase(const FrictionLaw& law, Phase phase, double v_rel);
/// True when apparent_phase can differ from `phase` along a trajectory in it: the smooth phase,
/// and slip without friction.
bool apparent_varies(const FrictionLaw& law, Phase phase);

}  // namespace oscidrum
