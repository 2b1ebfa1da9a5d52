// The log-spiral trough R(theta) = a exp(k theta), k > 0 (8): the roll curve (15)-(16), its
// derivatives (46)-(50) and the rolling relation (11).
#include <cmath>
#include <limits>

#include "physics/trough_shapes.hpp"
#include "util/format.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {

using detail::shortest;

LogSpiralTrough::LogSpiralTrough(double k, double a) : k_(k), a_(a) {
  alpha_ = std::atan2(1.0, k);          // (8): alpha = arctan(1/k); k = 0 gives pi/2 exactly
  const double theta0 = M_PI - alpha_;  // (8)
  R0_ = a * std::exp(k * theta0);       // (8)
  sin_alpha_ = std::sin(alpha_);
  cos_alpha_ = (k == 0.0) ? 0.0 : std::cos(alpha_);
  root_ = std::sqrt(1.0 + k * k);
}

std::string summary(const LogSpiralTrough& s) {
  return "log spiral, k = " + shortest(s.k()) + ", a = " + shortest(s.a()) + " m";
}

std::vector<TroughParameter> parameters(const LogSpiralTrough& s) {
  return {{"k", s.k(), "-", "trough.k"},
          {"a", s.a(), "m", "trough.a"},
          {"alpha", s.alpha(), "rad", nullptr},
          {"R0", s.R0(), "m", nullptr}};
}

double key_value(const LogSpiralTrough& s, std::string_view key) {
  if (key == "trough.k") return s.k();
  if (key == "trough.a") return s.a();
  return std::numeric_limits<double>::quiet_NaN();
}

double curvature_radius_at_bottom(const LogSpiralTrough& s) { return s.root() * s.R0(); }

const char* curvature_radius_formula(const LogSpiralTrough&) { return "sqrt(1+k^2) R0"; }

FitProblem fit_problem(const LogSpiralTrough& s, double r) {
  // The curvature radius at the bottom, sqrt(1+k^2) R0, must exceed r (f5(0) > 0).
  const double rho = curvature_radius_at_bottom(s);
  if (rho > r) return {};
  return {
      "trough (k, a) must give a curvature radius sqrt(1+k^2) R0 > roller.r at the bottom "
      "[m]; got " +
          shortest(rho) + " <= " + shortest(r),
      "trough.a"};
}

namespace {
// (15), (16), (46)-(50), (33), (37) from E = exp(-k delta), s = sin delta and c = cos delta, for T
// double or lanes (physics/kinematics_lanes.hpp).
template <class T, class K>
void spiral_kinematics(const LogSpiralTrough& g, double r, const T& E, const T& s, const T& c,
                       K& q) {
  const double k = g.k();
  // sin and cos of (alpha + delta) from the addition theorems (alpha is constant).
  const double sa = g.sin_alpha(), ca = g.cos_alpha();
  const T sad = sa * c + ca * s, cad = ca * c - sa * s;
  const T RE = g.R0() * E;

  q.sin_delta = s;
  q.cos_delta = c;
  q.x_roll = -RE * cad - r * s + g.R0() * ca;                  // (15)
  q.z_roll = RE * sad - r * c - (g.R0() * sa - r);             // (16)
  q.f1 = RE * (k * cad + sad) - r * c;                         // (46)
  q.f2 = RE * ((1.0 - k * k) * cad - 2.0 * k * sad) + r * s;   // (47)
  q.f3 = -RE * (k * sad - cad) + r * s;                        // (48)
  q.f4 = -RE * ((1.0 - k * k) * sad + 2.0 * k * cad) + r * c;  // (49)
  q.f5 = g.root() * E * g.R0() / r - 1.0;                      // (50)
  q.f6 = -k * g.root() * E * g.R0() / r;                       // (50)
  detail::set_bar_tilde(q);
}
}  // namespace

Kinematics kinematics(const LogSpiralTrough& g, double r, double delta) {
  Kinematics q;
  const auto [s, c] = detail::sincos_small(delta);
  spiral_kinematics(g, r, std::exp(-g.k() * delta), s, c, q);
  return q;
}

void detail::kinematics(const LogSpiralTrough& g, double r, const KinematicsLanes& delta,
                        KinematicsOf<KinematicsLanes>& k) {
  KinematicsLanes E, s, c;
  for (int j = 0; j < kKinematicsLanes; ++j) E[j] = std::exp(-g.k() * delta[j]);
  sincos_small(delta, s, c);
  spiral_kinematics(g, r, E, s, c, k);
}

KinematicsRates kinematics_rates(const LogSpiralTrough& g, double r, double delta) {
  // Derivatives of (47), (49) and (50), with u = alpha + delta and
  // d exp(-k delta) / d delta = -k exp(-k delta).
  const double k = g.k();
  const double E = std::exp(-k * delta);
  const auto [s, c] = detail::sincos_small(delta);
  const double su = g.sin_alpha() * c + g.cos_alpha() * s;
  const double cu = g.cos_alpha() * c - g.sin_alpha() * s;
  const double RE = g.R0() * E;
  KinematicsRates d;
  d.df2 = RE * ((k * k * k - 3.0 * k) * cu + (3.0 * k * k - 1.0) * su) + r * c;
  d.df4 = -RE * ((k * k * k - 3.0 * k) * su + (1.0 - 3.0 * k * k) * cu) - r * s;
  d.df6 = -k * (-k * g.root() * E * g.R0() / r);
  return d;
}

double phi_rolling(const LogSpiralTrough& g, double r, double delta) {
  // (11): phi = sqrt(1 + k^2) / (k r) R0 [1 - exp(-k delta)] - delta. For small k delta use the
  // series of (1 - exp(-x)) / x to avoid cancellation.
  const double x = g.k() * delta;
  const double ratio = std::abs(x) < 1e-5 ? 1.0 - x / 2.0 + x * x / 6.0 : -std::expm1(-x) / x;
  return g.root() * g.R0() * delta * ratio / r - delta;
}

TroughGap gap(const LogSpiralTrough& g, double r, double x, double z) {
  // M - A - roll(delta) = -gap n(delta), n = (sin, cos): the tangential part of the offset,
  // F(delta) = dx cos - dz sin with (dx, dz) = (x, z) - roll(delta), vanishes. F' = -(r f5 - gap)
  // ((f1, f3) = r f5 (cos, -sin): (33), (37)), so Newton's step is F / (r f5 - gap). Start at the
  // angle of the circle of the bottom's curvature.
  const double rho = curvature_radius_at_bottom(g);
  double delta = std::atan2(x, z + (rho - r));
  for (int i = 0; i < 50; ++i) {
    const Kinematics k = kinematics(g, r, delta);
    const double dx = x - k.x_roll, dz = z - k.z_roll;
    const double F = dx * k.cos_delta - dz * k.sin_delta;
    const double lever = r * k.f5 + (dx * k.sin_delta + dz * k.cos_delta);  // r f5 - gap
    const double step = F / lever;
    delta += step;
    if (std::abs(step) <= 1e-15 * (1.0 + std::abs(delta))) break;
  }
  const Kinematics k = kinematics(g, r, delta);
  return {delta, -((x - k.x_roll) * k.sin_delta + (z - k.z_roll) * k.cos_delta)};
}

}  // namespace oscidrum
