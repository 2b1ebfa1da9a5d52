// The forward model of the identification (identify.hpp, simulate_metrics): one bounded run of
// the model to its steady state, reduced to its metrics and what the fit needs beside them.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "drivers/period_recording.hpp"
#include "identify/problem.hpp"
#include "oscidrum/identify.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum {

ModelResponse simulate_metrics(const Case& c, int n_max, long max_steps) {
  return detail::simulate_metrics_from(c, n_max, max_steps, nullptr, nullptr);
}

std::array<double, 2> detail::PeriodicSignal::at(double t) const {
  double u = std::fmod(t - t0, period);
  if (u < 0.0) u += period;
  u += t0;
  const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(
      0, std::upper_bound(starts.begin(), starts.end(), u) - starts.begin() - 1));
  return {x[k](u), z[k](u)};
}

ModelResponse detail::simulate_metrics_from(const Case& c, int n_max, long max_steps,
                                            const WarmStart* warm, std::optional<WarmStart>* orbit,
                                            PeriodicSignal* signal) {
  if (signal != nullptr) *signal = PeriodicSignal{};  // (none without a steady state)
  const Model model(c);
  // The budget counts the flow's polls of `cancelled`: one per accepted integration step.
  long steps = 0;
  std::function<bool()> over_budget;
  if (max_steps > 0) over_budget = [&steps, max_steps] { return ++steps > max_steps; };
  recording::Recording period;  // the steady period, as the sampling integrated it
  const Result r = simulate_from(model, {}, over_budget, warm, true, &period);
  if (orbit) *orbit = orbit_start(model, r, period);
  ModelResponse out;
  out.status = r.status;
  out.message = r.message;
  out.friction_ratio = std::numeric_limits<double>::quiet_NaN();
  out.steps = r.diagnostics.steps;
  if (r.status == Status::cancelled && max_steps > 0 && steps > max_steps) {
    out.status = Status::budget_exceeded;
    out.message = "no steady state within " + std::to_string(max_steps) +
                  " integration steps (the budget of one model run; " + r.message + ")";
    return out;
  }
  // The harmonics are integrals over the trajectory itself (compute_metrics(model, result)):
  // read off the samples, harmonics above half their number would alias onto the compared ones
  // (about 0.1 % of G at 64 samples per period, a bias comparable to the uncertainty of a
  // record at 5 kHz).
  if (ok(r.status)) out.metrics = compute_metrics(model, r, n_max, &period);
  if (signal != nullptr && ok(r.status)) {
    const recording::Recording rec = steady_period(model, r, &period);
    signal->t0 = rec.t_begin;
    signal->period = rec.t_end - rec.t_begin;
    for (const recording::Piece& pc : rec.pieces) {
      signal->starts.push_back(pc.a);
      signal->x.push_back(pc.f[recording::kDdx]);
      signal->z.push_back(pc.f[recording::kDdz]);
    }
  }
  if (r.status == Status::steady_state) {
    double ratio = 0;
    for (std::size_t j = 0; j < r.samples.size(); ++j)
      ratio = std::max(ratio, std::abs(r.samples.T[j]) / r.samples.N[j]);
    out.friction_ratio = ratio;
    out.switches_per_period = r.diagnostics.switches_per_period;
  }
  return out;
}

}  // namespace oscidrum
