// The event functions of the hybrid flow (src/flow/event_functions.hpp), written once for one
// state (double) and for lanes of states (util/lanes.hpp), the same operations in each lane.
#include "flow/event_functions.hpp"

#include <algorithm>

#include "equations/phase_equations.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {

namespace {

// The event functions from the contact forces (24)-(26) at q with s = sin delta, c = cos delta;
// slip_velocity() gives (13) where a slip phase asks for it.
template <class T, class Q, class SlipVelocity>
std::array<T, kEventCount> event_values_of(const Model& model, Phase phase, const Q& q, const T& s,
                                           const T& c, SlipVelocity slip_velocity, T& N) {
  T Tf;
  detail::soil_contact_forces(model, q, s, c, N, Tf);
  const double W = model.W();
  std::array<T, kEventCount> e{T(1.0), T(1.0), N / W};
  // The friction law decides which switches exist: the cone in stick (none without a limit), the
  // end of slip in a slip phase (none without friction, and none in the smooth phase of a
  // regularised law, which has no stick).
  if (phase == Phase::stick) {
    if (model.friction_phases() == FrictionPhases::stick_slip) {
      e[kEventConeNegative] = (model.cone() * N - Tf) / W;
      e[kEventConePositive] = (model.cone() * N + Tf) / W;
    }
  } else if (phase != Phase::smooth && model.cone() > 0.0) {
    const double v_scale = model.r() * model.nu() * 1e-3;  // 1 mrad amplitude at nu
    e[kEventSlipVelocity] =
        static_cast<double>(static_cast<int>(phase)) * slip_velocity() / v_scale;
  }
  return e;
}

}  // namespace

EventValues event_values(const Model& model, Phase phase, const State& q, double* N) {
  const auto [s, c] = detail::sincos_small(q.delta);
  double normal = 0.0;
  const EventValues e = event_values_of<double>(
      model, phase, q, s, c, [&] { return slip_velocity(model, q); }, normal);
  if (N != nullptr) *N = normal;
  return e;
}

void event_values(const Model& model, Phase phase, const std::array<double, 8>* x, int n,
                  EventValues* e, double* N) {
  constexpr int kLanes = detail::kKinematicsLanes;
  using L = detail::KinematicsLanes;
  for (int i0 = 0; i0 < n; i0 += kLanes) {
    const int m = std::min(kLanes, n - i0);
    detail::StateOf<L> q;
    for (int j = 0; j < kLanes; ++j)  // unused lanes repeat the last state
      detail::set_lane(q, j, x[i0 + std::min(j, m - 1)]);
    L s, c, normal;
    detail::sincos_small(q.delta, s, c);
    const auto slip_velocity = [&] {
      detail::KinematicsOf<L> k;
      detail::kinematics(model.geometry(), q.delta, k);
      return detail::slip_velocity_of<L>(model, q, k);
    };
    const std::array<L, kEventCount> lanes =
        event_values_of<L>(model, phase, q, s, c, slip_velocity, normal);
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < kEventCount; ++i) e[i0 + j][i] = lanes[i][j];
      N[i0 + j] = normal[j];
    }
  }
}

}  // namespace oscidrum
