// Appendix A: absolute displacement transmissibility of the frame on the suspension (40).
#include "oscidrum/transmissibility.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

#include "oscidrum/error.hpp"
#include "util/format.hpp"

namespace oscidrum {

Transmissibility transmissibility(double kd, double cd, double m_f, double nu) {
  // The fields the arguments come from (a case's roller), named in the message.
  auto check = [](const char* name, const char* unit, double v, bool allow_zero) {
    if (!std::isfinite(v) || v < 0 || (!allow_zero && v == 0)) {
      throw Error(std::string("transmissibility (Appendix A): ") + name +
                      (allow_zero ? " must be >= 0 " : " must be > 0 ") + unit + "; got " +
                      detail::shortest(v) +
                      (v == 0 && !allow_zero && std::string_view(name) == "roller.kd"
                           ? " (without a suspension spring the frame has no natural frequency)"
                           : ""),
                  name, v);
    }
  };
  check("roller.kd", "[N/m]", kd, false);
  check("roller.cd", "[N s/m]", cd, true);
  check("roller.m_f", "[kg]", m_f, false);
  check("nu = 2 pi roller.f", "[rad/s]", nu, false);
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
