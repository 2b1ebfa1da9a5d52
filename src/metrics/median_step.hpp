// median_step.hpp: a record's typical sampling interval, internal (record.cpp's harmonics and
// in-step test, measured.cpp's window).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace oscidrum::detail {

/// The median of the time steps t[i] - t[i-1] [s]; t has at least two samples. Robust to a
/// logger's dropouts (a few long steps) and to jitter.
inline double median_step(std::span<const double> t) {
  std::vector<double> dt(t.size() - 1);
  for (std::size_t i = 1; i < t.size(); ++i) dt[i - 1] = t[i] - t[i - 1];
  const auto mid = dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2);
  std::nth_element(dt.begin(), mid, dt.end());
  return *mid;
}

}  // namespace oscidrum::detail
