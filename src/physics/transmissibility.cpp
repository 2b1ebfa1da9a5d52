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
  // Inputs each valid but at the ends of the doubles (kd 1e308 on m_f 1e-300) overflow or
  // underflow omega, zeta or nu/omega: a number printed from them would be meaningless (omega
  // inf, Tp 1), so say so. Tp alone may be inf: the undamped suspension at resonance.
  if (!std::isfinite(t.omega) || !(t.omega > 0) || !std::isfinite(t.zeta) ||
      !std::isfinite(t.ratio) || !(t.ratio > 0) || std::isnan(t.Tp)) {
    throw Error("transmissibility (Appendix A): roller.kd = " + detail::shortest(kd) +
                    " N/m, roller.cd = " + detail::shortest(cd) +
                    " N s/m and roller.m_f = " + detail::shortest(m_f) +
                    " kg give no finite natural frequency, damping ratio or frequency ratio in "
                    "double precision (omega = sqrt(kd / m_f) = " +
                    detail::shortest(t.omega) + " rad/s); use values nearer a real suspension",
                "roller.kd", kd);
  }
  return t;
}

}  // namespace oscidrum
