// Internal: numbers in error and status messages, formatted once for the whole core library.
#pragma once

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace oscidrum::detail {

/// std::to_chars(v)'s text by printf: the fewest significant digits that read back as exactly v,
/// written in fixed notation (%f) or scientific (%e), whichever is shorter, fixed on a tie (the
/// rule of std::to_chars). For a libc++ without floating-point std::to_chars (Emscripten 3.1.6):
/// the shortest %g printed 40 as "4e+01" there, and the explorer's messages read
/// "G = 4e+01 MN/m^2" where the command line said 40.
inline std::string shortest_by_printf(double v) {
  char buf[40];
  int digits = 1;
  for (; digits < 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*e", digits - 1, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::snprintf(buf, sizeof buf, "%.*e", digits - 1, v);
  const std::string sci = buf;
  if (!(v == v) || v - v != 0.0) return sci;  // nan, inf: as %e writes them
  // Fixed: the fewest decimals that read back exactly (%f prints an integer's exact value).
  char fixed[400];
  for (int decimals = 0; decimals < 330; ++decimals) {
    const int n = std::snprintf(fixed, sizeof fixed, "%.*f", decimals, v);
    if (n < 0 || n > static_cast<int>(sci.size())) break;  // longer than sci, and growing
    if (std::strtod(fixed, nullptr) == v) return fixed;
  }
  return sci;
}

/// The shortest text that reads back as exactly v (std::to_chars): -5e+06, 0.60000001, 1851.
inline std::string shortest(double v) {
#ifdef __EMSCRIPTEN__
  return shortest_by_printf(v);
#else
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
#endif
}

/// printf-style formatting of numbers into a std::string, for status messages (at most 1023
/// characters). Every argument is passed as a double, so the pattern uses %g, %f, %.0f ... only.
template <class... Numbers>
std::string format(const char* pattern, Numbers... numbers) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, pattern, static_cast<double>(numbers)...);
  return buf;
}

}  // namespace oscidrum::detail
