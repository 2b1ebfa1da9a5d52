// evib.cpp: the Evib-type vibration modulus (docs/outputs.md): the Young's modulus E of an elastic
// half-space under which Lundberg's (1939) rigid cylinder would settle as the drum does on the
// loading branch of its contact force - displacement loop (Kroeber, Floss and Wallrath 2001,
// BOMAG's Evib; described in Mooney and Adam 2007 and Adam and Kopf 2004).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string>

#include "oscidrum/error.hpp"
#include "oscidrum/metrics.hpp"

namespace oscidrum {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kLundbergConstant = 1.8864;  // Lundberg (1939), as quoted for Evib

void require_geometry(double R, double L, double nu, const char* where) {
  if (!(R > 0.0) || !std::isfinite(R))
    throw Error(std::string(where) + ": the drum radius R must be > 0 [m]; got " +
                std::to_string(R));
  if (!(L > 0.0) || !std::isfinite(L))
    throw Error(std::string(where) + ": the drum length L must be > 0 [m]; got " +
                std::to_string(L));
  if (!(nu >= 0.0 && nu < 0.5))
    throw Error(std::string(where) + ": Poisson's ratio nu must be in [0, 0.5); got " +
                std::to_string(nu));
}

// F (1.8864 + ln L - ln(b) at E = 1): z_L(F; E) = c / E (a(F) + F ln(E) / 2) with
// c = (1 - nu^2) (2 / pi) / L and b(F; E) = sqrt(16 R (1 - nu^2) F / (pi L E)); 0 at F = 0.
double lundberg_term(double F, double R, double L, double nu) {
  if (F == 0.0) return 0.0;
  const double b1 = std::sqrt(16.0 * R * (1.0 - nu * nu) * F / (std::numbers::pi * L));
  return F * (kLundbergConstant + std::log(L / b1));
}

}  // namespace

double lundberg_displacement(double F, double E, double R, double L, double nu) {
  require_geometry(R, L, nu, "lundberg_displacement");
  if (!(F >= 0.0) || !std::isfinite(F))
    throw Error("lundberg_displacement: the force F must be >= 0 [N]; got " + std::to_string(F));
  if (!(E > 0.0) || !std::isfinite(E))
    throw Error("lundberg_displacement: the modulus E must be > 0 [Pa]; got " + std::to_string(E));
  if (F == 0.0) return 0.0;
  const double b = std::sqrt(16.0 * R * (1.0 - nu * nu) * F / (std::numbers::pi * L * E));
  return (1.0 - nu * nu) / E * F / L * (2.0 / std::numbers::pi) *
         (kLundbergConstant + std::log(L / b));
}

double lundberg_modulus(double F1, double z1, double F2, double z2, double R, double L, double nu) {
  require_geometry(R, L, nu, "lundberg_modulus");
  if (!(F1 >= 0.0) || !(F2 > F1) || !(z2 > z1) || !std::isfinite(F2) || !std::isfinite(z1) ||
      !std::isfinite(z2))
    return kNaN;
  // z2 - z1 = c e^{-u} (A + D u / 2), u = ln E, A = a(F2) - a(F1), D = F2 - F1: the fixed point
  // of u = ln(c (A + D u / 2) / (z2 - z1)), a contraction of factor D / (2 (A + D u / 2)) =
  // 1 / (2 (mean over [F1, F2] of 1.8864 + ln(L / b)) - 1), below 0.2 wherever b < L / 4.
  const double c = (1.0 - nu * nu) * (2.0 / std::numbers::pi) / L;
  const double A = lundberg_term(F2, R, L, nu) - lundberg_term(F1, R, L, nu);
  const double D = F2 - F1, dz = z2 - z1;
  double u = std::log(c * std::max(A, D) / dz);
  for (int k = 0; k < 200; ++k) {
    const double s = A + 0.5 * D * u;
    if (!(s > 0.0)) return kNaN;
    const double next = std::log(c * s / dz);
    if (!std::isfinite(next)) return kNaN;
    const bool done = std::abs(next - u) <= 1e-15 * std::max(1.0, std::abs(next));
    u = next;
    if (done) break;
  }
  // The root is kept only where the map contracts by at least 1/2 (the mean of
  // 1.8864 + ln(L / b) over the branch above 1.5: a contact strip b narrower than about 1.5 L);
  // beyond that Lundberg's strip would be wider than the drum is long.
  const double s = A + 0.5 * D * u;
  if (!(s > D)) return kNaN;
  return std::exp(u);
}

double vibration_modulus(std::span<const double> z, std::span<const double> F, double R, double L,
                         double nu) {
  require_geometry(R, L, nu, "vibration_modulus");
  const std::size_t n = z.size();
  if (F.size() != n)
    throw Error("vibration_modulus: z has " + std::to_string(n) + " points and F " +
                std::to_string(F.size()) + "; expected the same number");
  if (n < 3) return kNaN;
  for (std::size_t j = 0; j < n; ++j)
    if (!std::isfinite(z[j]) || !std::isfinite(F[j])) return kNaN;
  // The loading branch: from the drum's highest position (least z, z downwards) forward in time
  // to its lowest (largest z), the drum moving into the soil.
  const std::size_t lo = static_cast<std::size_t>(std::min_element(z.begin(), z.end()) - z.begin());
  const std::size_t hi = static_cast<std::size_t>(std::max_element(z.begin(), z.end()) - z.begin());
  const std::size_t len = (hi + n - lo) % n + 1;  // points of the branch, both ends included
  if (len < 2) return kNaN;
  const auto at = [&](std::size_t k) { return (lo + k) % n; };
  // Its point of largest contact force (the first, if several).
  std::size_t k_max = 0;
  for (std::size_t k = 1; k < len; ++k)
    if (F[at(k)] > F[at(k_max)]) k_max = k;
  const double F2 = F[at(k_max)], z2 = z[at(k_max)];
  if (!(F2 > 0.0)) return kNaN;
  // Where the loading starts: the landing (the last point before the maximum without contact
  // force, F <= 0, and the next, interpolated linearly to F = 0) after a flight, else the branch's
  // first point (continuous contact: the force there is the least of the loading).
  double F1 = F[at(0)], z1 = z[at(0)];
  for (std::size_t k = k_max; k-- > 0;) {
    if (F[at(k)] <= 0.0) {
      const double Fa = F[at(k)], Fb = F[at(k + 1)];
      const double w = Fb > Fa ? -Fa / (Fb - Fa) : 0.0;
      F1 = 0.0;
      z1 = z[at(k)] + w * (z[at(k + 1)] - z[at(k)]);
      break;
    }
  }
  return lundberg_modulus(F1, z1, F2, z2, R, L, nu);
}

}  // namespace oscidrum
