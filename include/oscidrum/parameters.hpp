// oscidrum/parameters.hpp: plain input structs. Defaults are the paper's roller (HAMM HD+ 90 VO,
// docs/model.md section 1, paper Table 1) on the Table 2 soil at G = 25 MN/m^2, circular trough
// R = 0.606 m, Coulomb friction mu = 0.5, no driving torque. All units SI.
#pragma once

#include <numbers>

#include "oscidrum/trough.hpp"

namespace oscidrum {

/// Which dynamic roller the drum is (docs/model.md section 14).
enum class RollerType {
  oscillation,  ///< the paper's oscillation drum: the moment M0 sin(nu t) (5) about M
  vibratory,    ///< a vibratory drum: a rotating unbalance force of amplitude m_u e_u nu^2 on M
};

/// The direction of the vibratory drum's unbalance force F0 (cos, sin) in the (x, z) plane of the
/// model (z downwards); all three have the same vertical component F0 sin(nu t).
enum class Exciter {
  circular,           ///< F = F0 (cos nu t, sin nu t): the unbalance turns from +x towards +z
  circular_reversed,  ///< F = F0 (-cos nu t, sin nu t): the same unbalance turning the other way
  vertical,           ///< F = F0 (0, sin nu t): a directed exciter (two counter-rotating shafts)
};

/// The drum and its suspension (paper Table 1).
struct Roller {
  double r = 0.6;       ///< drum radius [m]
  double b = 1.68;      ///< drum width [m] (b0 = b/2 in Appendix B)
  double m = 1851.0;    ///< drum mass [kg]
  double I = 411.78;    ///< mass moment of inertia about the drum centre M [kg m^2]
  double P0 = 45224.0;  ///< static axle load [N]; Fz = P0 - m g (7)
  double f = 39.0;      ///< excitation frequency [Hz]; nu = 2 pi f
  double M0 = 54947.0;  ///< amplitude of the oscillation moment M_Mu^(0) (5) [N m]
  /// The unbalances' moment m_u e_u e_w [kg m^2]. > 0: M0 = 4 m_u e_u e_w nu^2 (5) follows f and
  /// replaces M0 (see oscillation_moment); 0: M0 is used as given. The paper's roller: 0.22877.
  double unbalance = 0.0;
  double kd = 4.0e6;    ///< drum/frame suspension stiffness, horizontal and vertical [N/m]
  double cd = 3.0e3;    ///< drum/frame suspension damping, horizontal and vertical [N s/m]
  double g = 9.81;      ///< gravitational acceleration [m/s^2]
  double m_f = 2760.0;  ///< effective frame mass on the drum's axle, Appendix A only [kg]
  RollerType type = RollerType::oscillation;  ///< oscillation (the paper) or vibratory drum
  /// The vibratory drum's static moment m_u e_u [kg m]: the force on M has the amplitude
  /// F0 = m_u e_u nu^2 (docs/model.md section 14). Read only when type = vibratory (> 0 there).
  double static_moment = 0.0;
  Exciter exciter = Exciter::circular;  ///< the vibratory drum's force direction
};

/// The amplitude of the oscillation moment [N m] the engine uses: 4 m_u e_u e_w nu^2 (5) with
/// nu = 2 pi f when the roller is given by its unbalance (> 0), else roller.M0.
inline double oscillation_moment(const Roller& r) {
  const double nu = 2.0 * std::numbers::pi * r.f;
  return r.unbalance > 0.0 ? 4.0 * r.unbalance * nu * nu : r.M0;
}

/// How the soil is given. Model turns each into the discrete coefficients ksh, ksv, csh, csv
/// (soil_coefficients in oscidrum/soil.hpp); key_in_effect (oscidrum/fields.hpp) says which keys
/// each input reads.
enum class SoilInput {
  coefficients,  ///< directly as the discrete Kelvin-Voigt coefficients ksh, ksv, csh, csv
  modulus,       ///< as continuum (G, nu, rho), converted by Appendix B (42)-(45)
  table2,        ///< the row of paper Table 2 at G (nu = 0.3, rho = 1900 kg/m^3)
};

/// The soil below the drum: the row of paper Table 2 at G (the default, G = 25 MN/m^2),
/// continuum properties or discrete coefficients (see `input`). The default coefficients are
/// Table 2's at G = 25 MN/m^2.
struct Soil {
  SoilInput input = SoilInput::table2;
  double G = 25.0e6;     ///< shear modulus [Pa] (input == modulus or table2)
  double nu = 0.3;       ///< Poisson's ratio [-], 0 <= nu < 0.5 (input == modulus)
  double rho = 1900.0;   ///< density [kg/m^3] (input == modulus)
  double ksh = 41.4e6;   ///< horizontal spring [N/m] (input == coefficients)
  double ksv = 66.3e6;   ///< vertical spring [N/m] (input == coefficients)
  double csh = 141.0e3;  ///< horizontal dashpot [N s/m] (input == coefficients)
  double csv = 263.0e3;  ///< vertical dashpot [N s/m] (input == coefficients)
};

/// The settlement trough: its shape, a component of oscidrum/trough.hpp (the paper's circle of
/// radius 0.606 m by default). The case keys trough.k and trough.a give it as the logarithmic
/// spiral R(theta) = a exp(k theta) (8), k = 0 being the circle of radius a (trough_shape).
struct Trough {
  TroughShape shape;  ///< CircleTrough{0.606} by default
};

/// Which friction law a Contact describes (besides pure_rolling and mu_static, see
/// oscidrum/friction.hpp).
enum class FrictionChoice {
  coulomb,      ///< the paper's Coulomb law (static/kinetic when mu_static is set)
  regularised,  ///< T = -mu tanh(v_rel / v_eps) N: one smooth phase, no stick
};

/// Drum/soil contact.
struct Contact {
  double mu = 0.5;            ///< Coulomb friction coefficient (kinetic: slip) [-], >= 0
  double mu_static = -1.0;    ///< static coefficient (the friction cone) [-]; < 0: equal to mu
  bool pure_rolling = false;  ///< ignore the friction limit (mu -> infinity): stick throughout
  FrictionChoice law = FrictionChoice::coulomb;  ///< the friction law
  double v_eps = 0.01;  ///< regularisation velocity of the regularised law [m/s]
  /// Unilateral contact: the drum may lift off (N reaching 0) and land again (docs/model.md
  /// section 13); false: the paper's permanent contact (N reaching 0 ends the run).
  bool unilateral = false;
};

/// How the periodic steady state is found (docs/periodic.md).
enum class SteadyMethod {
  shooting,   ///< Newton on the period map from a short transient, falling back to transient
  transient,  ///< integrate from rest until the response repeats (the paper's method)
};

/// "shooting", "transient".
const char* to_string(SteadyMethod method);

/// Numerical options of the hybrid integration and the steady-state search.
struct Numerics {
  /// How the steady state is found: shooting by default (it agrees with the paper's transient
  /// method to 1e-7 on every metric of the paper's cases, docs/periodic.md, and is 5-60x faster).
  SteadyMethod method = SteadyMethod::shooting;
  double rtol = 1e-8;                   ///< relative tolerance of the Dormand-Prince steps [-]
  double atol = 1e-11;                  ///< absolute tolerance (SI units of each state) [-]
  int max_periods = 5000;               ///< give up after this many excitation periods [-]
  double steady_tol = 1e-8;             ///< period-to-period change that counts as steady [-]
  int max_multiplicity = 8;             ///< longest steady period searched, in excitation periods
  int output_periods = 2;               ///< steady periods sampled (times the multiplicity) [-]
  int samples_per_period = 1024;        ///< uniform samples per excitation period [-]
  int max_switches_per_period = 200;    ///< more stick/slip switches in one period: chattering
  int max_steps_per_period = 8000;      ///< more steps in one period: budget_exceeded [-]
  double slip_constraint_rate = 0.0;    ///< Baumgarte rate on (39) during slip [1/s]; 0: 2 nu
  bool suspension_from_static = false;  ///< measure kd from static equilibrium (not the paper)
  /// In a study (sweep, run_study) with method shooting: start from the steady state of the
  /// neighbouring case (docs/periodic.md, "Continuation in studies"); ignored by a single run.
  bool continuation = true;
  /// Excitation periods over which the torque M0 sin(nu t) + MMd is ramped in from rest by
  /// (1 - cos(pi t / (n T))) / 2 (0: all at once, the paper's start). A run whose start from rest
  /// loses contact before a steady state is retried with a ramp (docs/periodic.md).
  int start_ramp_periods = 0;
};

/// One simulation case: everything the engine needs.
struct Case {
  Roller roller;
  Soil soil;
  Trough trough;
  Contact contact;
  double MMd = 0.0;  ///< constant driving torque (6) [N m]
  Numerics numerics;
};

}  // namespace oscidrum
