// Kinematics of the drum centre relative to the trough: (15), (16), (46)-(50), (33), (37), (11).
#include "oscidrum/kinematics.hpp"

#include <cmath>

namespace oscidrum {

TroughGeometry make_trough_geometry(double r, double k, double a) {
  TroughGeometry g;
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

Kinematics kinematics(const TroughGeometry& g, double delta) {
  Kinematics q;
  const double k = g.k, r = g.r;
  const double E = (k == 0.0) ? 1.0 : std::exp(-k * delta);
  const double s = std::sin(delta), c = std::cos(delta);
  // sin and cos of (alpha + delta) from the addition theorems (alpha is constant).
  const double sa = g.sin_alpha, ca = g.cos_alpha;
  const double sad = sa * c + ca * s, cad = ca * c - sa * s;
  const double RE = g.R0 * E;

  q.sin_delta = s;
  q.cos_delta = c;
  q.x_roll = -RE * cad - r * s + g.R0 * ca;                    // (15)
  q.z_roll = RE * sad - r * c - (g.R0 * sa - r);               // (16)
  q.f1 = RE * (k * cad + sad) - r * c;                         // (46)
  q.f2 = RE * ((1.0 - k * k) * cad - 2.0 * k * sad) + r * s;   // (47)
  q.f3 = -RE * (k * sad - cad) + r * s;                        // (48)
  q.f4 = -RE * ((1.0 - k * k) * sad + 2.0 * k * cad) + r * c;  // (49)
  const double root = g.root;
  q.f5 = root * E * g.R0 / r - 1.0;  // (50)
  q.f6 = -k * root * E * g.R0 / r;   // (50)
  q.f1_bar = q.f1 * c - q.f3 * s;    // (33)
  q.f2_bar = q.f2 * c - q.f4 * s;    // (33)
  q.f3_tilde = q.f1 * s + q.f3 * c;  // (37)
  q.f4_tilde = q.f2 * s + q.f4 * c;  // (37)
  return q;
}

double phi_rolling(const TroughGeometry& g, double delta) {
  // (11): phi = sqrt(1 + k^2) / (k r) R0 [1 - exp(-k delta)] - delta. For small k delta use the
  // series of (1 - exp(-x)) / x to avoid cancellation; k = 0 gives (R0 - r) delta / r.
  const double x = g.k * delta;
  double ratio;  // (1 - exp(-x)) / x
  if (std::abs(x) < 1e-5) {
    ratio = 1.0 - x / 2.0 + x * x / 6.0;
  } else {
    ratio = -std::expm1(-x) / x;
  }
  return std::sqrt(1.0 + g.k * g.k) * g.R0 * delta * ratio / g.r - delta;
}

}  // namespace oscidrum
