// Tests of the study runner: any number of threads gives the serial result bit for bit, in input
// order; cancellation stops cleanly; invalid cases and throwing callbacks are handled.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "oscidrum/error.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/study.hpp"

namespace oscidrum {
namespace {

// A few quick cases: stick-slip and pure rolling on Table 2 soils, with a driving torque. The
// cases are independent (no continuation, whatever the method), so that each equals the case run
// on its own bit for bit; continuation is tested in test_continuation.cpp.
std::vector<Case> some_cases() {
  std::vector<Case> cases;
  for (double G : {5e6, 25e6, 70e6})
    for (bool pure : {false, true}) {
      Case c;
      c.soil = table2_soil(G);
      c.contact.pure_rolling = pure;
      c.MMd = 0.05 * c.roller.M0;
      c.numerics.samples_per_period = 256;
      c.numerics.continuation = false;
      cases.push_back(c);
    }
  return cases;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_identical(const CaseOutcome& a, const CaseOutcome& b) {
  ASSERT_EQ(a.valid, b.valid);
  EXPECT_EQ(a.error, b.error);
  EXPECT_EQ(a.result.status, b.result.status);
  EXPECT_EQ(a.result.diagnostics.steps, b.result.diagnostics.steps);
  EXPECT_EQ(a.result.diagnostics.rhs_evaluations, b.result.diagnostics.rhs_evaluations);
  EXPECT_EQ(a.result.events.size(), b.result.events.size());
  const Samples &x = a.result.samples, &y = b.result.samples;
  for (auto member : {&Samples::t, &Samples::delta, &Samples::phi, &Samples::x_A, &Samples::s_A,
                      &Samples::ddx_M, &Samples::ddz_M, &Samples::N, &Samples::T})
    EXPECT_TRUE(same_bits(x.*member, y.*member));
  EXPECT_TRUE(same_bits(a.metrics.ddx_max, b.metrics.ddx_max));
  EXPECT_TRUE(same_bits(a.metrics.area, b.metrics.area));
  EXPECT_TRUE(same_bits(a.metrics.psi_xz, b.metrics.psi_xz));
  ASSERT_EQ(a.metrics.ddz_harmonics.size(), b.metrics.ddz_harmonics.size());
  for (std::size_t n = 0; n < a.metrics.ddz_harmonics.size(); ++n)
    EXPECT_TRUE(
        same_bits(a.metrics.ddz_harmonics[n].amplitude, b.metrics.ddz_harmonics[n].amplitude));
}

TEST(Study, ParallelEqualsSerialBitForBitInInputOrder) {
  const std::vector<Case> cases = some_cases();
  StudyOptions serial;
  serial.threads = 1;
  serial.keep_samples = true;
  StudyOptions parallel = serial;
  parallel.threads = 4;  // more threads than cores and than cases: still the same
  const std::vector<CaseOutcome> a = run_study(cases, serial);
  const std::vector<CaseOutcome> b = run_study(cases, parallel);
  ASSERT_EQ(a.size(), cases.size());
  ASSERT_EQ(b.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_TRUE(a[i].valid) << a[i].error;
    EXPECT_EQ(a[i].result.status, Status::steady_state);
    expect_identical(a[i], b[i]);
    // ... and equal to the case run on its own.
    expect_identical(a[i], run_case(cases[i], true, serial.n_harmonics));
  }
  // Input order: the pure-rolling cases (odd indices) never slip.
  EXPECT_EQ(a[1].metrics.stick_fraction, 1.0);
  EXPECT_LT(a[0].metrics.stick_fraction, 1.0);
}

// Without keep_samples (and without samples for the callback) a case takes only its first sample
// and records only its steady period (the periods beyond it are for the samples, and repeat it):
// the same orbit, confirmed on the same period, so every metric and the orbit's counters are the
// same bit for bit, and both integrate the same periods.
TEST(Study, MetricsWithoutSamplesEqualThoseWithSamples) {
  std::vector<Case> cases = some_cases();
  for (Case& c : cases) c.numerics.continuation = true;  // and the chains start the same
  StudyOptions with;
  with.threads = 1;
  with.keep_samples = true;
  StudyOptions without = with;
  without.keep_samples = false;
  std::size_t callbacks = 0;
  without.samples_in_callback = false;
  without.on_case_done = [&](std::size_t, const CaseOutcome& outcome) {
    ++callbacks;
    EXPECT_EQ(outcome.result.samples.size(), 0u);
  };
  const std::vector<CaseOutcome> a = run_study(cases, with);
  const std::vector<CaseOutcome> b = run_study(cases, without);
  EXPECT_EQ(callbacks, cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(i);
    ASSERT_TRUE(a[i].valid) << a[i].error;
    ASSERT_EQ(a[i].result.status, Status::steady_state);
    EXPECT_GT(a[i].result.samples.size(), 0u);
    EXPECT_EQ(b[i].result.samples.size(), 0u);
    const Diagnostics &x = a[i].result.diagnostics, &y = b[i].result.diagnostics;
    EXPECT_EQ(x.warm_start, y.warm_start);
    const int p = x.multiplicity, extra = (cases[i].numerics.output_periods - 1) * p;
    EXPECT_EQ(x.multiplicity, y.multiplicity);
    EXPECT_EQ(x.periods_simulated, y.periods_simulated);
    EXPECT_EQ(x.rhs_evaluations, y.rhs_evaluations);
    EXPECT_EQ(a[i].result.sample_periods, b[i].result.sample_periods + extra);
    EXPECT_EQ(x.newton_iterations, y.newton_iterations);
    EXPECT_EQ(x.jacobian_evaluations, y.jacobian_evaluations);
    EXPECT_TRUE(same_bits(x.final_change, y.final_change));
    EXPECT_TRUE(same_bits(x.phi_drift, y.phi_drift));
    EXPECT_TRUE(same_bits(x.switches_per_period, y.switches_per_period));
    // The phase times and events of the periodic orbit, per sampled period.
    EXPECT_NEAR(a[i].result.stick_time / a[i].result.sample_periods,
                b[i].result.stick_time / b[i].result.sample_periods, 1e-9 / cases[i].roller.f);
    EXPECT_EQ(a[i].result.events.size() * b[i].result.sample_periods,
              b[i].result.events.size() * a[i].result.sample_periods);
    const Metrics &m = a[i].metrics, &n = b[i].metrics;
    for (auto member : {&Metrics::ddx_max, &Metrics::ddz_min, &Metrics::delta_max,
                        &Metrics::mu_required, &Metrics::area, &Metrics::psi_xz, &Metrics::phi_lag,
                        &Metrics::friction_work, &Metrics::stick_fraction})
      EXPECT_TRUE(same_bits(m.*member, n.*member));
    ASSERT_EQ(m.ddx_harmonics.size(), n.ddx_harmonics.size());
    for (std::size_t k = 0; k < m.ddx_harmonics.size(); ++k)
      EXPECT_TRUE(same_bits(m.ddx_harmonics[k].phase, n.ddx_harmonics[k].phase));
  }
}

TEST(Study, CallbacksAreSerialisedAndCoverEveryCase) {
  const std::vector<Case> cases = some_cases();
  StudyOptions options;
  options.threads = 3;
  std::vector<int> seen(cases.size(), 0);
  std::size_t last_done = 0;
  bool in_callback = false, overlapped = false;
  options.on_case_done = [&](std::size_t i, const CaseOutcome& outcome) {
    overlapped = overlapped || in_callback;
    in_callback = true;
    ++seen.at(i);
    EXPECT_GT(outcome.result.samples.size(), 0u);  // samples reach the callback ...
    in_callback = false;
  };
  options.progress = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(done, last_done + 1);
    EXPECT_EQ(total, cases.size());
    last_done = done;
  };
  const std::vector<CaseOutcome> out = run_study(cases, options);
  EXPECT_FALSE(overlapped);
  EXPECT_EQ(last_done, cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(seen[i], 1);
    EXPECT_EQ(out[i].result.samples.size(), 0u);  // ... but are dropped without keep_samples
    EXPECT_GT(out[i].metrics.ddx_max, 0.0);
  }
}

TEST(Study, CancellationBetweenCasesLeavesTheRestCancelled) {
  const std::vector<Case> cases = some_cases();
  StudyOptions options;
  options.threads = 1;
  std::size_t done = 0;
  options.on_case_done = [&](std::size_t, const CaseOutcome&) { ++done; };
  options.cancelled = [&] { return done >= 2; };
  const std::vector<CaseOutcome> out = run_study(cases, options);
  EXPECT_EQ(done, 2u);
  EXPECT_TRUE(out[0].valid);
  EXPECT_TRUE(out[1].valid);
  for (std::size_t i = 2; i < out.size(); ++i) {
    EXPECT_FALSE(out[i].valid);
    EXPECT_EQ(out[i].error, "cancelled");
    EXPECT_EQ(out[i].result.status, Status::cancelled);  // it said steady_state
    EXPECT_TRUE(std::isnan(out[i].metrics.area));        // it was 0
  }
}

// An invalid case (a trough smaller than the drum) is refused, not run: its outcome said status
// steady_state with every metric 0, which a list of o.metrics.area took for a number.
TEST(Study, AnInvalidCaseHasNoSteadyStateAndNoMetrics) {
  Case bad;
  bad.trough.shape = CircleTrough{0.59};
  const std::vector<Case> cases = {bad, Case{}};
  const std::vector<CaseOutcome> out = run_study(cases, StudyOptions{});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FALSE(out[0].valid);
  EXPECT_EQ(out[0].result.status, Status::invalid);
  EXPECT_EQ(out[0].result.message, out[0].error);
  EXPECT_TRUE(std::isnan(out[0].metrics.area));
  EXPECT_TRUE(std::isnan(out[0].metrics.ddx_max));
  // No diagnostic values either: a final_change of 0 read as converged, a min_N of 0 as contact
  // lost (the results CSV leaves these cells empty).
  EXPECT_TRUE(std::isnan(out[0].result.diagnostics.final_change));
  EXPECT_TRUE(std::isnan(out[0].result.diagnostics.min_N));
  EXPECT_TRUE(std::isnan(out[0].result.diagnostics.phi_drift));
  EXPECT_TRUE(std::isnan(out[0].result.stick_time));
  // A case a study did not run: cancelled, the same way (Python's Interrupted.result).
  const CaseOutcome never = not_run_outcome();
  EXPECT_FALSE(never.valid);
  EXPECT_EQ(never.error, "cancelled");
  EXPECT_EQ(never.result.status, Status::cancelled);
  EXPECT_TRUE(std::isnan(never.result.diagnostics.final_change));
  EXPECT_TRUE(std::isnan(never.metrics.area));
  EXPECT_TRUE(out[1].valid);
  EXPECT_EQ(out[1].result.status, Status::steady_state);
}

TEST(Study, CancellationStopsARunningCase) {
  // A long case: 1000 sampled periods of 10^4 samples (an impossible steady_tol no longer runs
  // forever: the steady state is accepted at the integration's noise floor, or by shooting).
  Case endless;
  endless.numerics.output_periods = 1000;
  endless.numerics.samples_per_period = 10000;
  endless.numerics.max_multiplicity = 1;
  const std::vector<Case> cases(2, endless);
  std::atomic<bool> stop{false};
  StudyOptions options;
  options.threads = 2;
  options.cancelled = [&] { return stop.load(); };
  std::size_t reported = 0;
  options.on_case_done = [&](std::size_t, const CaseOutcome&) { ++reported; };
  std::thread timer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    stop = true;
  });
  const auto start = std::chrono::steady_clock::now();
  const std::vector<CaseOutcome> out = run_study(cases, options);
  timer.join();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_EQ(reported, 0u);  // an interrupted case is not a result
  for (const CaseOutcome& o : out) EXPECT_EQ(o.error, "cancelled");
}

// Before its first case a study builds every case (its checks and its chains: seconds for a
// million). Cancelled then, it stops within a few thousand builds and runs nothing.
TEST(Study, CancellationWhilePlanningBuildsFewCases) {
  constexpr std::size_t n = 200000;
  std::size_t built = 0;
  const CaseSource case_at = [&](std::size_t i) {
    ++built;
    Case c;
    c.soil.input = SoilInput::modulus;
    c.soil.G = 5e6 + static_cast<double>(i);
    return c;
  };
  for (const bool chained : {false, true}) {
    SCOPED_TRACE(chained ? "links given" : "links found");
    built = 0;
    StudyOptions options;
    options.threads = 1;
    if (chained) {
      options.previous.assign(n, -1);
      for (std::size_t k = 1; k < n; ++k) options.previous[k] = static_cast<std::ptrdiff_t>(k - 1);
    }
    std::size_t polls = 0, reported = 0;
    options.cancelled = [&] { return ++polls > 3; };
    options.on_case_done = [&](std::size_t, const CaseOutcome&) { ++reported; };
    const std::vector<CaseOutcome> out = run_study(n, case_at, options);
    EXPECT_LT(built, 20000u);
    EXPECT_EQ(reported, 0u);
    ASSERT_EQ(out.size(), n);
    EXPECT_EQ(out.front().error, "cancelled");
    EXPECT_EQ(out.back().error, "cancelled");
  }
}

TEST(Study, InvalidCaseIsReportedNotThrown) {
  std::vector<Case> cases = some_cases();
  cases[1].trough.shape = CircleTrough{0.5};  // R < r
  const std::vector<CaseOutcome> out = run_study(cases, {});
  EXPECT_TRUE(out[0].valid);
  EXPECT_FALSE(out[1].valid);
  EXPECT_NE(out[1].error.find("trough.a"), std::string::npos);
  EXPECT_TRUE(out[2].valid);
  EXPECT_FALSE(run_case(cases[1]).valid);
}

// A harmonic count is bounded by the samples' Nyquist limit, before any case runs (10^7 harmonics
// of the dense output once took minutes per case).
TEST(Study, HarmonicsBeyondTheSamplesNyquistLimitAreRefused) {
  std::vector<Case> cases = some_cases();
  StudyOptions options;
  options.n_harmonics = cases[0].numerics.samples_per_period / 2;
  EXPECT_THROW(
      {
        try {
          run_study(cases, options);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("n_harmonics must be <"), std::string::npos);
          throw;
        }
      },
      Error);
  options.n_harmonics -= 1;
  cases.resize(1);
  EXPECT_TRUE(run_study(cases, options)[0].valid);
  const CaseOutcome single = run_case(cases[0], false, 10'000'000);
  EXPECT_FALSE(single.valid);
  EXPECT_NE(single.error.find("n_max must be <"), std::string::npos);
}

TEST(Study, CallbackExceptionStopsTheStudyAndPropagates) {
  const std::vector<Case> cases = some_cases();
  StudyOptions options;
  options.threads = 2;
  options.on_case_done = [](std::size_t, const CaseOutcome&) {
    throw std::runtime_error("disk full");
  };
  EXPECT_THROW(run_study(cases, options), std::runtime_error);
  EXPECT_TRUE(run_study({}, options).empty());
}

// concurrent_on_case_done: the callbacks of different workers may overlap (here they are made
// to: each waits until another one has started or the study is nearly done), every case is
// reported once, progress stays serialised and counts every case, and an exception still stops
// the study and reaches the caller.
TEST(Study, ConcurrentCallbacksOverlapAndCoverEveryCase) {
  const std::vector<Case> cases = some_cases();
  StudyOptions options;
  options.threads = 2;
  options.concurrent_on_case_done = true;
  std::mutex m;
  std::vector<int> seen(cases.size(), 0);
  std::atomic<int> inside{0}, most{0};
  options.on_case_done = [&](std::size_t i, const CaseOutcome& outcome) {
    const int now = ++inside;
    for (int seen_most = most.load(); seen_most < now;)
      if (most.compare_exchange_weak(seen_most, now)) break;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
    while (inside.load() < 2 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
    {
      const std::lock_guard lock(m);
      ++seen.at(i);
    }
    EXPECT_GT(outcome.result.samples.size(), 0u);
    --inside;
  };
  std::size_t last_done = 0;
  options.progress = [&](std::size_t done, std::size_t) {
    EXPECT_EQ(done, last_done + 1);
    last_done = done;
  };
  run_study(cases, options);
  EXPECT_EQ(most.load(), 2);
  EXPECT_EQ(last_done, cases.size());
  for (int n : seen) EXPECT_EQ(n, 1);
  options.on_case_done = [](std::size_t, const CaseOutcome&) {
    throw std::runtime_error("disk full");
  };
  EXPECT_THROW(run_study(cases, options), std::runtime_error);
}

}  // namespace
}  // namespace oscidrum
