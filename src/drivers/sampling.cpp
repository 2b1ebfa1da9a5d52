// The sampling driver (src/drivers/sampling.hpp): an observer of the flow that takes uniform
// samples from the dense output of each piece of the trajectory.
#include "drivers/sampling.hpp"

#include <algorithm>

#include "equations/equations.hpp"
#include "oscidrum/kinematics.hpp"

namespace oscidrum::detail {
namespace {

class Sampler : public FlowObserver {
 public:
  Sampler(const Flow& flow, double t_start, int periods, int per_period, bool all_samples,
          Result& result)
      : model_(flow.model()),
        baumgarte_(flow.options().baumgarte),
        period_(flow.model().period()),
        t_start_(t_start),
        t_end_(t_start + periods * flow.model().period()),
        per_period_(per_period),
        total_(all_samples ? static_cast<long>(periods) * per_period : 1),
        result_(result) {}

  bool on_step(const StepView& step) override {
    // Samples in [t0, t1] not yet taken (a sample on a piece boundary belongs to the first).
    while (next_ < total_) {
      const double ts = t_start_ + static_cast<double>(next_) * period_ / per_period_;
      if (ts > step.t1()) break;
      append_sample(model_, baumgarte_, ts, step.state(ts), step.phase(), result_.samples);
      ++next_;
    }
    const double lo = std::max(step.t0(), t_start_), hi = std::min(step.t1(), t_end_);
    if (hi > lo) {
      if (step.phase() != Phase::smooth) {
        add_time(step.phase(), hi - lo);
      } else {
        // The smooth phase of a regularised law: the time in each apparent phase, from the
        // midpoints of kSmoothParts equal parts of the piece (a piece is at most T/16, so the
        // times are good to about 1/500 of a period).
        constexpr int kSmoothParts = 16;
        const double h = (hi - lo) / kSmoothParts;
        for (int i = 0; i < kSmoothParts; ++i) {
          const State q = step.state(lo + (i + 0.5) * h);
          add_time(apparent_phase(model_.friction(), Phase::smooth, slip_velocity(model_, q)), h);
        }
      }
    }
    return true;
  }

  void add_time(Phase phase, double dt) {
    switch (phase) {
      case Phase::stick:
        result_.stick_time += dt;
        break;
      case Phase::slip_positive:
        result_.slip_positive_time += dt;
        break;
      case Phase::slip_negative:
        result_.slip_negative_time += dt;
        break;
      case Phase::smooth:
        break;  // apparent phases only
    }
  }

  bool on_event(const Event& event, const State&, const State&) override {
    if (event.t >= t_start_ && event.t < t_end_) result_.events.push_back(event);
    return true;
  }

 private:
  const Model& model_;
  const double baumgarte_, period_, t_start_, t_end_;
  const int per_period_;
  const long total_;  // samples to record
  long next_ = 0;
  Result& result_;
};

}  // namespace

void append_sample(const Model& model, double baumgarte, double t, const State& q, Phase phase,
                   Samples& s) {
  const Kinematics k = kinematics(model.geometry(), q.delta);  // once for all columns
  const Accelerations a = accelerations(model, t, q, phase, baumgarte, k);
  const DrumMotion d = drum_motion(q, a, k);
  const ContactForces f = contact_forces(model, q, k);
  // In stick phi' is fixed by the rolling condition (12), phi' = f5 delta', and the drum does not
  // slide (v_rel = 0, (13)). The flow integrates phi' there without reading it, so the state's
  // own phi' carries the integration's round-off drift (up to ~1e-9 rad/s after a long transient
  // from rest): the columns report the constrained values instead.
  const bool stick = phase == Phase::stick;
  const double v_rel = stick ? 0.0 : slip_velocity(model, q, k);
  s.t.push_back(t);
  s.delta.push_back(q.delta);
  s.phi.push_back(q.phi);
  s.x_A.push_back(q.x_A);
  s.s_A.push_back(q.s_A);
  s.ddelta.push_back(q.ddelta);
  s.dphi.push_back(stick ? k.f5 * q.ddelta : q.dphi);
  s.dx_A.push_back(q.dx_A);
  s.ds_A.push_back(q.ds_A);
  s.x_M.push_back(d.x_M);
  s.z_M.push_back(d.z_M);
  s.ddx_M.push_back(d.ddx_M);
  s.ddz_M.push_back(d.ddz_M);
  s.N.push_back(f.N);
  s.T.push_back(f.T);
  s.v_rel.push_back(v_rel);
  s.torque.push_back(model.torque(t));
  // A smooth law's samples show the apparent phase (stick while creeping, oscidrum/friction.hpp).
  s.phase.push_back(apparent_phase(model.friction(), phase, v_rel));
}

FlowStop sample_periods(Flow& flow, int periods, int samples_per_period, Result& result,
                        bool all_samples) {
  const double t0 = flow.t();
  result.sample_periods = periods;
  result.samples_per_period = samples_per_period;
  Sampler sampler(flow, t0, periods, samples_per_period, all_samples, result);
  const FlowStop stop = flow.advance(t0 + periods * flow.model().period(), &sampler);
  long switches = 0;
  for (const Event& e : result.events)
    if (e.kind != EventKind::contact_lost) ++switches;
  result.diagnostics.switches_per_period = static_cast<double>(switches) / periods;
  return stop;
}

}  // namespace oscidrum::detail
