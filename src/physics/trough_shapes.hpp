// Internal: what the trough shapes' files share (oscidrum/trough.hpp). Each shape's formulas are
// in its own file, src/physics/trough_<name>.cpp.
#pragma once

#include "oscidrum/kinematics.hpp"
#include "oscidrum/trough.hpp"
#include "physics/kinematics_lanes.hpp"

namespace oscidrum::detail {

// (33), (37) from f1 ... f4, shared by the shapes (Kinematics, or KinematicsOf lanes).
template <class K>
inline void set_bar_tilde(K& q) {
  const auto s = q.sin_delta, c = q.cos_delta;
  q.f1_bar = q.f1 * c - q.f3 * s;    // (33)
  q.f2_bar = q.f2 * c - q.f4 * s;    // (33)
  q.f3_tilde = q.f1 * s + q.f3 * c;  // (37)
  q.f4_tilde = q.f2 * s + q.f4 * c;  // (37)
}

// The shapes' own kinematics in lanes (physics/kinematics_lanes.hpp); optional: a shape without
// one is evaluated angle by angle.
void kinematics(const CircleTrough& s, double r, const KinematicsLanes& delta,
                KinematicsOf<KinematicsLanes>& k);
void kinematics(const LogSpiralTrough& s, double r, const KinematicsLanes& delta,
                KinematicsOf<KinematicsLanes>& k);

}  // namespace oscidrum::detail
