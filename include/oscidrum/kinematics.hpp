// oscidrum/kinematics.hpp: the drum centre relative to the trough, (15)-(16), and its
// derivatives f1 ... f6 (46)-(50), plus the shorthands (33) and (37).
#pragma once

#include "oscidrum/trough.hpp"

namespace oscidrum {

/// The trough's shape with the drum radius: what the kinematics need (docs/model.md section 1.4).
/// The shape holds its own parameters and derived values (oscidrum/trough.hpp).
struct TroughGeometry {
  TroughShape shape;  ///< the kinematics dispatch on it
  double r = 0.6;     ///< drum radius [m]
};

/// The geometry of a drum of radius r [m] in the trough that trough.k and trough.a describe
/// (trough_shape: k = 0 is the circle of radius a).
TroughGeometry make_trough_geometry(double r, double k, double a);

/// Everything that depends on delta alone.
struct Kinematics {
  double x_roll = 0.0;  ///< (15) [m]
  double z_roll = 0.0;  ///< (16) [m]
  double f1 = 0.0;      ///< (46) d x_roll / d delta [m]
  double f2 = 0.0;      ///< (47) d f1 / d delta [m]
  double f3 = 0.0;      ///< (48) d z_roll / d delta [m]
  double f4 = 0.0;      ///< (49) d f3 / d delta [m]
  double f5 = 0.0;      ///< (50) phi' = f5 delta' in stick [-]
  double f6 = 0.0;      ///< (50) d f5 / d delta [-]
  double sin_delta = 0.0;
  double cos_delta = 1.0;
  double f1_bar = 0.0;    ///< (33) f1 cos - f3 sin (identically r f5)
  double f2_bar = 0.0;    ///< (33) f2 cos - f4 sin
  double f3_tilde = 0.0;  ///< (37) f1 sin + f3 cos (identically 0)
  double f4_tilde = 0.0;  ///< (37) f2 sin + f4 cos (identically -f1_bar)
};

/// Evaluate (15), (16), (46)-(50), (33), (37) at delta [rad], by the shape's own formulas
/// (std::visit on the shape).
Kinematics kinematics(const TroughGeometry& geometry, double delta);

/// Third derivatives of the roll curves (15), (16), for the Jacobians of the equations of motion.
struct KinematicsRates {
  double df2 = 0.0;  ///< d f2 / d delta (derivative of (47)) [m]
  double df4 = 0.0;  ///< d f4 / d delta (derivative of (49)) [m]
  double df6 = 0.0;  ///< d f6 / d delta (derivative of (50)) [1/rad]
};
KinematicsRates kinematics_rates(const TroughGeometry& geometry, double delta);

/// Rolling condition (11): phi as a function of delta with no slip since t = 0 [rad], by the
/// shape's own formula.
double phi_rolling(const TroughGeometry& geometry, double delta);

}  // namespace oscidrum
