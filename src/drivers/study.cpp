// The study runner: cases are grouped into chains of continuation (a chain runs in order, each
// case starting from its predecessor's steady state; a case without continuation is a chain of
// its own). A pool of worker threads takes chains from one atomic counter and stores each outcome
// at its case's index, so the outcome vector is the same whatever the number of threads or the
// order in which chains finish (each chain is a deterministic sequence of simulations). The
// callbacks are serialised by one mutex; the first exception a callback throws stops the pool and
// is rethrown to the caller.
#include "oscidrum/study.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#include "drivers/continuation.hpp"
#include "drivers/period_recording.hpp"
#include "metrics/indicators.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Shared by the workers of one run_study call.
struct Pool {
  Pool(std::size_t n, const CaseSource& c, const StudyOptions& o, std::vector<CaseOutcome>& out,
       std::vector<std::vector<std::size_t>> ch)
      : count(n), case_at(c), options(o), outcomes(out), chains(std::move(ch)) {}

  std::size_t count;
  const CaseSource& case_at;
  const StudyOptions& options;
  std::vector<CaseOutcome>& outcomes;            // empty unless options.keep_outcomes
  std::vector<std::vector<std::size_t>> chains;  // case indices, each chain in order
  std::atomic<std::size_t> next{0};              // the next chain to run
  std::atomic<bool> stop{false};                 // cancelled, or a callback threw
  std::mutex mutex;                              // serialises the callbacks and `done`
  std::size_t done = 0;
  std::exception_ptr error;

  bool cancelled() {
    if (stop.load()) return true;
    if (!options.cancelled) return false;
    std::lock_guard lock(mutex);
    if (options.cancelled()) stop.store(true);
    return stop.load();
  }
};

// The outcome of a case that did not run: `status` (invalid, cancelled), no metrics, and no
// diagnostic values (NaN: a final_change of 0 read as converged, a min_N of 0 as contact lost).
CaseOutcome never_run(Status status, const std::string& error, const std::string& message) {
  CaseOutcome o;
  o.valid = false;
  o.error = error;
  o.result.status = status;
  o.result.message = message;
  o.result.diagnostics = detail::all_unavailable<Diagnostics>(diagnostic_outputs());
  o.result.stick_time = o.result.slip_positive_time = o.result.slip_negative_time = kNaN;
  o.result.flight_time = kNaN;
  o.metrics = Metrics::unavailable();
  return o;
}

// One case; `interrupted` is set if the cancellation callback stopped it midway.
// `cancelled` (the caller's callback, serialised) is polled once per period, `stop_now` (cheap)
// at every integration step.
// `warm`: the predecessor's steady state (continuation), or null; `orbit` (may be null) receives
// this case's steady state as a start for its successor. Without keep_samples only the first
// sample is taken (what the metrics and the successor start from), and none is kept.
CaseOutcome run_one(const Case& c, bool keep_samples, int n_harmonics,
                    const std::function<bool()>& cancelled, const std::function<bool()>& stop_now,
                    bool* interrupted, const detail::WarmStart* warm = nullptr,
                    std::optional<detail::WarmStart>* orbit = nullptr,
                    detail::recording::Recording* reused = nullptr) {
  CaseOutcome out;
  try {
    const Model model(c);
    ProgressCallback progress;
    if (cancelled) progress = [&](int, double) { return !cancelled(); };
    // The steady period as the sampling recorded it: the metrics need not integrate it again
    // (`reused`: a thread's recording, whose storage the cases share).
    detail::recording::Recording own;
    detail::recording::Recording& period = reused != nullptr ? *reused : own;
    // A failed warm start leaves the cold start the whole budget: the case's status must not
    // depend on continuation.
    std::optional<detail::WarmStart> start;
    if (warm != nullptr) {
      start = *warm;
      start->cold_start_budget = true;
    }
    out.result = detail::simulate_from(model, progress, stop_now, start ? &*start : nullptr,
                                       keep_samples, &period);
    if (orbit) *orbit = detail::orbit_start(model, out.result, period);
    if (out.result.status == Status::cancelled) {
      *interrupted = true;
      return out;
    }
    out.metrics = ok(out.result.status)
                      ? detail::compute_metrics(model, out.result, n_harmonics, &period)
                      : Metrics::unavailable();
  } catch (const Error& e) {
    out.valid = false;
    out.error = e.what();
  } catch (const std::exception& e) {
    out.valid = false;
    out.error = std::string("internal error: ") + e.what();
  }
  if (!out.valid) {
    // Never run: its result said steady_state and its metrics were 0 (a default Result and
    // Metrics), which a list of o.metrics.area took for numbers.
    out = never_run(Status::invalid, out.error, out.error);
  }
  if (!keep_samples) out.result.samples = Samples{};
  return out;
}

void work(Pool& pool) {
  const StudyOptions& opt = pool.options;
  std::function<bool()> cancelled, stop_now;
  if (opt.cancelled) {
    cancelled = [&pool] { return pool.cancelled(); };
    // Inside a period, poll the caller's callback (which may be slow, e.g. take Python's GIL)
    // at most every 50 ms, so that even a period that takes long stops promptly.
    stop_now = [&pool, last = std::chrono::steady_clock::now()]() mutable {
      if (pool.stop.load(std::memory_order_relaxed)) return true;
      const auto now = std::chrono::steady_clock::now();
      if (now - last < std::chrono::milliseconds(50)) return false;
      last = now;
      return pool.cancelled();
    };
  }
  detail::recording::Recording period;  // every case of this thread records into its storage
  while (!pool.stop.load()) {
    const std::size_t k = pool.next.fetch_add(1);
    if (k >= pool.chains.size()) break;
    // The predecessor's steady state and the two before it, with their cases: the start of the
    // next case extrapolated along the chain (secant_start), or the predecessor's state.
    std::optional<detail::WarmStart> warm, before, earlier;
    std::optional<Case> warm_case, before_case, earlier_case;
    for (const std::size_t i : pool.chains[k]) {
      if (pool.cancelled()) return;
      bool interrupted = false;
      std::optional<detail::WarmStart> orbit, predicted;
      const Case now = pool.case_at(i);
      if (warm && before && warm_case && before_case)
        predicted = detail::secant_start(*before, *warm, *before_case, *warm_case, now,
                                         earlier ? &*earlier : nullptr,
                                         earlier_case ? &*earlier_case : nullptr);
      const detail::WarmStart* start = predicted ? &*predicted : (warm ? &*warm : nullptr);
      const bool samples =
          opt.keep_samples || (static_cast<bool>(opt.on_case_done) && opt.samples_in_callback);
      CaseOutcome outcome = run_one(now, samples, opt.n_harmonics, cancelled, stop_now,
                                    &interrupted, start, &orbit, &period);
      if (interrupted) return;  // stays "cancelled"; never reported as done
      earlier = std::move(before);
      earlier_case = std::move(before_case);
      before = std::move(warm);
      before_case = std::move(warm_case);
      warm = std::move(orbit);
      warm_case = now;
      std::exception_ptr failed;
      if (opt.on_case_done && opt.concurrent_on_case_done) {
        try {
          opt.on_case_done(i, outcome);
        } catch (...) {
          failed = std::current_exception();
        }
      }
      std::lock_guard lock(pool.mutex);
      try {
        if (failed) std::rethrow_exception(failed);
        ++pool.done;
        if (opt.on_case_done && !opt.concurrent_on_case_done) opt.on_case_done(i, outcome);
        if (opt.progress) opt.progress(pool.done, pool.count);
      } catch (...) {
        if (!pool.error) pool.error = std::current_exception();
        pool.stop.store(true);
      }
      if (!opt.keep_samples) outcome.result.samples = Samples{};
      if (opt.keep_outcomes) pool.outcomes[i] = std::move(outcome);
      if (pool.stop.load()) return;
    }
  }
}

}  // namespace

CaseOutcome not_run_outcome() {
  return never_run(Status::cancelled, "cancelled", "cancelled before the case ran");
}

namespace {

bool continues(const Case& c) {
  return c.numerics.method == SteadyMethod::shooting && c.numerics.continuation;
}

// Planning builds every case (seconds for the largest studies): the caller's cancellation callback
// is polled every kPlanningPoll cases.
constexpr std::size_t kPlanningPoll = 4096;
bool planning_cancelled(std::size_t k, const std::function<bool()>& cancelled) {
  return cancelled && k % kPlanningPoll == 0 && cancelled();
}

// The chains of `previous` (validated), cut into pieces of at most max_continuation_piece(n),
// ordered by their first case.
std::vector<std::vector<std::size_t>> make_chains(std::size_t n, const CaseSource& case_at,
                                                  const std::vector<std::ptrdiff_t>& previous,
                                                  const std::function<bool()>& cancelled) {
  if (previous.size() != n)
    throw Error("StudyOptions::previous must have one entry per case (" + std::to_string(n) +
                "); got " + std::to_string(previous.size()));
  std::vector<std::ptrdiff_t> next(n, -1);
  std::vector<bool> linked(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    if (planning_cancelled(k, cancelled)) return {};  // no chains: every case cancelled
    const std::ptrdiff_t p = previous[k];
    if (p == -1) continue;
    if (p < 0 || static_cast<std::size_t>(p) >= k)
      throw Error("StudyOptions::previous[" + std::to_string(k) +
                  "] must be -1 or the index of an earlier case (0 ... " + std::to_string(k) +
                  " - 1); got " + std::to_string(p));
    if (next[p] != -1)
      throw Error("StudyOptions::previous: case " + std::to_string(p) +
                  " is the predecessor of two cases (" + std::to_string(next[p]) + " and " +
                  std::to_string(k) + "); a case continues at most one chain");
    if (!continues(case_at(k))) continue;
    next[p] = static_cast<std::ptrdiff_t>(k);
    linked[k] = true;
  }
  std::vector<std::vector<std::size_t>> chains;
  const std::size_t piece = max_continuation_piece(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (linked[k]) continue;  // inside a chain
    chains.emplace_back();
    for (std::ptrdiff_t i = static_cast<std::ptrdiff_t>(k); i != -1; i = next[i]) {
      if (chains.back().size() == piece) chains.emplace_back();
      chains.back().push_back(static_cast<std::size_t>(i));
    }
  }
  std::sort(chains.begin(), chains.end(),
            [](const auto& a, const auto& b) { return a.front() < b.front(); });
  return chains;
}

}  // namespace

namespace detail {

std::optional<WarmStart> secant_start(const WarmStart& w2, const WarmStart& w1, const Case& c2,
                                      const Case& c1, const Case& c0, const WarmStart* w3,
                                      const Case* c3) {
  if (w1.phase != w2.phase || w1.state.size() != w2.state.size()) return {};
  for (const Field& f : fields()) {
    const double u0 = f.get(c0), u1 = f.get(c1), u2 = f.get(c2);
    if (u0 == u1 || (std::isnan(u0) && std::isnan(u1))) continue;
    const double s = (u0 - u1) / (u1 - u2);
    if (!(s > 0.0 && s <= kMaxSecantRatio)) return {};
    WarmStart out = w1;
    out.then = w1.state;
    // Through three states when the step before continues this one too (same phase, a ratio of
    // steps in (0, kMaxSecantRatio]): the Lagrange polynomial of degree 2 in the parameter.
    bool quadratic = w3 != nullptr && c3 != nullptr && w3->phase == w1.phase &&
                     w3->state.size() == w1.state.size();
    double l1 = 1.0 + s, l2 = -s, l3 = 0.0;  // the secant: w1 + s (w1 - w2)
    if (quadratic) {
      const double u3 = f.get(*c3);
      const double s3 = (u1 - u2) / (u2 - u3);
      quadratic = s3 > 0.0 && s3 <= kMaxSecantRatio;
      if (quadratic) {
        l1 = (u0 - u2) * (u0 - u3) / ((u1 - u2) * (u1 - u3));
        l2 = (u0 - u1) * (u0 - u3) / ((u2 - u1) * (u2 - u3));
        l3 = (u0 - u1) * (u0 - u2) / ((u3 - u1) * (u3 - u2));
      }
    }
    for (std::size_t j = 0; j < out.state.size(); ++j) {
      out.state[j] = l1 * w1.state[j] + l2 * w2.state[j];
      if (quadratic) out.state[j] += l3 * w3->state[j];
      if (!std::isfinite(out.state[j])) return {};
    }
    return out;
  }
  return {};
}

}  // namespace detail

CaseOutcome run_case(const Case& c, bool keep_samples, int n_harmonics) {
  bool interrupted = false;
  return run_one(c, keep_samples, n_harmonics, {}, {}, &interrupted);
}

namespace {

// continuation_chains over cases built on demand (each built once, kept while it is the newest).
std::vector<std::ptrdiff_t> chains_of(std::size_t n, const CaseSource& case_at,
                                      const std::function<bool()>& cancelled = {}) {
  std::vector<std::ptrdiff_t> previous(n, -1);
  const std::span<const Field> all = fields();
  std::vector<bool> along;  // the fields in which the chain's first two cases differ
  std::size_t length = 0;   // of the current chain
  if (n == 0) return previous;
  Case before = case_at(0);
  for (std::size_t k = 1; k < n; ++k) {
    if (planning_cancelled(k, cancelled)) break;  // make_chains stops too
    Case now = case_at(k);
    auto differs = [&](std::size_t f) {
      const double a = all[f].get(before), b = all[f].get(now);
      return !(a == b || (std::isnan(a) && std::isnan(b)));
    };
    bool link = continues(before) && continues(now);
    if (link && length <= 1) {  // the chain's second case: its step sets the direction
      along.assign(all.size(), false);
      for (std::size_t f = 0; f < all.size(); ++f) along[f] = differs(f);
    } else if (link) {
      for (std::size_t f = 0; f < all.size() && link; ++f) link = along[f] || !differs(f);
    }
    if (link) {
      previous[k] = static_cast<std::ptrdiff_t>(k - 1);
      length = std::max<std::size_t>(length, 1) + 1;
    } else {
      length = 1;
    }
    before = std::move(now);
  }
  return previous;
}

}  // namespace

std::vector<std::ptrdiff_t> continuation_chains(std::span<const Case> cases) {
  return chains_of(cases.size(), [cases](std::size_t i) { return cases[i]; });
}

std::vector<CaseOutcome> run_study(std::span<const Case> cases, const StudyOptions& options) {
  return run_study(
      cases.size(), [cases](std::size_t i) { return cases[i]; }, options);
}

std::vector<CaseOutcome> run_study(std::size_t count, const CaseSource& case_at,
                                   const StudyOptions& options) {
  if (options.threads < 0)
    throw Error("StudyOptions::threads must be >= 0 (0: all cores); got " +
                std::to_string(options.threads));
  if (options.n_harmonics < 0)
    throw Error("StudyOptions::n_harmonics must be >= 0; got " +
                std::to_string(options.n_harmonics));
  std::vector<CaseOutcome> outcomes(options.keep_outcomes ? count : 0);
  // A case never run (the study cancelled before it) is no steady state: status cancelled, no
  // metrics (a default Result said steady_state, and the metrics were 0).
  for (CaseOutcome& o : outcomes) o = not_run_outcome();
  // Checked before the first case (compute_metrics would refuse each case alike).
  for (std::size_t i = 0; i < count; ++i) {
    if (planning_cancelled(i, options.cancelled)) return outcomes;
    const int spp = case_at(i).numerics.samples_per_period;
    if (options.n_harmonics >= spp / 2)
      throw Error("StudyOptions::n_harmonics must be < numerics.samples_per_period / 2 = " +
                  std::to_string(spp / 2) + " (the samples' Nyquist limit); got " +
                  std::to_string(options.n_harmonics));
  }
  Pool pool(count, case_at, options, outcomes,
            make_chains(count, case_at,
                        options.previous.empty() ? chains_of(count, case_at, options.cancelled)
                                                 : options.previous,
                        options.cancelled));
  std::size_t threads = options.threads > 0 ? static_cast<std::size_t>(options.threads)
                                            : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min(threads, pool.chains.size());
  if (threads <= 1) {
    work(pool);
  } else {
    std::vector<std::jthread> workers;
    workers.reserve(threads);
    for (std::size_t t = 0; t < threads; ++t) workers.emplace_back([&pool] { work(pool); });
  }  // the jthreads join here
  if (pool.error) std::rethrow_exception(pool.error);
  return outcomes;
}

}  // namespace oscidrum
