// clipping.hpp: whether a run of equal samples at a channel's extreme is clipping (record.cpp's
// plateau gate), internal; exposed for its tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>
#include <vector>

namespace oscidrum::detail {

/// Samples of a window allowed beyond a run's level for the run to count as at the channel's
/// extreme there: a spike or two past the rail (a record with one sample beyond the clip level),
/// not noise peaks.
inline constexpr std::size_t kSpikesAllowed = 2;

/// The channel's resolution in the window y[first..last] (a logger's code): the step of which
/// every step between samples (larger than `tol`) is a whole number (to 0.05 of it, after the
/// code is fitted to them all: a file's decimals round the codes), tried as the smallest step
/// over 1 ... 16 (a steep channel may never step by one code); 0 where none is (the samples are
/// not in codes: the smallest step of a smooth signal is no resolution).
inline double record_code(std::span<const double> y, std::size_t first, std::size_t last,
                          double tol) {
  std::vector<double> steps;
  for (std::size_t i = first + 1; i <= last; ++i)
    if (const double step = std::abs(y[i] - y[i - 1]); step > tol) steps.push_back(step);
  if (steps.empty()) return 0.0;
  const double smallest = *std::min_element(steps.begin(), steps.end());
  for (int k = 1; k <= 16; ++k) {
    double sum = 0.0, codes = 0.0;
    for (const double step : steps) {
      sum += step;
      codes += std::round(step / (smallest / k));
    }
    const double code = sum / codes;
    if (std::all_of(steps.begin(), steps.end(), [&](double step) {
          return std::abs(step / code - std::round(step / code)) <= 0.05;
        }))
      return code;
  }
  return 0.0;
}

/// Whether the run of equal samples y[a..b] of a window is clipping (a rail), where its
/// channel is recorded in codes of `quantum` (record_code; 0: not in codes, a value of any
/// precision). `beyond()`: the window's samples past the run's level, `per_period`: samples per
/// excitation period, `amplitude`: half the channel's range in the window.
///
/// Values of any precision never repeat on a smooth signal: a run is a rail (as before). In
/// codes, a smooth peak holds its top code for a few samples, and noise makes chance runs of
/// equal codes on the way up and down; a logger's record (a 16-bit logger's codes of 0.5 mg, a
/// peak of 1.47 g) failed the gate in half its windows. A run in codes is a rail where it is
/// longer than a peak holds a code (over the fraction sqrt(2 q / A) / pi of a period of a
/// sinusoid of amplitude A, three times that for the flatter peaks of a response with
/// overtones), or where it is at the window's extreme (at most kSpikesAllowed samples beyond:
/// a chance run lies below the noise peaks) and the signal meets or leaves it at its own slope,
/// by more than three codes between samples (over a run of L codes of a smooth peak the
/// curvature is at most 8 q / L^2, so the next sample differs by under 3 q) and three times what
/// the noise makes of a step (`noise`: the deviation of one sample's noise).
template <class Beyond>
bool clipped_run(std::span<const double> y, std::size_t a, std::size_t b, const Beyond& beyond,
                 double per_period, double amplitude, double quantum, double noise) {
  if (!(quantum > 0.0)) return true;
  const double peak_holds =
      3.0 * per_period * std::sqrt(2.0 * quantum / amplitude) / std::numbers::pi + 2.0;
  if (static_cast<double>(b - a + 1) > peak_holds) return true;
  if (beyond() > kSpikesAllowed) return false;  // below the extreme: noise, not a rail
  double step = 0.0;                            // into or out of the run, the larger
  if (a > 0) step = std::max(step, std::abs(y[a - 1] - y[a]));
  if (b + 1 < y.size()) step = std::max(step, std::abs(y[b + 1] - y[b]));
  return step > 3.0 * (quantum + std::sqrt(2.0) * noise);
}

/// The deviation of the noise of samples y[first..last]: the median absolute second difference
/// (robust to the steps at a rail) over its value for white noise, 0.6745 sqrt(6). A smooth
/// signal's own second differences count too, more the fewer samples a period has.
inline double second_difference_noise(std::span<const double> y, std::size_t first,
                                      std::size_t last) {
  if (last < first + 2) return 0.0;
  std::vector<double> d;
  for (std::size_t i = first + 1; i < last; ++i)
    d.push_back(std::abs(y[i + 1] - 2 * y[i] + y[i - 1]));
  const auto mid = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
  std::nth_element(d.begin(), mid, d.end());
  return *mid / (0.6745 * std::sqrt(6.0));
}

}  // namespace oscidrum::detail
