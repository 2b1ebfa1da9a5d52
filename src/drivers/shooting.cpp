// Periodic steady states by shooting (src/drivers/shooting.hpp, docs/periodic.md).
#include "drivers/shooting.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "flow/monodromy.hpp"

namespace oscidrum::detail {
namespace {

using Vec = std::array<double, 8>;
using Mat7 = Eigen::Matrix<double, 7, 7>;
using Vec7 = Eigen::Matrix<double, 7, 1>;

// The components of the fixed-point problem: all but phi (index 3), which is cyclic.
constexpr std::array<int, 7> kPeriodic = {0, 1, 2, 4, 5, 6, 7};

// Short transient: at least kMinTransient periods, until the switching sequence of a period
// repeats in the next one; at most kMaxTransient.
constexpr int kMinTransient = 2;
constexpr int kMaxTransient = 24;
// Transient periods integrated as period maps with sensitivities, at most (see short_transient).
constexpr int kMaxTransientMaps = 2;

// Newton: at most kMaxNewton steps; each halves its step up to kMaxHalvings times until the
// scaled residual decreases; more than kMaxSequenceChanges changes of the switching sequence
// between accepted iterates mean the linearisation does not hold (fall back).
constexpr int kMaxNewton = 12;
constexpr int kMaxHalvings = 4;
constexpr int kMaxSequenceChanges = 3;

// Converged when the scaled residual is below kNewtonTol times the steady-state tolerance (the
// orbit is then closer to periodic than any state the transient accepts), or below the
// steady-state tolerance and no longer decreasing by half (the integration's noise floor).
constexpr double kNewtonTol = 1e-2;

// Below this scaled residual, Newton steps reuse the last monodromy matrix (chord steps).
constexpr double kFreshMonodromy = 1e-3;

// The last step is taken without evaluating the period map at its result when the previous full
// step contracted the residual by at least kPredictContraction and the same contraction predicts
// a residual below kPredictMargin times the convergence threshold: the plain integration of the
// sampled periods that follows confirms it (or the run falls back).
constexpr double kPredictContraction = 1e-2;
constexpr double kPredictMargin = 0.1;

// Runge-Kutta substeps of the variational equations: at most T / kSubstepsPerPeriod.
constexpr double kSubstepsPerPeriod = 64.0;

std::string fmt(const char* format, double a = 0.0, double b = 0.0, double c = 0.0) {
  char buf[512];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

// Records the switches and the range of each component over a plain period.
class PlainObserver : public FlowObserver {
 public:
  bool on_step(const StepView& step) override {
    if (step.ends_step()) include(step.state(step.t1()).to_array());
    return true;
  }
  bool on_event(const Event& event, const State&, const State&) override {
    if (event.kind != EventKind::contact_lost) switches.push_back(event);
    recent.push_back(event);
    if (recent.size() > 64) recent.erase(recent.begin());
    return true;
  }
  void start(const Vec& x) {
    lo = hi = x;
    switches.clear();
  }
  void include(const Vec& x) {
    for (int i = 0; i < 8; ++i) {
      lo[i] = std::min(lo[i], x[i]);
      hi[i] = std::max(hi[i], x[i]);
    }
  }
  Vec lo{}, hi{};
  std::vector<Event> switches, recent;
};

struct PeriodMap {
  FlowStop stop = FlowStop::reached;
  State end;
  Phase phase = Phase::stick;
  Mat7 M = Mat7::Zero();
  std::vector<Event> switches;
  bool grazing = false;
  bool has_monodromy = false;  // M was computed at this state (else: carried over)
  double residual = std::numeric_limits<double>::infinity();  // scaled |P(z) - z|
};

class Shooter {
 public:
  Shooter(Flow& flow, const ProgressCallback& progress)
      : flow_(flow),
        model_(flow.model()),
        num_(flow.model().parameters().numerics),
        period_(flow.model().period()),
        progress_(progress),
        mono_(flow.model(), flow.options().baumgarte, flow.model().period() / kSubstepsPerPeriod) {}

  ShootingOutcome run(const ShootingStart& start);

 private:
  bool short_transient(ShootingOutcome& out);
  PeriodMap period_map(const State& z, Phase phase, bool sensitivities);
  State consistent(State z, Phase phase) const;

  Flow& flow_;
  const Model& model_;
  const Numerics& num_;
  const double period_;
  const ProgressCallback& progress_;
  MonodromyObserver mono_;
  // The last period of the short transient, integrated as the period map of its start.
  bool have_first_ = false;
  PeriodMap first_;
  State first_z_;
  Phase first_phase_ = Phase::stick;
  double t0_ = 0.0;
  std::array<double, 8> scale_{};
  int maps_ = 0, plain_maps_ = 0;
};

State Shooter::consistent(State z, Phase phase) const {
  // In stick phi' = f5 delta' (12); a Newton update must not break it.
  if (phase == Phase::stick) z.dphi = kinematics(model_.geometry(), z.delta).f5 * z.ddelta;
  return z;
}

bool Shooter::short_transient(ShootingOutcome& out) {
  PlainObserver obs;
  std::vector<Event> previous;
  bool have_previous = false;
  int map_periods = 0;
  for (int n = 1; n <= kMaxTransient; ++n) {
    // A period that may be the last one (the third, or the second after a period without
    // switches, as in pure rolling) is integrated as the period map of its consistent start,
    // with sensitivities: if its switching sequence repeats, it is Newton's first map.
    // Only up to kMaxTransientMaps such periods: a transient that takes longer to settle goes on
    // plainly, and Newton's first map follows it.
    const bool as_map = map_periods < kMaxTransientMaps &&
                        (n >= kMinTransient + 1 || (n >= kMinTransient && previous.empty()));
    if (as_map) ++map_periods;
    FlowStop stop;
    std::vector<Event> switches;
    if (as_map) {
      t0_ = flow_.t();
      const Phase phase = flow_.phase();
      const State z = consistent(flow_.state(), phase);
      first_ = period_map(z, phase, true);
      first_z_ = z;
      first_phase_ = phase;
      stop = first_.stop;
      switches = first_.switches;
    } else {
      obs.start(flow_.state().to_array());
      stop = flow_.advance(n * period_, &obs);
      switches = obs.switches;
    }
    if (stop != FlowStop::reached) {
      out.terminal = true;
      out.recent_events = as_map ? first_.switches : obs.recent;
      switch (stop) {
        case FlowStop::contact_lost:
          out.status = Status::contact_lost;
          break;
        case FlowStop::chattering:
          out.status = Status::chattering;
          break;
        case FlowStop::non_finite:
          out.status = Status::non_finite;
          break;
        case FlowStop::invalid_geometry:
          out.status = Status::invalid_geometry;
          break;
        case FlowStop::budget_exceeded:
          out.status = Status::budget_exceeded;
          break;
        default:
          out.status = Status::cancelled;
      }
      out.message = flow_.message();
      return false;
    }
    out.transient_periods = n - map_periods;  // the maps are counted as such
    // The scale of each component: its range over the period, floored at what the integration
    // tolerances resolve (as in the transient search). A period integrated as a map keeps the
    // scale of the period before.
    if (!as_map) {
      for (int i = 0; i < 8; ++i) {
        const double range = obs.hi[i] - obs.lo[i];
        const double floor =
            100.0 * (num_.atol + num_.rtol * std::max(std::abs(obs.hi[i]), std::abs(obs.lo[i])));
        scale_[i] = std::max(range, floor);
      }
    }
    if (progress_ && !progress_(n, std::numeric_limits<double>::infinity())) {
      out.terminal = true;
      out.status = Status::cancelled;
      out.message = fmt("cancelled after %.0f periods", n);
      return false;
    }
    const bool same = have_previous && same_switching_sequence(previous, switches);
    if (n >= kMinTransient && same) {
      have_first_ = as_map;
      break;
    }
    previous = switches;
    have_previous = true;
  }
  return true;
}

PeriodMap Shooter::period_map(const State& z, Phase phase, bool sensitivities) {
  PeriodMap p;
  flow_.reset(t0_, z, phase);
  if (sensitivities) {
    ++maps_;
    mono_.reset();
    p.stop = flow_.advance(t0_ + period_, &mono_);
    p.switches = mono_.switches();
    p.grazing = mono_.grazing();
  } else {
    ++plain_maps_;
    PlainObserver obs;
    p.stop = flow_.advance(t0_ + period_, &obs);
    p.switches = obs.switches;
  }
  if (p.stop != FlowStop::reached) return p;
  p.end = flow_.state();
  p.phase = flow_.phase();
  p.residual =
      p.phase == phase ? scaled_change(p.end, z, scale_) : std::numeric_limits<double>::infinity();
  if (!sensitivities) return p;
  // The map Newton sees is P(consistent(z)): at a stick section phi' is set to f5 delta' (12)
  // before the period starts (the flow's stick phase integrates phi' without ever reading it, so
  // without the projection its offset would be a neutral direction, a multiplier 1).
  const Mat8 phi =
      phase == Phase::stick ? Mat8(mono_.phi() * jump_jacobian(model_, z, true, 0)) : mono_.phi();
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) p.M(i, j) = phi(kPeriodic[i], kPeriodic[j]);
  p.has_monodromy = true;
  return p;
}

ShootingOutcome Shooter::run(const ShootingStart& start) {
  ShootingOutcome out;
  State z;
  Phase phase;
  if (start.from_state) {
    z = start.state;
    phase = start.phase;
    t0_ = flow_.t();
    // Scales from one plain period from the supplied state.
    PlainObserver obs;
    flow_.reset(t0_, z, phase);
    obs.start(z.to_array());
    if (flow_.advance(t0_ + period_, &obs) != FlowStop::reached) {
      out.message = "the supplied start state does not survive one period: " + flow_.message();
      return out;
    }
    for (int i = 0; i < 8; ++i) {
      const double range = obs.hi[i] - obs.lo[i];
      const double floor =
          100.0 * (num_.atol + num_.rtol * std::max(std::abs(obs.hi[i]), std::abs(obs.lo[i])));
      scale_[i] = std::max(range, floor);
    }
    out.transient_periods = 1;
  } else {
    if (!short_transient(out)) return out;
    if (have_first_) {  // t0_ is its start
      z = first_z_;
      phase = first_phase_;
    } else {
      t0_ = flow_.t();
      z = flow_.state();
      phase = flow_.phase();
    }
  }
  z = consistent(z, phase);

  PeriodMap cur = have_first_ ? std::move(first_) : period_map(z, phase, true);
  int sequence_changes = 0;
  bool converged = false;
  // Contraction of the residual by the last accepted full step (1: none yet).
  double contraction = 1.0;
  for (int k = 0; k <= kMaxNewton; ++k) {
    if (cur.stop != FlowStop::reached || cur.grazing || !std::isfinite(cur.residual)) {
      out.message = cur.stop != FlowStop::reached
                        ? "the period map failed at a Newton iterate: " + flow_.message()
                        : (cur.grazing ? "a switch grazes the switching surface"
                                       : "the phase at the section changed over a period");
      break;
    }
    if (cur.residual < kNewtonTol * num_.steady_tol) {
      converged = true;
      break;
    }
    if (k == kMaxNewton) {
      out.message =
          fmt("Newton did not converge in %.0f steps (scaled residual %.3g)", k, cur.residual);
      break;
    }
    if (progress_ && !progress_(out.transient_periods + k + 1, cur.residual)) {
      out.terminal = true;
      out.status = Status::cancelled;
      out.message = "cancelled during the Newton iteration";
      return out;
    }
    // (M - I) dz = -(P(z) - z) on the reduced state, in scaled units.
    Vec7 F, s;
    for (int i = 0; i < 7; ++i) {
      const int c = kPeriodic[i];
      s[i] = scale_[c];
      F[i] = (cur.end.to_array()[c] - z.to_array()[c]) / s[i];
    }
    const Mat7 A = s.asDiagonal().inverse() * (cur.M - Mat7::Identity()) * s.asDiagonal();
    // A multiplier at 1 (a neutral direction: phi' of the frictionless drum, whose mean any
    // constant shifts) makes the matrix singular; the minimum-norm step leaves that direction
    // where the transient put it.
    const Eigen::CompleteOrthogonalDecomposition<Mat7> cod(A);
    const Vec7 dz = cod.solve(-F);
    if (!dz.allFinite()) {
      out.message = "Newton's matrix M - I is singular";
      break;
    }
    if (contraction < kPredictContraction &&
        contraction * cur.residual < kPredictMargin * kNewtonTol * num_.steady_tol) {
      Vec y = z.to_array();
      for (int i = 0; i < 7; ++i) y[kPeriodic[i]] += dz[i] * s[i];
      z = consistent(State::from_array(y), phase);
      ++out.newton_iterations;
      out.predicted_last_step = true;
      converged = true;
      break;
    }
    bool accepted = false;
    double lambda = 1.0;
    for (int h = 0; h <= kMaxHalvings; ++h, lambda *= 0.5) {
      Vec y = z.to_array();
      for (int i = 0; i < 7; ++i) y[kPeriodic[i]] += lambda * dz[i] * s[i];
      const State trial = consistent(State::from_array(y), phase);
      // Close to the orbit (residual below kFreshMonodromy) the step is small and the monodromy
      // hardly changes: the trial is integrated without sensitivities and keeps the current M.
      PeriodMap next = period_map(trial, phase, cur.residual > kFreshMonodromy);
      if (next.stop != FlowStop::reached || !std::isfinite(next.residual)) continue;
      if (!next.has_monodromy) next.M = cur.M;
      // Accept a decrease; near the noise floor (below the steady tolerance) a full step that
      // does not halve the residual ends the iteration as converged.
      if (next.residual < (1.0 - 0.1 * lambda) * cur.residual) {
        if (!same_switching_sequence(next.switches, cur.switches)) ++sequence_changes;
        const bool stalled =
            lambda == 1.0 && cur.residual < num_.steady_tol && next.residual > 0.5 * cur.residual;
        contraction = lambda == 1.0 ? next.residual / cur.residual : 1.0;
        z = trial;
        cur = std::move(next);
        accepted = true;
        ++out.newton_iterations;
        if (stalled) converged = true;
        break;
      }
      if (cur.residual < num_.steady_tol) break;  // already steady: halving will not help
    }
    if (converged) break;
    if (!accepted) {
      if (cur.residual < num_.steady_tol) {
        converged = true;  // at the integration's noise floor
        break;
      }
      out.message = fmt("Newton's step did not reduce the residual (scaled %.3g)", cur.residual);
      break;
    }
    if (sequence_changes > kMaxSequenceChanges) {
      out.message = "the switching sequence changed between Newton iterates";
      break;
    }
  }
  out.period_maps = maps_;
  out.plain_maps = plain_maps_;
  out.jacobian_evaluations = mono_.jacobian_evaluations();
  out.final_change = cur.residual;
  if (!converged) {
    if (out.message.empty()) out.message = "Newton failed";
    return out;
  }

  // Floquet multipliers: eigenvalues of the monodromy at the orbit.
  const Eigen::EigenSolver<Mat7> eig(cur.M, false);
  std::vector<std::complex<double>> mult(7);
  for (int i = 0; i < 7; ++i) mult[i] = eig.eigenvalues()[i];
  out.floquet = classify_multipliers(std::move(mult));
  if (out.floquet.stability != Stability::stable) {
    out.message = fmt("the period-1 orbit is unstable (largest Floquet multiplier modulus %.6g, ",
                      out.floquet.max_modulus) +
                  to_string(out.floquet.stability) + "): the transient is followed instead";
    return out;
  }
  out.converged = true;
  out.t0 = t0_;
  out.scale = scale_;
  out.orbit = z;
  out.phase = phase;
  out.phi_drift = cur.end.phi - z.phi;
  out.message = fmt("periodic orbit by shooting after %.0f transient periods and %.0f Newton steps",
                    out.transient_periods, out.newton_iterations);
  flow_.reset(t0_, z, phase);
  return out;
}

}  // namespace

double scaled_change(const State& a, const State& b, const std::array<double, 8>& scale) {
  const Vec x = a.to_array(), y = b.to_array();
  double change = 0.0;
  for (int i : kPeriodic) change = std::max(change, std::abs(x[i] - y[i]) / scale[i]);
  return change;
}

ShootingOutcome shoot_periodic_orbit(Flow& flow, const ProgressCallback& progress,
                                     const ShootingStart& start) {
  Shooter shooter(flow, progress);
  return shooter.run(start);
}

}  // namespace oscidrum::detail
