// Internal: the words of oscidrum::analyze_motion's (src/drivers/motion.cpp) undecided verdict
// whose exponent has not settled, apart from any one motion, so that tests can check them for
// halves of either sign (a motion that produces a given pair is chaotic, and which pair it
// produces differs between builds).
#pragma once

#include <cmath>
#include <string>

#include "util/format.hpp"

namespace oscidrum::detail {

/// The evidence of an undecided verdict from the window's two halves a and b [per period] of the
/// exponent's estimate; `numbers` is the estimate as analyze_motion writes it. Halves of one sign
/// whose difference exceeds the whole window's exponent have a sign but not a settled one (read
/// as "no sign" beside two positive halves, the words contradicted the numbers).
inline std::string unsettled_evidence(const std::string& numbers, double a, double b) {
  if ((a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0))
    return "the " + numbers + ": both halves " + (a > 0.0 ? "positive" : "negative") +
           ", but they differ by " + format("%.4g", std::abs(a - b)) +
           " per period, more than the window's exponent: not settled over this window";
  return "the " + numbers + " do not settle on a sign";
}

}  // namespace oscidrum::detail
