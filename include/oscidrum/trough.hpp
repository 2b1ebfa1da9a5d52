// oscidrum/trough.hpp: the settlement trough's shape as a component (docs/model.md section 1.4).
// Each shape owns its roll curve (15)-(16), the derivatives (46)-(50) and their rates, the
// rolling relation (11), its curvature at the bottom and its checks; a new shape is one more
// type here, its file in src/physics/ and its tests.
#pragma once

#include <string>
#include <variant>

namespace oscidrum {

/// Circular trough of radius R (the paper's circle, k = 0 in (8)).
struct CircleTrough {
  double R = 0.606;  ///< trough radius [m]
};

/// Log-spiral trough R(theta) = a exp(k theta), k > 0 (8), with alpha = atan(1/k),
/// theta0 = pi - alpha and R0 = a exp(k theta0), the radius at the bottom.
struct LogSpiralTrough {
  double k = 0.002;  ///< spiral parameter [-]
  double a = 0.606;  ///< spiral parameter [m]
};

using TroughShape = std::variant<CircleTrough, LogSpiralTrough>;

/// The shape trough.k and trough.a describe: the circle of radius a for k = 0, else the spiral.
TroughShape trough_shape(double k, double a);

/// Radius of curvature of the trough at its bottom (delta = 0) [m]: R for the circle,
/// sqrt(1 + k^2) R0 for the spiral. The drum rolls inside only if it exceeds the drum radius.
double curvature_radius_at_bottom(const TroughShape& shape);

/// Why a drum of radius r [m] cannot roll in the trough ("" if it can), naming the keys.
std::string trough_problem(const TroughShape& shape, double r);

}  // namespace oscidrum
