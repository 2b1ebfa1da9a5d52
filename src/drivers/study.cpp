// The study runner: a pool of worker threads takes case indices from one atomic counter and
// stores each outcome at its index, so the outcome vector is the same whatever the number of
// threads or the order in which cases finish (each case is an independent, deterministic
// simulation). The callbacks are serialised by one mutex; the first exception a callback throws
// stops the pool and is rethrown to the caller.
#include "oscidrum/study.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "oscidrum/error.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum {
namespace {

// Shared by the workers of one run_study call.
struct Pool {
  Pool(std::span<const Case> c, const StudyOptions& o, std::vector<CaseOutcome>& out)
      : cases(c), options(o), outcomes(out) {}

  std::span<const Case> cases;
  const StudyOptions& options;
  std::vector<CaseOutcome>& outcomes;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};  // cancelled, or a callback threw
  std::mutex mutex;               // serialises the callbacks and `done`
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

// One case; `interrupted` is set if the cancellation callback stopped it midway.
// `cancelled` (the caller's callback, serialised) is polled once per period, `stop_now` (cheap)
// at every integration step.
CaseOutcome run_one(const Case& c, bool keep_samples, int n_harmonics,
                    const std::function<bool()>& cancelled, const std::function<bool()>& stop_now,
                    bool* interrupted) {
  CaseOutcome out;
  try {
    const Model model(c);
    ProgressCallback progress;
    if (cancelled) progress = [&](int, double) { return !cancelled(); };
    out.result = simulate(model, progress, stop_now);
    if (out.result.status == Status::cancelled) {
      *interrupted = true;
      return out;
    }
    out.metrics = ok(out.result.status) ? compute_metrics(model, out.result, n_harmonics)
                                        : Metrics::unavailable();
  } catch (const Error& e) {
    out.valid = false;
    out.error = e.what();
  } catch (const std::exception& e) {
    out.valid = false;
    out.error = std::string("internal error: ") + e.what();
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
  while (!pool.stop.load()) {
    const std::size_t i = pool.next.fetch_add(1);
    if (i >= pool.cases.size()) break;
    if (pool.cancelled()) break;
    bool interrupted = false;
    CaseOutcome outcome =
        run_one(pool.cases[i], opt.keep_samples || static_cast<bool>(opt.on_case_done),
                opt.n_harmonics, cancelled, stop_now, &interrupted);
    if (interrupted) break;  // stays "cancelled"; never reported as done
    std::lock_guard lock(pool.mutex);
    try {
      ++pool.done;
      if (opt.on_case_done) opt.on_case_done(i, outcome);
      if (opt.progress) opt.progress(pool.done, pool.cases.size());
    } catch (...) {
      if (!pool.error) pool.error = std::current_exception();
      pool.stop.store(true);
    }
    if (!opt.keep_samples) outcome.result.samples = Samples{};
    pool.outcomes[i] = std::move(outcome);
  }
}

}  // namespace

CaseOutcome run_case(const Case& c, bool keep_samples, int n_harmonics) {
  bool interrupted = false;
  return run_one(c, keep_samples, n_harmonics, {}, {}, &interrupted);
}

std::vector<CaseOutcome> run_study(std::span<const Case> cases, const StudyOptions& options) {
  if (options.threads < 0)
    throw Error("StudyOptions::threads must be >= 0 (0: all cores); got " +
                std::to_string(options.threads));
  if (options.n_harmonics < 0)
    throw Error("StudyOptions::n_harmonics must be >= 0; got " +
                std::to_string(options.n_harmonics));
  std::vector<CaseOutcome> outcomes(cases.size());
  for (CaseOutcome& o : outcomes) o.valid = false, o.error = "cancelled";
  Pool pool(cases, options, outcomes);
  std::size_t threads = options.threads > 0 ? static_cast<std::size_t>(options.threads)
                                            : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min(threads, cases.size());
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
