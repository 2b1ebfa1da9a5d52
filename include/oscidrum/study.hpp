// oscidrum/study.hpp: many cases on all cores, results in input order.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "oscidrum/metrics.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

/// What one case of a study produced.
struct CaseOutcome {
  bool valid = true;  ///< false: the case was rejected (invalid parameters); see `error`
  std::string error;  ///< the oscidrum::Error message when !valid
  Result result;      ///< samples dropped unless StudyOptions::keep_samples
  Metrics metrics;    ///< computed whenever the result has samples
};

struct StudyOptions {
  int threads = 0;            ///< worker threads; 0: std::thread::hardware_concurrency()
  bool keep_samples = false;  ///< keep each case's steady-state samples in the outcome
  int n_harmonics = 10;       ///< harmonics in the metrics
  /// Called from worker threads, serialised by the runner, after each case (index into the
  /// input, outcome). Use it to stream results to disk.
  std::function<void(std::size_t index, const CaseOutcome& outcome)> on_case_done;
  /// Called (serialised) after each case with (done, total).
  std::function<void(std::size_t done, std::size_t total)> progress;
  /// Polled (serialised with the other callbacks) before each case and once per excitation
  /// period inside a running case; return true to stop (interrupt): running cases end as
  /// "cancelled" and are not passed to on_case_done.
  std::function<bool()> cancelled;
};

/// Run every case (each is independent: identical results to a serial run). The outcome vector
/// has one entry per input case, in input order; cases not started because of cancellation have
/// valid = false and error = "cancelled".
std::vector<CaseOutcome> run_study(std::span<const Case> cases, const StudyOptions& options = {});

/// One case, as run_study runs it (never throws for invalid parameters: see CaseOutcome::valid).
CaseOutcome run_case(const Case& c, bool keep_samples = true, int n_harmonics = 10);

}  // namespace oscidrum
