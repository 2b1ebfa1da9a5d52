// Benchmarks of the identification (docs/identify.md): one window of 40 periods at 1 kHz, and a
// pass of 60 s at 1 kHz in 1 s windows (39 periods), each window started from the previous one.
#include <benchmark/benchmark.h>

#include "oscidrum/oscidrum.hpp"

namespace {

oscidrum::RecordSamples record(double duration, bool pure_rolling) {
  oscidrum::Case c;
  const double f = 39.0 * 1.01;
  c.soil.input = oscidrum::SoilInput::modulus;
  c.soil.G = 17.3e6;
  c.contact.pure_rolling = pure_rolling;
  c.roller.M0 *= (f / 39.0) * (f / 39.0);
  c.roller.f = f;
  oscidrum::SyntheticRecord o;
  o.duration = duration;
  o.noise = 0.05;
  o.drift = 0.05;
  return oscidrum::synthetic_record({c}, o);
}

void BM_IdentifyOneWindow(benchmark::State& state) {
  const bool pure_rolling = state.range(0) != 0;
  const oscidrum::RecordSamples r = record(1.05, pure_rolling);
  oscidrum::Case base;
  base.contact.pure_rolling = pure_rolling;
  oscidrum::WindowOptions w;
  w.window_periods = 40;
  for (auto _ : state)
    benchmark::DoNotOptimize(oscidrum::identify_pass(base, r.t, r.ddx_M, r.ddz_M, {}, w));
}
BENCHMARK(BM_IdentifyOneWindow)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_IdentifyPass60s(benchmark::State& state) {
  const oscidrum::RecordSamples r = record(60.0, false);
  oscidrum::WindowOptions w;
  w.window_periods = 39;
  for (auto _ : state)
    benchmark::DoNotOptimize(
        oscidrum::identify_pass(oscidrum::Case{}, r.t, r.ddx_M, r.ddz_M, {}, w));
}
BENCHMARK(BM_IdentifyPass60s)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
