// Benchmarks of one steady-state case from rest, as the issue asks: pure rolling and stick-slip
// (G = 25 MN/m^2, mu = 0.5, MMd = 0.05 M0), each at the default tolerance and at rtol = 1e-7.
// Counters: RHS evaluations, accepted steps and periods to the steady state per case. Every
// iteration simulates from the same immutable Model (no state carried between iterations).
#include <benchmark/benchmark.h>

#include "oscidrum/oscidrum.hpp"

namespace {

oscidrum::Case bench_case(bool pure_rolling, double MMd_fraction, double rtol,
                          oscidrum::SteadyMethod method = oscidrum::SteadyMethod::transient,
                          double R = 0.606) {
  oscidrum::Case c;
  c.numerics.method = method;
  c.trough.a = R;
  c.soil = oscidrum::table2_soil(25e6);
  c.contact.pure_rolling = pure_rolling;
  c.contact.mu = 0.5;
  c.MMd = MMd_fraction * c.roller.M0;
  if (rtol > 0) {
    c.numerics.rtol = rtol;
    c.numerics.atol = rtol * 1e-3;
  }
  return c;
}

void run(benchmark::State& state, const oscidrum::Case& c) {
  const oscidrum::Model model(c);
  oscidrum::Result r;
  for (auto _ : state) {
    r = oscidrum::simulate(model);
    benchmark::DoNotOptimize(r.samples.ddx_M.data());
  }
  if (r.status != oscidrum::Status::steady_state) state.SkipWithError(r.message.c_str());
  state.counters["rhs_evals"] = static_cast<double>(r.diagnostics.rhs_evaluations);
  state.counters["steps"] = static_cast<double>(r.diagnostics.steps);
  state.counters["periods"] = r.diagnostics.periods_to_steady;
  state.counters["period_equivalents"] = r.diagnostics.period_equivalents;
  state.counters["newton"] = r.diagnostics.newton_iterations;
}

// Shooting against the transient method, side by side (issue 7): the default stick-slip case,
// pure rolling at R = 0.606 m and R = 0.65 m (MMd = 0).
using oscidrum::SteadyMethod;
void BM_Method_StickSlip_Transient(benchmark::State& s) {
  run(s, bench_case(false, 0.05, 0, SteadyMethod::transient));
}
void BM_Method_StickSlip_Shooting(benchmark::State& s) {
  run(s, bench_case(false, 0.05, 0, SteadyMethod::shooting));
}
void BM_Method_Rolling_R0606_Transient(benchmark::State& s) {
  run(s, bench_case(true, 0.0, 0, SteadyMethod::transient));
}
void BM_Method_Rolling_R0606_Shooting(benchmark::State& s) {
  run(s, bench_case(true, 0.0, 0, SteadyMethod::shooting));
}
void BM_Method_Rolling_R065_Transient(benchmark::State& s) {
  run(s, bench_case(true, 0.0, 0, SteadyMethod::transient, 0.65));
}
void BM_Method_Rolling_R065_Shooting(benchmark::State& s) {
  run(s, bench_case(true, 0.0, 0, SteadyMethod::shooting, 0.65));
}
BENCHMARK(BM_Method_StickSlip_Transient)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Method_StickSlip_Shooting)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Method_Rolling_R0606_Transient)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Method_Rolling_R0606_Shooting)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Method_Rolling_R065_Transient)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Method_Rolling_R065_Shooting)->Unit(benchmark::kMillisecond);

void BM_StickSlip_G25_MMd005(benchmark::State& s) { run(s, bench_case(false, 0.05, 0)); }
void BM_StickSlip_G25_MMd005_rtol1e7(benchmark::State& s) { run(s, bench_case(false, 0.05, 1e-7)); }
void BM_PureRolling_G25_MMd005(benchmark::State& s) { run(s, bench_case(true, 0.05, 0)); }
void BM_PureRolling_G25_MMd005_rtol1e7(benchmark::State& s) {
  run(s, bench_case(true, 0.05, 1e-7));
}
void BM_PureRolling_G25_MMd0(benchmark::State& s) { run(s, bench_case(true, 0.0, 0)); }

BENCHMARK(BM_StickSlip_G25_MMd005)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StickSlip_G25_MMd005_rtol1e7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PureRolling_G25_MMd005)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PureRolling_G25_MMd005_rtol1e7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PureRolling_G25_MMd0)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
