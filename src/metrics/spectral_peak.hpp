// spectral_peak.hpp: the first step of the record's frequency estimate (record.cpp), internal;
// exposed for its tests.
#pragma once

#include <cstddef>
#include <span>

#include "oscidrum/record.hpp"

namespace oscidrum::detail {

/// The peak of the harmonic-sum spectrum and its grid spacing.
struct SpectralPeak {
  double f = 0;   ///< [Hz]
  double df = 0;  ///< grid spacing [Hz]
};

/// The peak of P(f) = sum_{n=1}^{3} (|X(n f)|^2 + |Z(n f)|^2) (n f below the Nyquist frequency
/// fs/2 only: n = 1, 2 above fs/6) over [max(f_min, 1/span), min(f_max, fs/5)] of at most the
/// first 4096 samples (demeaned), frequencies whose own term is
/// below a tenth of P (subharmonics) left out. Uniformly sampled records (and allow_fft): by an
/// FFT zero-padded to fft_size(4 (n - 1)) points, on its bins; otherwise by direct sums on a grid
/// of a quarter of the frequency resolution. Throws oscidrum::Error on too few samples, an empty
/// range or constant accelerations.
SpectralPeak spectral_peak(std::span<const double> t, std::span<const double> ddx,
                           std::span<const double> ddz, const FrequencySearch& search,
                           bool allow_fft = true);

/// Samples in the segment the record's frequency is first estimated on (spectral_peak's).
inline constexpr std::size_t kEstimationSamples = 4096;

/// Where that segment starts: 0 (the record's beginning) unless the beginning is quiet, i.e. a
/// logger started before the exciter. The record is cut into blocks of kEstimationSamples (the
/// last, shorter one left out); a block's loudness is the mean absolute deviation of x_M'' and of
/// z_M'' from their means, added (robust to a spike: one sample moves it by its size over the
/// block's length). When the first block is less than half as loud as the loudest, the segment
/// starts with the first block at least half as loud: the first stretch where the drum
/// oscillates. A stationary record (every block about as loud) keeps 0.
std::size_t estimation_start(std::span<const double> ddx, std::span<const double> ddz);

/// The smallest L >= n whose only prime factors are 2, 3 and 5.
std::size_t fft_size(std::size_t n);

}  // namespace oscidrum::detail
