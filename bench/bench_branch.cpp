// Benchmark of the continuation of periodic orbits (oscidrum continue, docs/bifurcations.md):
// branches of the paper's roller on one core, with and without the metrics of every orbit.
// Counters: points on the branch, points per second, period maps per point. Issue 29 asks for a
// branch of 200 points in at most 1 s on one core.
#include <benchmark/benchmark.h>

#include "oscidrum/oscidrum.hpp"

namespace {

// soil.G from 10 to 60 MN/m^2 (Appendix B), the paper's roller, mu = 0.5: about 200 points at
// the default steps.
void branch_in_G(benchmark::State& state) {
  oscidrum::Case c;
  oscidrum::set_field_text(c, "soil.input", "modulus");
  oscidrum::BranchOptions o;
  o.key = "soil.G";
  o.from = 10e6;
  o.to = 60e6;
  o.metrics = state.range(0) != 0;
  oscidrum::Branch b;
  for (auto _ : state) {
    b = oscidrum::continue_branch(c, o);
    benchmark::DoNotOptimize(b.points.data());
  }
  if (b.end != oscidrum::BranchEnd::reached_end) state.SkipWithError(b.message.c_str());
  const double points = static_cast<double>(b.points.size());
  state.counters["points"] = points;
  state.counters["points_per_s"] =
      benchmark::Counter(points, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["maps_per_point"] = static_cast<double>(b.period_maps) / points;
}

// The driving torque to the gross-slip limit (two grazings located by bisection).
void branch_in_MMd(benchmark::State& state) {
  oscidrum::Case c;
  oscidrum::BranchOptions o;
  o.key = "MMd";
  o.from = 0.0;
  o.to = 14000.0;
  o.metrics = false;
  oscidrum::Branch b;
  for (auto _ : state) {
    b = oscidrum::continue_branch(c, o);
    benchmark::DoNotOptimize(b.points.data());
  }
  const double points = static_cast<double>(b.points.size());
  state.counters["points"] = points;
  state.counters["bifurcations"] = static_cast<double>(b.bifurcations.size());
  state.counters["maps_per_point"] = static_cast<double>(b.period_maps) / points;
}

}  // namespace

BENCHMARK(branch_in_G)->Arg(0)->Arg(1)->ArgName("metrics")->Unit(benchmark::kMillisecond);
BENCHMARK(branch_in_MMd)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
