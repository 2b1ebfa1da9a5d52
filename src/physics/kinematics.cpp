// Kinematics of the drum centre relative to the trough: (15), (16), (46)-(50), (33), (37), (11),
// dispatched on the trough's shape (oscidrum/trough.hpp; the formulas in trough_circle.cpp and
// trough_log_spiral.cpp).
#include "oscidrum/kinematics.hpp"

#include <cmath>
#include <type_traits>
#include <variant>

#include "physics/trough_shapes.hpp"
#include "util/format.hpp"

namespace oscidrum {

TroughShape trough_shape(double k, double a) {
  if (k == 0.0) return CircleTrough{a};
  return LogSpiralTrough{k, a};
}

TroughGeometry make_trough_geometry(double r, double k, double a) {
  TroughGeometry g;
  g.shape = trough_shape(k, a);
  g.r = r;
  g.k = k;
  g.a = a;
  // alpha = arctan(1/k) (8); k = 0 gives pi/2 exactly.
  g.alpha = std::atan2(1.0, k);
  const double theta0 = M_PI - g.alpha;  // (8)
  g.R0 = a * std::exp(k * theta0);
  g.sin_alpha = std::sin(g.alpha);
  g.cos_alpha = (k == 0.0) ? 0.0 : std::cos(g.alpha);
  g.root = std::sqrt(1.0 + k * k);
  return g;
}

double curvature_radius_at_bottom(const TroughShape& shape) {
  return std::visit(
      [](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, CircleTrough>) {
          return s.R;
        } else {
          const double alpha = std::atan2(1.0, s.k);               // (8)
          const double R0 = s.a * std::exp(s.k * (M_PI - alpha));  // (8), theta0 = pi - alpha
          return std::sqrt(1.0 + s.k * s.k) * R0;
        }
      },
      shape);
}

std::string trough_problem(const TroughShape& shape, double r) {
  using detail::shortest;
  if (const auto* circle = std::get_if<CircleTrough>(&shape)) {
    if (!(circle->R > r))
      return "trough.a must be > roller.r for a circular trough (k = 0): the trough radius R = a "
             "must exceed the drum radius [m]; got a = " +
             shortest(circle->R) + " <= r = " + shortest(r);
    return "";
  }
  // The spiral's curvature radius at the bottom, sqrt(1+k^2) R0, must exceed r (f5(0) > 0).
  const double rho = curvature_radius_at_bottom(shape);
  if (!(rho > r))
    return "trough (k, a) must give a curvature radius sqrt(1+k^2) R0 > roller.r at the bottom "
           "[m]; got " +
           shortest(rho) + " <= " + shortest(r);
  return "";
}

Kinematics kinematics(const TroughGeometry& g, double delta) {
  return std::holds_alternative<CircleTrough>(g.shape) ? detail::circle_kinematics(g, delta)
                                                       : detail::log_spiral_kinematics(g, delta);
}

KinematicsRates kinematics_rates(const TroughGeometry& g, double delta) {
  return std::holds_alternative<CircleTrough>(g.shape)
             ? detail::circle_kinematics_rates(g, delta)
             : detail::log_spiral_kinematics_rates(g, delta);
}

double phi_rolling(const TroughGeometry& g, double delta) {
  return std::holds_alternative<CircleTrough>(g.shape) ? detail::circle_phi_rolling(g, delta)
                                                       : detail::log_spiral_phi_rolling(g, delta);
}

}  // namespace oscidrum
