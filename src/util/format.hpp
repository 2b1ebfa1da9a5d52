// Internal: numbers in error messages, formatted once for the whole library.
#pragma once

#include <charconv>
#include <string>

namespace oscidrum::detail {

/// The shortest text that reads back as exactly v (std::to_chars): -5e+06, 0.60000001, 1851.
inline std::string shortest(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace oscidrum::detail
