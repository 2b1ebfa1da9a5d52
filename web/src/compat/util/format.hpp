// web/src/compat/util/format.hpp: stands in for src/util/format.hpp in the WebAssembly build
// only (scripts/build-web.sh puts web/src/compat before src/ on the include path). Emscripten
// 3.1.6's libc++ has no floating-point std::to_chars; this gives the same shortest text that
// reads back exactly (-5e+06, 0.60000001, 1851) with snprintf and strtod. Used for the numbers in
// error messages only.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace oscidrum::detail {

/// The shortest %g text that reads back as exactly v.
inline std::string shortest(double v) {
  char buf[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

}  // namespace oscidrum::detail
