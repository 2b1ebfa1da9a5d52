// Kinematics of the drum centre relative to the trough: (15), (16), (46)-(50), (33), (37), (11),
// dispatched on the trough's shape (oscidrum/trough.hpp; each shape's formulas are in its file,
// src/physics/trough_<name>.cpp).
#include "oscidrum/kinematics.hpp"

#include <variant>

#include "physics/trough_shapes.hpp"

namespace oscidrum {

TroughGeometry make_trough_geometry(double r, double k, double a) {
  return TroughGeometry{trough_shape(k, a), r};
}

Kinematics kinematics(const TroughGeometry& g, double delta) {
  return std::visit([&](const auto& s) { return kinematics(s, g.r, delta); }, g.shape);
}

void detail::kinematics(const TroughGeometry& g, const KinematicsLanes& delta,
                        KinematicsOf<KinematicsLanes>& k) {
  std::visit(
      [&](const auto& s) {
        if constexpr (requires { detail::kinematics(s, g.r, delta, k); }) {
          detail::kinematics(s, g.r, delta, k);
        } else {
          for (int j = 0; j < kKinematicsLanes; ++j) {
            set_lane(k, j, oscidrum::kinematics(s, g.r, delta[j]));
          }
        }
      },
      g.shape);
}

KinematicsRates kinematics_rates(const TroughGeometry& g, double delta) {
  return std::visit([&](const auto& s) { return kinematics_rates(s, g.r, delta); }, g.shape);
}

double phi_rolling(const TroughGeometry& g, double delta) {
  return std::visit([&](const auto& s) { return phi_rolling(s, g.r, delta); }, g.shape);
}

}  // namespace oscidrum
