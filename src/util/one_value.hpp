// Internal: whether a channel holds one value in every sample (a dead or disconnected sensor, a
// logger holding its last value): the record reader's note, analyze's gates and the frequency
// search, identify's and calibrate's refusal.
#pragma once

#include <algorithm>
#include <span>

namespace oscidrum::detail {

/// True when y has samples and all of them are the same value (compared exactly).
inline bool one_value(std::span<const double> y) {
  return !y.empty() && std::all_of(y.begin(), y.end(), [&](double v) { return v == y.front(); });
}

}  // namespace oscidrum::detail
