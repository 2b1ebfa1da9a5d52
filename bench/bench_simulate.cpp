// Benchmarks of one steady-state case from rest, as the issue asks: pure rolling and stick-slip
// (G = 25 MN/m^2, mu = 0.5, MMd = 0.05 M0), each at the default tolerance and at rtol = 1e-7.
// Counters: RHS evaluations, accepted steps and periods to the steady state per case. Every
// iteration simulates from the same immutable Model (no state carried between iterations).
#include <benchmark/benchmark.h>
#include <time.h>

#include <vector>

#include "oscidrum/oscidrum.hpp"
#include "oscidrum_paper/validation.hpp"

namespace {

oscidrum::Case bench_case(bool pure_rolling, double MMd_fraction, double rtol,
                          oscidrum::SteadyMethod method = oscidrum::SteadyMethod::transient,
                          double R = 0.606) {
  oscidrum::Case c;
  c.numerics.method = method;
  c.trough.shape = oscidrum::CircleTrough{R};
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

// The same, interleaved: every iteration runs the case with both methods and times each by the
// thread's CPU clock, so that both see the same machine load; the counters are the two times per
// case, their ratio and each method's period-equivalents (RHS-evaluation cost in plain periods).
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void side_by_side(benchmark::State& state, oscidrum::Case c) {
  c.numerics.method = SteadyMethod::transient;
  const oscidrum::Model transient(c);
  c.numerics.method = SteadyMethod::shooting;
  const oscidrum::Model shooting(c);
  double t_transient = 0.0, t_shooting = 0.0;
  oscidrum::Result a, b;
  for (auto _ : state) {
    double t0 = cpu_seconds();
    a = oscidrum::simulate(transient);
    const double t1 = cpu_seconds();
    b = oscidrum::simulate(shooting);
    t_transient += t1 - t0;
    t_shooting += cpu_seconds() - t1;
    benchmark::DoNotOptimize(b.samples.ddx_M.data());
  }
  if (a.status != oscidrum::Status::steady_state) state.SkipWithError(a.message.c_str());
  if (b.diagnostics.method != SteadyMethod::shooting)
    state.SkipWithError(("shooting fell back: " + b.diagnostics.fallback).c_str());
  const double n = static_cast<double>(state.iterations());
  state.counters["transient_ms"] = 1e3 * t_transient / n;
  state.counters["shooting_ms"] = 1e3 * t_shooting / n;
  state.counters["speedup"] = t_transient / t_shooting;
  state.counters["pe_transient"] = a.diagnostics.period_equivalents;
  state.counters["pe_shooting"] = b.diagnostics.period_equivalents;
  state.counters["newton"] = b.diagnostics.newton_iterations;
}

void BM_SideBySide_StickSlip(benchmark::State& s) { side_by_side(s, bench_case(false, 0.05, 0)); }
void BM_SideBySide_Rolling_R0606(benchmark::State& s) { side_by_side(s, bench_case(true, 0.0, 0)); }
void BM_SideBySide_Rolling_R065(benchmark::State& s) {
  side_by_side(s, bench_case(true, 0.0, 0, SteadyMethod::transient, 0.65));
}
BENCHMARK(BM_SideBySide_StickSlip)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SideBySide_Rolling_R0606)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SideBySide_Rolling_R065)->Unit(benchmark::kMillisecond);

// The steady-state metrics (compute_metrics(model, result): one period integrated again, peaks,
// harmonics, lags, area on the trajectory) against the simulation (shooting) they follow: every
// iteration runs both, each timed by the thread's CPU clock.
void metrics_after_simulate(benchmark::State& state, oscidrum::Case c) {
  c.numerics.method = SteadyMethod::shooting;
  const oscidrum::Model model(c);
  double t_simulate = 0.0, t_metrics = 0.0;
  for (auto _ : state) {
    const double t0 = cpu_seconds();
    const oscidrum::Result r = oscidrum::simulate(model);
    const double t1 = cpu_seconds();
    if (r.status != oscidrum::Status::steady_state) {
      state.SkipWithError(r.message.c_str());
      break;
    }
    const oscidrum::Metrics m = oscidrum::compute_metrics(model, r);
    t_simulate += t1 - t0;
    t_metrics += cpu_seconds() - t1;
    benchmark::DoNotOptimize(m.area);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["simulate_ms"] = 1e3 * t_simulate / n;
  state.counters["metrics_ms"] = 1e3 * t_metrics / n;
}
void BM_Metrics_StickSlip(benchmark::State& s) {
  metrics_after_simulate(s, bench_case(false, 0.05, 0));
}
void BM_Metrics_Rolling_R0606(benchmark::State& s) {
  metrics_after_simulate(s, bench_case(true, 0.0, 0));
}
BENCHMARK(BM_Metrics_StickSlip)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Metrics_Rolling_R0606)->Unit(benchmark::kMillisecond);

// `oscidrum validate`: all of the paper's cases on all cores, and the check of every claim (the
// command's work without its output); wall time.
void validate_with(benchmark::State& state, SteadyMethod method) {
  oscidrum::PaperRunOptions o;
  o.method = method;
  std::size_t agree = 0;
  for (auto _ : state) {
    const std::vector<oscidrum::ValidationRow> rows =
        oscidrum::validate(oscidrum::run_paper_studies(o));
    agree = 0;
    for (const auto& r : rows) agree += r.agrees;
    benchmark::DoNotOptimize(agree);
  }
  state.counters["claims_agreeing"] = static_cast<double>(agree);
}
void BM_Validate_Shooting(benchmark::State& s) { validate_with(s, SteadyMethod::shooting); }
void BM_Validate_Transient(benchmark::State& s) { validate_with(s, SteadyMethod::transient); }
BENCHMARK(BM_Validate_Shooting)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Validate_Transient)->Unit(benchmark::kMillisecond)->UseRealTime();

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

// Unilateral contact (issue 27): a steady state with flight against comparable cases without
// (pure rolling, Appendix B soil, 65 Hz with M0 following f^2): G = 80 MN/m^2 lifts off once per
// period; G = 40 MN/m^2 stays in contact, with unilateral contact and with the paper's.
oscidrum::Case flight_case(double G, bool unilateral) {
  oscidrum::Case c;
  c.soil.input = oscidrum::SoilInput::modulus;
  c.soil.G = G;
  c.roller.f = 65.0;
  c.roller.unbalance = 0.22877;
  c.contact.pure_rolling = true;
  c.contact.unilateral = unilateral;
  return c;
}
void BM_Unilateral_WithFlight_G80(benchmark::State& s) { run(s, flight_case(80e6, true)); }
void BM_Unilateral_NoFlight_G40(benchmark::State& s) { run(s, flight_case(40e6, true)); }
void BM_Permanent_NoFlight_G40(benchmark::State& s) { run(s, flight_case(40e6, false)); }
BENCHMARK(BM_Unilateral_WithFlight_G80)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Unilateral_NoFlight_G40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Permanent_NoFlight_G40)->Unit(benchmark::kMillisecond);

// The vibratory drum (issue 28: a case from rest at most 1 ms): examples/vibratory.toml (the
// paper's drum, circular exciter m_u e_u = 0.9 kg m at 30 Hz, mu = 0.5, unilateral contact) on
// Table 2 soil, G = 10 MN/m^2 in continuous contact and G = 25 MN/m^2 in partial uplift.
oscidrum::Case vibratory_case(double G) {
  oscidrum::Case c;
  oscidrum::set_field_text(c, "roller.type", "vibratory");
  c.roller.static_moment = 0.9;
  c.roller.f = 30.0;
  c.contact.unilateral = true;
  c.soil.G = G;
  return c;
}
void BM_Vibratory_ContinuousContact_G10(benchmark::State& s) { run(s, vibratory_case(10e6)); }
void BM_Vibratory_PartialUplift_G25(benchmark::State& s) { run(s, vibratory_case(25e6)); }
BENCHMARK(BM_Vibratory_ContinuousContact_G10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Vibratory_PartialUplift_G25)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
