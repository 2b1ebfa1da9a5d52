// Internal: the kinematics (15)-(16), (46)-(50), (33), (37) at kKinematicsLanes angles at once
// (util/lanes.hpp), for the output's samples: lane j holds kinematics(g, delta[j]) to the bit. A
// shape computes them in lanes where its file has a lanes version (the circle and the spiral,
// whose formulas are written once for both), otherwise angle by angle.
#pragma once

#include "oscidrum/kinematics.hpp"
#include "util/lanes.hpp"

namespace oscidrum::detail {

/// The quantities of Kinematics as T.
template <class T>
struct KinematicsOf {
  T x_roll, z_roll, f1, f2, f3, f4, f5, f6, sin_delta, cos_delta, f1_bar, f2_bar, f3_tilde,
      f4_tilde;
};

/// Lane j of k from one point's kinematics.
template <int N>
inline void set_lane(KinematicsOf<Lanes<N>>& k, int j, const Kinematics& q) {
  k.x_roll[j] = q.x_roll;
  k.z_roll[j] = q.z_roll;
  k.f1[j] = q.f1;
  k.f2[j] = q.f2;
  k.f3[j] = q.f3;
  k.f4[j] = q.f4;
  k.f5[j] = q.f5;
  k.f6[j] = q.f6;
  k.sin_delta[j] = q.sin_delta;
  k.cos_delta[j] = q.cos_delta;
  k.f1_bar[j] = q.f1_bar;
  k.f2_bar[j] = q.f2_bar;
  k.f3_tilde[j] = q.f3_tilde;
  k.f4_tilde[j] = q.f4_tilde;
}

inline constexpr int kKinematicsLanes = 8;
using KinematicsLanes = Lanes<kKinematicsLanes>;

/// kinematics(g, delta[j]) in lane j of k.
void kinematics(const TroughGeometry& g, const KinematicsLanes& delta,
                KinematicsOf<KinematicsLanes>& k);

}  // namespace oscidrum::detail
