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

/// The outcome of a case a study did not run (cancelled before it): valid false, error
/// "cancelled", status cancelled, metrics and diagnostic values NaN.
CaseOutcome not_run_outcome();

struct StudyOptions {
  int threads = 0;            ///< worker threads; 0: std::thread::hardware_concurrency()
  bool keep_samples = false;  ///< keep each case's steady-state samples in the outcome
  int n_harmonics = 10;       ///< harmonics in the metrics
  /// Called from worker threads, serialised by the runner, after each case (index into the
  /// input, outcome). Use it to stream results to disk.
  std::function<void(std::size_t index, const CaseOutcome& outcome)> on_case_done;
  /// True: on_case_done is called from the worker threads concurrently, not serialised (it
  /// must be thread-safe and serialise what needs it itself), so that expensive work in it
  /// (formatting, compressing a steady state) runs in parallel. progress stays serialised.
  bool concurrent_on_case_done = false;
  /// Whether on_case_done receives each case's samples. False: a case's samples are not taken
  /// unless keep_samples (the periods are integrated all the same, so every number of the
  /// outcome is the same); a study that keeps only the metrics then runs faster.
  bool samples_in_callback = true;
  /// Called (serialised) after each case with (done, total).
  std::function<void(std::size_t done, std::size_t total)> progress;
  /// Polled (serialised with the other callbacks) before each case and once per excitation
  /// period inside a running case; return true to stop (interrupt): running cases end as
  /// "cancelled" and are not passed to on_case_done.
  std::function<bool()> cancelled;
  /// Continuation (numerics.continuation, docs/periodic.md): for each case, the index of the
  /// case whose steady state it starts from (an earlier case: its predecessor in a chain), or -1
  /// for a start from rest. A case is the predecessor of at most one case. Empty: the chains of
  /// continuation_chains(cases). Links to a case that does not use continuation are ignored.
  std::vector<std::ptrdiff_t> previous;
  /// False: run_study keeps no outcome (it returns an empty vector); each goes only to
  /// on_case_done. A study's memory then does not grow with its number of cases.
  bool keep_outcomes = true;
};

/// Chains of continuation are cut into pieces (each piece starts from rest), so that a long
/// one-parameter study still spreads over the threads: pieces of at most
/// max_continuation_piece(n) cases in a study of n cases, at least kMinContinuationPiece, and long
/// enough that the study has about kContinuationPieces of them when its chains are long. The cut
/// depends only on the study, never on the threads (the outcomes do not either).
inline constexpr std::size_t kMinContinuationPiece = 16;
inline constexpr std::size_t kContinuationPieces = 64;
inline constexpr std::size_t max_continuation_piece(std::size_t n) {
  const std::size_t even = (n + kContinuationPieces - 1) / kContinuationPieces;
  return even > kMinContinuationPiece ? even : kMinContinuationPiece;
}

/// Chains of continuation inferred from the input order, as StudyOptions::previous: case k
/// continues case k - 1 when the parameters in which they differ are among those in which the
/// chain's first two cases differ (a nested-loop product, innermost loop last, gives one chain
/// per line of the innermost loop; zipped values give one chain). Only cases with
/// numerics.method = shooting and numerics.continuation are linked.
std::vector<std::ptrdiff_t> continuation_chains(std::span<const Case> cases);

/// Run every case on `threads` threads. Cases are independent, except that with continuation
/// (numerics.method = shooting and numerics.continuation) a case starts from the steady state of
/// its predecessor in its chain (StudyOptions::previous), falling back to the start from rest
/// when that fails. Each chain runs in order on one thread, so the outcomes are identical whatever
/// the number of threads; they agree with run_case to the steady-state tolerance
/// (Diagnostics::warm_start says how each case started). The outcome vector has one entry per
/// input case, in input order; cases not started because of cancellation have valid = false and
/// error = "cancelled".
std::vector<CaseOutcome> run_study(std::span<const Case> cases, const StudyOptions& options = {});

/// Case i of a study of `count` cases, built when it runs (a study need not hold its cases).
using CaseSource = std::function<Case(std::size_t index)>;

/// run_study over cases built on demand by `case_at` (called once per case from the worker
/// threads, concurrently: it must be thread-safe, e.g. a pure function of the index), for
/// studies too large to hold as a vector. StudyOptions::previous may be empty only when no case
/// continues another (every case then starts from rest).
std::vector<CaseOutcome> run_study(std::size_t count, const CaseSource& case_at,
                                   const StudyOptions& options = {});

/// One case, as run_study runs it (never throws for invalid parameters: see CaseOutcome::valid).
CaseOutcome run_case(const Case& c, bool keep_samples = true, int n_harmonics = 10);

}  // namespace oscidrum
