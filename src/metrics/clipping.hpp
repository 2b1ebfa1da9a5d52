// clipping.hpp: whether a run of equal samples at a channel's extreme is clipping (record.cpp's
// plateau gate), internal; exposed for its tests.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

namespace oscidrum::detail {

/// Samples on each side of a run that judge it (clipped_run).
inline constexpr std::size_t kClipNeighbours = 3;

/// Whether the run y[a..b] of equal samples (of a window of the record t, y: at the top of the
/// window's range of the channel when `upper`, else at its bottom) is clipping: the signal
/// around it would pass its level. The run is taken as far as it goes in the record, and its
/// neighbours from the record (a run at a window's edge has them outside the window). A quadratic
/// in t through kClipNeighbours samples on each side of the run (least squares) is evaluated at the
/// run's middle; the run is clipping where that lies beyond the run's level by more than the
/// channel's resolution `quantum` plus three standard errors of the value there (each sample's
/// error: the code's rounding, q / sqrt(12), and the noise, the residual of a straight line through
/// each side's samples). A clipped signal meets its rail rising and leaves it falling: the
/// quadratic runs far beyond the rail. A smooth peak recorded with a finite resolution (a 16-bit
/// logger) holds its top code for a few samples and its neighbours lie within a code or two of it;
/// noise makes chance runs of equal codes on the way, which the quadratic follows. Before, every
/// run of three equal samples in the outer quarter of the range counted, and a logger's record of a
/// peak of 1.47 g with codes of 0.5 mg failed the gate in half its windows. A run with fewer than
/// kClipNeighbours samples on a side (at the record's ends) is not judged (not counted): a clipped
/// channel is clipped at every extreme of a window, at least one per period, and the others say so.
inline bool clipped_run(std::span<const double> t, std::span<const double> y, std::size_t a,
                        std::size_t b, bool upper, double quantum) {
  constexpr std::size_t m = kClipNeighbours;
  while (a > 0 && y[a - 1] == y[a]) --a;
  while (b + 1 < y.size() && y[b + 1] == y[b]) ++b;
  if (a < m || y.size() - 1 - b < m) return false;
  const double t_mid = 0.5 * (t[a] + t[b]);
  // The time unit: the sampling step around the run (the normal equations stay well scaled).
  const double unit = (t[b + m] - t[a - m]) / static_cast<double>(b - a + 2 * m);
  if (!(unit > 0.0)) return true;
  Eigen::Matrix<double, 2 * m, 3> A;
  Eigen::Matrix<double, 2 * m, 1> v;
  for (std::size_t k = 0; k < 2 * m; ++k) {
    const std::size_t i = k < m ? a - m + k : b + 1 + (k - m);
    const double tau = (t[i] - t_mid) / unit;
    const auto row = static_cast<Eigen::Index>(k);
    A(row, 0) = 1.0, A(row, 1) = tau, A(row, 2) = tau * tau;
    v[row] = y[i] - y[a];  // relative to the run's level
  }
  const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 2 * m, 3>> qr(A);
  if (qr.rank() < 3) return true;
  const double middle = (qr.solve(v))[0];  // the quadratic at the run's middle
  // The noise: each side's samples about their straight line (m - 2 degrees of freedom each).
  double squares = 0.0;
  for (std::size_t side = 0; side < 2; ++side) {
    const auto lines = A.template block<m, 2>(static_cast<Eigen::Index>(side * m), 0);
    const auto values = v.template segment<m>(static_cast<Eigen::Index>(side * m));
    const Eigen::Vector2d c = lines.colPivHouseholderQr().solve(values);
    squares += (lines * c - values).squaredNorm();
  }
  const double noise = std::sqrt(squares / static_cast<double>(2 * (m - 2)));
  const double error = std::sqrt(quantum * quantum / 12.0 + noise * noise);  // of one sample
  // The standard error of the quadratic's value at the middle: (A^T A)^-1's first entry.
  const Eigen::Matrix3d normal = A.transpose() * A;
  const double spread = std::sqrt(std::max(0.0, normal.inverse()(0, 0)));
  const double beyond = upper ? middle : -middle;
  return beyond > quantum + 3.0 * error * spread;
}

}  // namespace oscidrum::detail
