// Internal: what the trough shapes' files share (oscidrum/trough.hpp). Each shape's formulas are
// in its own file, src/physics/trough_<name>.cpp.
#pragma once

#include "oscidrum/kinematics.hpp"

namespace oscidrum::detail {

// (33), (37) from f1 ... f4, shared by the shapes.
inline void set_bar_tilde(Kinematics& q) {
  const double s = q.sin_delta, c = q.cos_delta;
  q.f1_bar = q.f1 * c - q.f3 * s;    // (33)
  q.f2_bar = q.f2 * c - q.f4 * s;    // (33)
  q.f3_tilde = q.f1 * s + q.f3 * c;  // (37)
  q.f4_tilde = q.f2 * s + q.f4 * c;  // (37)
}

}  // namespace oscidrum::detail
