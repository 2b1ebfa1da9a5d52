// The circular trough of radius R (k = 0 in (8)): the roll curve (15)-(16) is a circle of
// radius R - r about the trough's centre. The products are written unfactored (R s - r s, not
// (R - r) s) so that they round exactly as the spiral's formulas at k = 0 did, which keeps the
// stored regression profiles bit for bit.
#include <cmath>
#include <limits>

#include "physics/trough_shapes.hpp"
#include "util/format.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {

using detail::shortest;

std::string summary(const CircleTrough& s) { return "circle, R = " + shortest(s.R) + " m"; }

std::vector<TroughParameter> parameters(const CircleTrough& s) {
  return {{"R", s.R, "m", "trough.a"}};
}

double key_value(const CircleTrough& s, std::string_view key) {
  if (key == "trough.k") return 0.0;  // the circle is the spiral family's k = 0
  if (key == "trough.a") return s.R;
  return std::numeric_limits<double>::quiet_NaN();
}

double curvature_radius_at_bottom(const CircleTrough& s) { return s.R; }

const char* curvature_radius_formula(const CircleTrough&) { return "trough.a"; }

FitProblem fit_problem(const CircleTrough& s, double r) {
  if (s.R > r) return {};
  return {
      "trough.a must be > roller.r for a circular trough (k = 0): the trough radius R = a "
      "must exceed the drum radius [m]; got a = " +
          shortest(s.R) + " <= r = " + shortest(r),
      "trough.a"};
}

namespace {
// (15), (16), (46)-(50), (33), (37) from s = sin delta and c = cos delta, for T double or lanes.
template <class T, class K>
void circle_kinematics(double R, double r, const T& s, const T& c, K& q) {
  q.sin_delta = s;
  q.cos_delta = c;
  q.x_roll = R * s - r * s;            // (15): (R - r) sin delta
  q.z_roll = R * c - r * c - (R - r);  // (16): (R - r) (cos delta - 1)
  q.f1 = R * c - r * c;                // (46)
  q.f2 = -R * s + r * s;               // (47)
  q.f3 = -R * s + r * s;               // (48)
  q.f4 = -R * c + r * c;               // (49)
  q.f5 = T(R / r - 1.0);               // (50): phi' = (R - r) / r delta' in stick
  q.f6 = T(0.0);                       // (50)
  detail::set_bar_tilde(q);
}
}  // namespace

Kinematics kinematics(const CircleTrough& trough, double r, double delta) {
  Kinematics q;
  const auto [s, c] = detail::sincos_small(delta);
  circle_kinematics(trough.R, r, s, c, q);
  return q;
}

void detail::kinematics(const CircleTrough& trough, double r, const KinematicsLanes& delta,
                        KinematicsOf<KinematicsLanes>& k) {
  KinematicsLanes s, c;
  sincos_small(delta, s, c);
  circle_kinematics(trough.R, r, s, c, k);
}

KinematicsRates kinematics_rates(const CircleTrough& trough, double r, double delta) {
  const double R = trough.R;
  KinematicsRates d;
  const auto [s, c] = detail::sincos_small(delta);
  d.df2 = -R * c + r * c;
  d.df4 = R * s - r * s;
  d.df6 = 0.0;
  return d;
}

double phi_rolling(const CircleTrough& trough, double r, double delta) {
  return trough.R * delta / r - delta;  // (11) at k = 0: (R - r) delta / r
}

TroughGap gap(const CircleTrough& trough, double r, double x, double z) {
  // The centre M = O + (R - r - gap) (sin delta, cos delta), O = (0, -(R - r)) from A (z down).
  const double c = trough.R - r;
  const double dx = x, dz = z + c;
  return {std::atan2(dx, dz), c - std::hypot(dx, dz)};
}

}  // namespace oscidrum
