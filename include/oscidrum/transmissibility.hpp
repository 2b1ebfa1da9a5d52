// oscidrum/transmissibility.hpp: Appendix A, dynamic decoupling of drum and frame.
#pragma once

namespace oscidrum {

struct Transmissibility {
  double omega = 0.0;  ///< natural circular frequency sqrt(kd / m_f) [rad/s]
  double zeta = 0.0;   ///< damping ratio cd / (2 m_f omega) [-]
  double ratio = 0.0;  ///< nu / omega [-]
  double Tp = 0.0;     ///< absolute displacement transmissibility (40) [-]
};

/// Appendix A (40) for a frame of mass m_f [kg] on the suspension kd [N/m], cd [N s/m], base
/// excitation at nu [rad/s]. Throws oscidrum::Error if kd, m_f or nu is not > 0 or cd < 0
/// (cd = 0, an undamped suspension, is allowed).
Transmissibility transmissibility(double kd, double cd, double m_f, double nu);

}  // namespace oscidrum
