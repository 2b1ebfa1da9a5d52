// Internal: the kinematics of each trough shape (oscidrum/trough.hpp). kinematics.cpp dispatches
// on the shape; each shape's file holds its formulas.
#pragma once

#include "oscidrum/kinematics.hpp"

namespace oscidrum::detail {

// The circle (src/physics/trough_circle.cpp).
Kinematics circle_kinematics(const TroughGeometry& g, double delta);
KinematicsRates circle_kinematics_rates(const TroughGeometry& g, double delta);
double circle_phi_rolling(const TroughGeometry& g, double delta);

// The log spiral (src/physics/trough_log_spiral.cpp).
Kinematics log_spiral_kinematics(const TroughGeometry& g, double delta);
KinematicsRates log_spiral_kinematics_rates(const TroughGeometry& g, double delta);
double log_spiral_phi_rolling(const TroughGeometry& g, double delta);

// (33), (37) from f1 ... f4, shared by the shapes.
inline void set_bar_tilde(Kinematics& q) {
  const double s = q.sin_delta, c = q.cos_delta;
  q.f1_bar = q.f1 * c - q.f3 * s;    // (33)
  q.f2_bar = q.f2 * c - q.f4 * s;    // (33)
  q.f3_tilde = q.f1 * s + q.f3 * c;  // (37)
  q.f4_tilde = q.f2 * s + q.f4 * c;  // (37)
}

}  // namespace oscidrum::detail
