// oscidrum/model.hpp: a validated Case with its derived constants, and the equations of motion.
#pragma once

#include "oscidrum/friction.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/state.hpp"

namespace oscidrum {

/// The external load on the drum centre M besides the buffers and the soil: the paper's static
/// load W (19), (20) and, for the vibratory drum, the unbalance force F(t) (docs/model.md
/// section 14). Every equation of motion reads it in place of W and of a zero horizontal force.
struct CentreLoad {
  double x = 0.0;  ///< horizontal force F_x(t) [N] (0 for the oscillation drum)
  double z = 0.0;  ///< vertical force, downwards: W + F_z(t) [N] (W for the oscillation drum)
};

/// An immutable, validated model: the Case plus the constants derived from it. Construction
/// checks every field and throws oscidrum::Error naming the field, the rule and the value.
class Model {
 public:
  explicit Model(const Case& c);

  const Case& parameters() const { return case_; }
  const TroughGeometry& geometry() const { return geometry_; }

  double m() const { return case_.roller.m; }
  double I() const { return case_.roller.I; }
  double r() const { return case_.roller.r; }
  double kd() const { return case_.roller.kd; }
  double cd() const { return case_.roller.cd; }
  double ksh() const { return ksh_; }  ///< [N/m]
  double ksv() const { return ksv_; }  ///< [N/m]
  double csh() const { return csh_; }  ///< [N s/m]
  double csv() const { return csv_; }  ///< [N s/m]
  /// The friction law at the contact (oscidrum/friction.hpp): the equations, the events and the
  /// steady-state search ask it, never the contact's coefficients directly.
  const FrictionLaw& friction() const { return friction_; }
  /// Its cone coefficient, stick while |T| <= cone N (28) [-] (cone_coefficient, cached).
  double cone() const { return cone_; }
  /// Its phases (friction_phases, cached).
  FrictionPhases friction_phases() const { return phases_; }
  double W() const { return W_; }    ///< m g + Fz (= P0) [N]
  double Fz() const { return Fz_; }  ///< P0 - m g (7) [N]
  double nu() const { return nu_; }  ///< excitation circular frequency 2 pi f [rad/s]
  double period() const { return 1.0 / case_.roller.f; }  ///< excitation period [s]
  double z_ref() const { return z_ref_; }  ///< suspension reference of z_M (0 as in the paper) [m]

  /// Total excitation MM(t) = M0 sin(nu t) + MMd (5, 6) [N m], times the start ramp
  /// (1 - cos(pi t / t_ramp)) / 2 for t < t_ramp = numerics.start_ramp_periods T.
  double torque(double t) const;

  /// The angle of the excitation at time t, nu t wrapped to [0, 2 pi) [rad]: the oscillation
  /// moment is M0 sin(angle) (5), the vibratory drum's vertical unbalance force F0 sin(angle)
  /// (every Exciter), the angle `analyze --unbalance-col` expects (oscidrum/record.hpp). Not
  /// ramped: the start ramp scales the amplitudes only.
  double excitation_angle(double t) const;

  /// The load on M at time t (CentreLoad): W and 0 for the oscillation drum; for the vibratory
  /// drum W + F_z(t) and F_x(t), F = m_u e_u nu^2 times the exciter's direction (Exciter), ramped
  /// in as the torque is.
  CentreLoad centre_load(double t) const;
  /// torque(t), excitation_angle(t) and centre_load(t) at the n times t[0 ... n-1] into MM, angle
  /// and load (the same values; the output's samples ask for all three at many times).
  void excitation(const double* t, int n, double* MM, double* angle, CentreLoad* load) const;
  /// The vibratory drum's unbalance force amplitude F0 = m_u e_u nu^2 [N] (0 for the oscillation
  /// drum).
  double F0() const { return F0_; }

  /// The initial state: at rest at the bottom of the trough, s_A = (W + kd z_ref)/(ksv + kd).
  State initial_state() const;

 private:
  Case case_;
  TroughGeometry geometry_;
  FrictionLaw friction_;
  double cone_;
  FrictionPhases phases_;
  double ksh_, ksv_, csh_, csv_;
  double W_, Fz_, nu_, z_ref_;
  double ramp_end_;  ///< the end of the start ramp, numerics.start_ramp_periods T (0: none) [s]
  double M0_;        ///< oscillation_moment(roller) (5); 0 for the vibratory drum [N m]
  double F0_;        ///< m_u e_u nu^2 for the vibratory drum, else 0 [N]

  double torque_at(double t) const;
  double excitation_angle_at(double t) const;
};

/// Normal and tangential contact forces at C. The soil is massless, so both are functions of
/// the state alone: N (26), T from (24)-(25).
struct ContactForces {
  double N = 0.0;  ///< [N]
  double T = 0.0;  ///< [N]
};
ContactForces contact_forces(const Model& model, const State& q);

/// Slip velocity (13): v_rel = r f5 delta' - r phi' [m/s].
double slip_velocity(const Model& model, const State& q);

/// Stick phase (30)-(32) solved for (delta'', x_A'', s_A''); phi'' = f5 delta'' + f6 delta'^2
/// (12).
Accelerations stick_accelerations(const Model& model, double t, const State& q);

/// Slip phase (34), (38), (53), (36) solved for (delta'', x_A'', s_A'', phi''); s = +1 or -1 is
/// sign(v_rel), 0 the smooth phase of a regularised law. T = -m N with m the friction law's slip
/// coefficient at v_rel (s mu for Coulomb's law). `baumgarte` [1/s] adds rate * residual(39) to
/// (53) so that drift decays.
Accelerations slip_accelerations(const Model& model, double t, const State& q, int s,
                                 double baumgarte = 0.0);

/// Residual of the slip coupling (39): fmu1 (csh x_A' + ksh x_A) - fmu2 (csv s_A' + ksv s_A) [N],
/// fmu1 = cos - m sin, fmu2 = sin + m cos (35), m the law's slip coefficient in a slip phase of
/// sign s (0: the smooth phase) at the state's v_rel.
double slip_constraint_residual(const Model& model, const State& q, int s);

/// Drum-centre displacement (14), velocity (17) and acceleration (18).
struct DrumMotion {
  double x_M = 0.0, z_M = 0.0;      ///< [m]
  double dx_M = 0.0, dz_M = 0.0;    ///< [m/s]
  double ddx_M = 0.0, ddz_M = 0.0;  ///< [m/s^2]
};
DrumMotion drum_motion(const Model& model, const State& q, const Accelerations& a);

/// Accelerations of the given phase (stick, slip with s = phase, or the smooth phase).
Accelerations accelerations(const Model& model, double t, const State& q, Phase phase,
                            double baumgarte = 0.0);

}  // namespace oscidrum
