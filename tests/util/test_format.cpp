// test_format.cpp: the explorer's (WebAssembly) shortest number text, written with printf
// (src/util/format.hpp: Emscripten 3.1.6's libc++ has no floating-point std::to_chars), is the
// native std::to_chars text: the same messages on the command line and in the browser.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "util/format.hpp"

namespace oscidrum {
namespace {

std::string to_chars_text(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

TEST(Format, ShortestByPrintfIsToCharsText) {
  // The explorer printed "4e+01" for 40 and "1.9e+03" for 1900 (the shortest %g).
  EXPECT_EQ(detail::shortest_by_printf(40.0), "40");
  EXPECT_EQ(detail::shortest_by_printf(1900.0), "1900");
  EXPECT_EQ(detail::shortest_by_printf(5e6), "5e+06");
  EXPECT_EQ(detail::shortest_by_printf(0.60000001), "0.60000001");
  const double inf = std::numeric_limits<double>::infinity();
  for (double v : {0.0, -0.0, 1e-4, 1e4, 0.1, 1e15, 1e16, 1e22, 1e300, 1e-300,
                   1.2345678901234568e20, 125001552.0, inf, -inf})
    EXPECT_EQ(detail::shortest_by_printf(v), to_chars_text(v)) << to_chars_text(v);
  std::mt19937_64 g(20261205);
  std::uniform_real_distribution<double> decade(-30.0, 30.0);
  std::uniform_int_distribution<int> decimals(0, 6);
  std::uniform_int_distribution<std::uint64_t> bits;
  int differ = 0;
  for (int i = 0; i < 100000; ++i) {
    const double x = std::pow(10.0, decade(g)), scale = std::pow(10.0, decimals(g));
    std::uint64_t b = bits(g);
    double random_bits;
    std::memcpy(&random_bits, &b, sizeof random_bits);
    for (double v : {x, -std::round(x * scale) / scale, random_bits})
      if (std::isfinite(v) && detail::shortest_by_printf(v) != to_chars_text(v) && ++differ < 5)
        ADD_FAILURE() << to_chars_text(v) << " printed " << detail::shortest_by_printf(v);
  }
  EXPECT_EQ(differ, 0);
}

}  // namespace
}  // namespace oscidrum
