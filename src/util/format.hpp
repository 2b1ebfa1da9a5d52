// Internal: numbers in error and status messages, formatted once for the whole core library.
#pragma once

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace oscidrum::detail {

/// The shortest text that reads back as exactly v (std::to_chars): -5e+06, 0.60000001, 1851.
inline std::string shortest(double v) {
#ifdef __EMSCRIPTEN__
  // Emscripten 3.1.6's libc++ has no floating-point std::to_chars: the shortest %g that reads
  // back exactly gives the same text.
  char buf[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
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
