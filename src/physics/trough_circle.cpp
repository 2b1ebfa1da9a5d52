// The circular trough of radius R (k = 0 in (8)): the roll curve (15)-(16) is a circle of
// radius R - r about the trough's centre. The products are written unfactored (R s - r s, not
// (R - r) s) so that they round exactly as the spiral's formulas at k = 0 did, which keeps the
// stored regression profiles bit for bit.
#include <cmath>

#include "physics/trough_shapes.hpp"

namespace oscidrum::detail {

Kinematics circle_kinematics(const TroughGeometry& g, double delta) {
  Kinematics q;
  const double R = g.R0, r = g.r;
  const double s = std::sin(delta), c = std::cos(delta);
  q.sin_delta = s;
  q.cos_delta = c;
  q.x_roll = R * s - r * s;            // (15): (R - r) sin delta
  q.z_roll = R * c - r * c - (R - r);  // (16): (R - r) (cos delta - 1)
  q.f1 = R * c - r * c;                // (46)
  q.f2 = -R * s + r * s;               // (47)
  q.f3 = -R * s + r * s;               // (48)
  q.f4 = -R * c + r * c;               // (49)
  q.f5 = R / r - 1.0;                  // (50): phi' = (R - r) / r delta' in stick
  q.f6 = 0.0;                          // (50)
  set_bar_tilde(q);
  return q;
}

KinematicsRates circle_kinematics_rates(const TroughGeometry& g, double delta) {
  const double R = g.R0, r = g.r;
  KinematicsRates d;
  d.df2 = -R * std::cos(delta) + r * std::cos(delta);
  d.df4 = R * std::sin(delta) - r * std::sin(delta);
  d.df6 = 0.0;
  return d;
}

double circle_phi_rolling(const TroughGeometry& g, double delta) {
  return g.R0 * delta / g.r - delta;  // (11) at k = 0: (R - r) delta / r
}

}  // namespace oscidrum::detail
