// What a Jacobian costs: the weight Diagnostics::period_equivalents gives one evaluation of a
// phase Jacobian (with its share of the Magnus step of the sensitivity matrix), measured.
// At a steady orbit found by shooting, one excitation period is integrated alternately plainly
// and with the variational equations (the monodromy observer shooting uses), each timed by the
// thread's CPU clock. Counters: the CPU time of each map, the right-hand sides and Jacobians
// each evaluates, and jacobian_cost = (t_variational - t_plain) / Jacobians over the time of one
// right-hand side (t_plain / its right-hand sides), the number src/drivers/simulate.cpp's
// kJacobianCost must be close to.
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <string>

#include "drivers/continuation.hpp"
#include "drivers/shooting.hpp"
#include "flow/matrix_product.hpp"
#include "flow/monodromy.hpp"
#include "oscidrum/oscidrum.hpp"
#include "roller/oscillation_drum.hpp"

namespace {

using oscidrum::SteadyMethod;

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void maps(benchmark::State& state, oscidrum::Case c) {
  using R = oscidrum::OscillationDrum;
  c.numerics.method = SteadyMethod::shooting;
  const oscidrum::Model model(c);
  const oscidrum::Result r = oscidrum::simulate(model);
  const auto orbit = oscidrum::detail::orbit_start(model, r);
  if (r.status != oscidrum::Status::steady_state || !orbit) {
    state.SkipWithError(("no period-1 steady state: " + r.message).c_str());
    return;
  }
  oscidrum::detail::Dynamics<R>::Vector x{};
  std::copy(orbit->state.begin(), orbit->state.end(), x.begin());
  const auto z = R::State::from_array(x);
  const oscidrum::FlowOptions options = oscidrum::FlowOptions::from(model);
  oscidrum::BasicFlow<R> flow(model, options);
  oscidrum::detail::MonodromyObserver<R> mono(
      model, options.baumgarte, model.period() / oscidrum::detail::kMonodromyStepsPerPeriod);
  const double T = model.period();
  double t_plain = 0.0, t_var = 0.0;
  long rhs_plain = 0, rhs_var = 0, jacobians = 0;
  for (auto _ : state) {
    long rhs0 = flow.counters().rhs_evaluations;
    double t0 = cpu_seconds();
    flow.reset(0.0, z, orbit->phase);
    flow.advance(T);
    const double t1 = cpu_seconds();
    t_plain += t1 - t0;
    rhs_plain += flow.counters().rhs_evaluations - rhs0;
    rhs0 = flow.counters().rhs_evaluations;
    const long jac0 = mono.jacobian_evaluations();
    flow.reset(0.0, z, orbit->phase);
    mono.reset();
    flow.advance(T, &mono);
    t_var += cpu_seconds() - t1;
    rhs_var += flow.counters().rhs_evaluations - rhs0;
    jacobians += mono.jacobian_evaluations() - jac0;
    benchmark::DoNotOptimize(mono.phi().data());
  }
  const double n = static_cast<double>(state.iterations());
  const double per_rhs = t_plain / static_cast<double>(rhs_plain);
  state.counters["plain_us"] = 1e6 * t_plain / n;
  state.counters["variational_us"] = 1e6 * t_var / n;
  state.counters["rhs"] = static_cast<double>(rhs_plain) / n;
  state.counters["jacobians"] = static_cast<double>(jacobians) / n;
  state.counters["jacobian_cost"] =
      (t_var - t_plain - per_rhs * static_cast<double>(rhs_var - rhs_plain)) /
      static_cast<double>(jacobians) / per_rhs;
}

oscidrum::Case product_case(double G, double mu, double MMd_fraction) {
  oscidrum::Case c;
  c.soil.input = oscidrum::SoilInput::modulus;
  c.soil.G = G;
  c.contact.mu = mu;
  c.MMd = MMd_fraction * c.roller.M0;
  return c;
}

// The paper's defaults; the product sweep's soil (Appendix B) in stick-slip and pure rolling.
void BM_Maps_PaperDefaults(benchmark::State& s) { maps(s, oscidrum::Case{}); }
void BM_Maps_Product_G50_StickSlip(benchmark::State& s) { maps(s, product_case(50e6, 0.5, 0.05)); }
void BM_Maps_Product_G50_PureRolling(benchmark::State& s) {
  oscidrum::Case c = product_case(50e6, 0.5, 0.0);
  c.contact.pure_rolling = true;
  maps(s, c);
}
BENCHMARK(BM_Maps_PaperDefaults)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Maps_Product_G50_StickSlip)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Maps_Product_G50_PureRolling)->Unit(benchmark::kMicrosecond);

// One 8 x 8 product by each wide kernel this processor can run (src/flow/matrix_product.hpp),
// called through its pointer, and by Eigen's lazyProduct inlined (where there is none): what a
// Magnus step's 12-15 products cost (the inputs are read anew at every iteration: DoNotOptimize
// clobbers memory).
void product_kernel(benchmark::State& state,
                    void (*multiply)(const double*, const double*, double*) noexcept) {
  using Mat8 = Eigen::Matrix<double, 8, 8>;
  const Mat8 A = Mat8::Random(), B = Mat8::Random();
  Mat8 C;
  for (auto _ : state) {
    benchmark::DoNotOptimize(A.data());
    multiply(A.data(), B.data(), C.data());
    benchmark::DoNotOptimize(C.data());
  }
}
void BM_Product8_EigenInline(benchmark::State& state) {
  using Mat8 = Eigen::Matrix<double, 8, 8>;
  const Mat8 A = Mat8::Random(), B = Mat8::Random();
  Mat8 C;
  for (auto _ : state) {
    benchmark::DoNotOptimize(A.data());
    C = A.lazyProduct(B);
    benchmark::DoNotOptimize(C.data());
  }
}
BENCHMARK(BM_Product8_EigenInline)->Unit(benchmark::kNanosecond);
const int registered = [] {
  for (const auto& kernel : oscidrum::detail::wide_product8_kernels())
    benchmark::RegisterBenchmark((std::string("BM_Product8_") + kernel.name).c_str(),
                                 product_kernel, kernel.multiply)
        ->Unit(benchmark::kNanosecond);
  return 0;
}();

}  // namespace

BENCHMARK_MAIN();
