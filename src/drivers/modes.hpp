// Internal: the name of the vibratory drum's operating mode (Diagnostics::operating_mode), by the
// literature's names (docs/model.md section 14), from what the run found: its contact_mode, its
// multiplicity and, without a periodic steady state, the motion examined after it.
#pragma once

#include <algorithm>
#include <string>

#include "oscidrum/parameters.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum::detail {

inline std::string operating_mode(RollerType type, const Diagnostics& d) {
  if (type != RollerType::vibratory) return "";
  const std::string& mode = d.contact_mode;
  if (mode.empty()) return "";
  if (mode == "permanent contact") return "continuous contact";
  if (mode == "aperiodic") {
    // A verdict only from the motion's examination (Diagnostics::motion: the largest Lyapunov
    // exponent and the stroboscopic points); a run that merely found no steady state has none.
    if (d.motion == "chaotic") return "chaotic";
    if (d.motion == "quasi_periodic") return "quasi-periodic";
    return "";
  }
  const int p = std::max(1, d.multiplicity);
  if (p == 1) return "partial uplift";
  if (p == 2) return "double jump";
  return "lift-off with period " + std::to_string(p);
}

}  // namespace oscidrum::detail
