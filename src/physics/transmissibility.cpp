// Appendix A: absolute displacement transmissibility of the frame on the suspension (40).
#include "oscidrum/transmissibility.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "oscidrum/error.hpp"
#include "util/format.hpp"

namespace oscidrum {

Transmissibility transmissibility(double kd, double cd, double m_f, double nu) {
  auto check = [](const char* name, double v, bool allow_zero) {
    if (!std::isfinite(v) || v < 0 || (!allow_zero && v == 0)) {
      throw Error(std::string(name) + (allow_zero ? " must be >= 0" : " must be > 0") + "; got " +
                  detail::shortest(v));
    }
  };
  check("kd", kd, false);
  check("cd", cd, true);
  check("m_f", m_f, false);
  check("nu", nu, false);
  Transmissibility t;
  t.omega = std::sqrt(kd / m_f);
  t.zeta = cd / (2.0 * m_f * t.omega);
  t.ratio = nu / t.omega;
  const double two_zeta_r = 2.0 * t.zeta * t.ratio;
  const double one_minus_r2 = 1.0 - t.ratio * t.ratio;
  t.Tp = std::sqrt((1.0 + two_zeta_r * two_zeta_r) /
                   (one_minus_r2 * one_minus_r2 + two_zeta_r * two_zeta_r));  // (40)
  return t;
}

}  // namespace oscidrum
