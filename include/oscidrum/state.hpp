// oscidrum/state.hpp: the state vector and the contact phase.
#pragma once

#include <array>

namespace oscidrum {

/// Contact phase. The value of a slip phase is s = sign(v_rel) of (27)-(29).
enum class Phase : int {
  slip_negative = -1,  ///< v_rel < 0, T = +mu N > 0
  stick = 0,           ///< pure rolling, |T| <= mu N
  slip_positive = 1,   ///< v_rel > 0, T = -mu N < 0
  /// No contact: the drum has lifted off the trough (contact.unilateral, docs/model.md
  /// section 13); N = T = 0 and the soil relaxes.
  flight = 2,
  /// The one phase of a smooth (regularised) friction law: T = -m(v_rel) N for every v_rel,
  /// no stick and no switches (oscidrum/friction.hpp). Samples show its apparent phase instead.
  smooth = 3,
};

/// Human-readable name: "stick", "slip+", "slip-", "flight", "smooth".
const char* to_string(Phase phase);

/// The sign s of a slip phase (+1, -1), 0 for stick and the smooth phase.
constexpr int slip_sign(Phase phase) {
  return phase == Phase::slip_positive ? 1 : phase == Phase::slip_negative ? -1 : 0;
}

/// The state q = (delta, x_A, s_A, phi, delta', x_A', s_A', phi') of (51) and (54). The engine
/// carries phi in every phase; in stick phi' = f5 delta' (12).
struct State {
  double delta = 0.0;   ///< position angle of the drum in the trough [rad]
  double x_A = 0.0;     ///< horizontal displacement of the trough (soil point A) [m]
  double s_A = 0.0;     ///< vertical displacement of the trough, down positive [m]
  double phi = 0.0;     ///< total drum rotation [rad]
  double ddelta = 0.0;  ///< delta' [rad/s]
  double dx_A = 0.0;    ///< x_A' [m/s]
  double ds_A = 0.0;    ///< s_A' [m/s]
  double dphi = 0.0;    ///< phi' [rad/s]

  std::array<double, 8> to_array() const {
    return {delta, x_A, s_A, phi, ddelta, dx_A, ds_A, dphi};
  }
  static State from_array(const std::array<double, 8>& q) {
    return {q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7]};
  }
};

/// Second derivatives (delta'', x_A'', s_A'', phi'').
struct Accelerations {
  double delta = 0.0;  ///< [rad/s^2]
  double x_A = 0.0;    ///< [m/s^2]
  double s_A = 0.0;    ///< [m/s^2]
  double phi = 0.0;    ///< [rad/s^2]
};

}  // namespace oscidrum
