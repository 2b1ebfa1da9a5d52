// oscidrum/record.hpp: the metrics of a measured drum acceleration record, for comparing
// simulations with field measurements (paper Fig. 23). A measured record rarely holds a whole
// number of periods at a sampling rate commensurate with f, so the harmonics are fitted by least
// squares rather than read off a DFT.
#pragma once

#include <span>
#include <vector>

#include "oscidrum/metrics.hpp"

namespace oscidrum {

/// One member per entry of OSCIDRUM_RECORD_METRICS (oscidrum/outputs.hpp): the fit's cycles and
/// residuals, then the acceleration metrics shared with Metrics (peaks and area of the fitted
/// periodic signals, harmonics with absolute-time phases, psi_xz and the compaction indicators).
struct RecordMetrics {
#define OSCIDRUM_MEMBER(type, name, unit, label, description) type name{};
  OSCIDRUM_RECORD_METRICS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
};

/// Fit y(t) = sum_{n=0}^{n_max} (a_n cos(n nu t) + b_n sin(n nu t)) to x_M'' and z_M'' by least
/// squares (t [s] strictly increasing, any spacing, at least one excitation period f [Hz]), then
/// evaluate the metrics on the fitted periodic signals (1024 samples per period). The fitted
/// signal is what repeats from period to period: noise and slow drifts go to the residuals.
/// Throws oscidrum::Error on inconsistent sizes, non-finite values, a record shorter than one
/// period or too coarse for n_max (fewer than 2 n_max + 1 samples per period).
RecordMetrics analyze_record(std::span<const double> t, std::span<const double> ddx_M,
                             std::span<const double> ddz_M, double f, int n_max = 10);

}  // namespace oscidrum
