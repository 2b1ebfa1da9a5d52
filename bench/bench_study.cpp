// Benchmark of a Table 2 sweep with shooting, warm-started case to case (continuation,
// docs/periodic.md) against every case from rest, on one thread: 14 G x 4 trough radii x
// {stick-slip, pure rolling} = 112 cases, G varying fastest (the chains). Counter: cases per
// second (per core: one thread).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "oscidrum/oscidrum.hpp"

namespace {

std::vector<oscidrum::Case> table2_sweep(bool continuation) {
  std::vector<oscidrum::Case> cases;
  for (double R : {0.603, 0.606, 0.62, 0.65})
    for (bool pure : {false, true})
      for (const oscidrum::Table2Row& row : oscidrum::table2()) {
        oscidrum::Case c;
        c.numerics.method = oscidrum::SteadyMethod::shooting;
        c.numerics.continuation = continuation;
        c.trough.shape = oscidrum::CircleTrough{R};
        c.soil = oscidrum::table2_soil(row.G);
        c.contact.pure_rolling = pure;
        cases.push_back(c);
      }
  return cases;
}

void run(benchmark::State& state, bool continuation) {
  const std::vector<oscidrum::Case> cases = table2_sweep(continuation);
  oscidrum::StudyOptions options;
  options.threads = 1;
  std::vector<oscidrum::CaseOutcome> out;
  for (auto _ : state) {
    out = oscidrum::run_study(cases, options);
    benchmark::DoNotOptimize(out.data());
  }
  double warm = 0, equivalents = 0;
  for (const oscidrum::CaseOutcome& o : out) {
    if (!o.valid || o.result.status != oscidrum::Status::steady_state) {
      state.SkipWithError("a case did not reach its steady state");
      return;
    }
    warm += o.result.diagnostics.warm_start == 1;
    equivalents += o.result.diagnostics.period_equivalents;
  }
  const double n = static_cast<double>(cases.size());
  state.counters["cases_per_s"] =
      benchmark::Counter(n * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["warm_started"] = warm;
  state.counters["period_equivalents"] = equivalents / n;
}

// The study a user would write (the performance issue's measure): soil by Appendix B, G = 5 ... 100
// MN/m^2 in 400 steps x mu in {0.4, 0.5, 0.6} x MMd_fraction in {0, 0.05} = 2400 cases, the first
// key varying slowest (as a study file's product expands).
std::vector<oscidrum::Case> product_sweep(bool continuation) {
  std::vector<oscidrum::Case> cases;
  for (int i = 0; i < 400; ++i)
    for (double mu : {0.4, 0.5, 0.6})
      for (double fraction : {0.0, 0.05}) {
        oscidrum::Case c;
        c.numerics.method = oscidrum::SteadyMethod::shooting;
        c.numerics.continuation = continuation;
        c.soil.input = oscidrum::SoilInput::modulus;
        c.soil.G = 5e6 + (100e6 - 5e6) * i / 399.0;
        c.contact.mu = mu;
        c.MMd = fraction * c.roller.M0;
        cases.push_back(c);
      }
  return cases;
}

void run_product(benchmark::State& state, bool continuation) {
  const std::vector<oscidrum::Case> cases = product_sweep(continuation);
  oscidrum::StudyOptions options;
  options.threads = static_cast<int>(state.range(0));
  // Chained along G, the factor with the most values, as `oscidrum sweep` chains a study: each
  // case starts from the case 6 rows before it (same mu and MMd_fraction, the previous G).
  options.previous.assign(cases.size(), -1);
  for (std::size_t k = 6; k < cases.size(); ++k)
    options.previous[k] = static_cast<std::ptrdiff_t>(k - 6);
  std::vector<oscidrum::CaseOutcome> out;
  for (auto _ : state) {
    out = oscidrum::run_study(cases, options);
    benchmark::DoNotOptimize(out.data());
  }
  std::vector<double> warm_work;
  double warm = 0, steady = 0;
  for (const oscidrum::CaseOutcome& o : out) {
    steady += o.valid && o.result.status == oscidrum::Status::steady_state;
    if (o.valid && o.result.diagnostics.warm_start == 1) {
      ++warm;
      warm_work.push_back(o.result.diagnostics.period_equivalents);
    }
  }
  const double n = static_cast<double>(cases.size());
  state.counters["cases_per_s"] =
      benchmark::Counter(n * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["steady"] = steady;
  state.counters["warm_started"] = warm;
  if (!warm_work.empty()) {
    std::nth_element(warm_work.begin(), warm_work.begin() + warm_work.size() / 2, warm_work.end());
    state.counters["warm_median_period_eq"] = warm_work[warm_work.size() / 2];
  }
}

void BM_ProductSweep_Continuation(benchmark::State& s) { run_product(s, true); }
void BM_ProductSweep_FromRest(benchmark::State& s) { run_product(s, false); }
BENCHMARK(BM_ProductSweep_Continuation)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ProductSweep_FromRest)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Table2Sweep_Shooting_Continuation(benchmark::State& s) { run(s, true); }
void BM_Table2Sweep_Shooting_FromRest(benchmark::State& s) { run(s, false); }
BENCHMARK(BM_Table2Sweep_Shooting_Continuation)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Table2Sweep_Shooting_FromRest)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
