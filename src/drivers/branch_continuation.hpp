// Internal: the continuation of branches of periodic orbits (oscidrum/branch.hpp,
// docs/bifurcations.md), written once against a roller type R (src/roller/dynamics.hpp):
// pseudo-arclength continuation of the shooting problem P^p(z; q) - z = 0 in a parameter q, with
// the bifurcations on the branch. continue_branch (src/drivers/branch.cpp) runs it on the rollers
// of the registry; the tests also run it on textbook oscillators with known bifurcations
// (tests/drivers/soft_impact_oscillator.hpp).
//
// Unknowns: the periodic components y of the roller's state at the section t0 (the drum: delta,
// x_A, s_A and their rates, phi'; not phi, which is cyclic) and q, scaled by the components'
// ranges over a period and by |to - from|. The residual F(y, q) = P^p(y; q) - y is the shooting
// residual; dF/dy = M - I with M the monodromy matrix of the period map (the variational
// equations with the saltation matrices of every switch, src/flow/monodromy.hpp), dF/dq a forward
// difference of two period maps. Predictor: the tangent, the null vector of [dF/dy, dF/dq]
// oriented as the previous one; corrector: Newton on F = 0 and the tangent's hyperplane through
// the prediction (Keller's pseudo-arclength condition). Step control halves a step whose
// corrector fails and grows one that converges quickly.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/sampling.hpp"
#include "drivers/varied_parameter.hpp"
#include "flow/monodromy.hpp"
#include "oscidrum/branch.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/friction.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/simulate.hpp"
#include "util/format.hpp"

namespace oscidrum::detail::branching {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The counts that change at a bifurcation of the smooth kinds: real multipliers beyond +1 and
/// beyond -1, complex pairs outside the unit circle.
struct MultiplierCounts {
  int beyond_plus_one = 0, beyond_minus_one = 0, complex_outside = 0;
  bool operator==(const MultiplierCounts&) const = default;
};

// A pair with an imaginary part above 1e-8 of its modulus counts as complex (as
// classify_multipliers does).
inline bool is_complex(std::complex<double> m) { return std::abs(m.imag()) > 1e-8 * std::abs(m); }

// A multiplier within 1e-6 of the unit circle counts as on it (neutral), as classify_multipliers
// has it: the integration's tolerances leave ~1e-8 on a multiplier that is 1 by the physics.
inline constexpr double kNeutral = 1e-6;

// A point of a period-p branch (p even) whose P^(p/2) residual, in the corrector's scaled units, is
// below this is an orbit of half its period: the genuine period-p orbits near their period
// doubling differ from their P^(p/2) image by about the square root of the parameter's distance
// from it, far above this; the orbits of half the period repeat to the corrector's tolerance.
inline constexpr double kHalfOrbit = 1e-6;

// `neutral`: the band around the unit circle that counts as on it (kNeutral for the detection;
// 0 where a change already detected is located: the band's edge is not the crossing).
inline MultiplierCounts count_multipliers(const Floquet& f, double neutral = kNeutral) {
  MultiplierCounts c;
  for (const std::complex<double> m : f.multipliers) {
    if (std::abs(m) <= 1.0 + neutral) continue;
    if (is_complex(m))
      c.complex_outside += m.imag() > 0 ? 1 : 0;
    else if (m.real() > 0)
      ++c.beyond_plus_one;
    else
      ++c.beyond_minus_one;
  }
  return c;
}

/// Which multipliers crossed the unit circle between two solutions of counts a and b: real ones
/// at +1, at -1, a complex pair. A complex pair outside the circle that meets the real axis and
/// parts into two reals there (or two reals beyond +1 or -1 that join into a pair: a collision)
/// moves two multipliers between the counts and none across the circle: counted by kind, it was
/// reported as a branch point and a Neimark-Sacker point at once, with "critical" multipliers of
/// modulus 0.02, where every multiplier stayed outside (pure rolling with lift-off near 68.44 Hz,
/// the pair 2.03 +- 1.23i parting into 3.82 and 2.24). The changes of the counts are explained
/// by crossings and collisions, dp = c+ + 2 k+, dm = c- + 2 k-, dc = c_pair - k+ - k- (k: pairs
/// parted into reals beyond +1 or -1, negative where reals joined), with the fewest crossings
/// (then the fewest collisions): a crossing is a bifurcation, a collision is not, and between two
/// points of a branch one crossing is what happens generically. A single real crossing changes its
/// side's count by one, so an odd change is always a crossing there.
struct Crossings {
  bool plus_one = false, minus_one = false, complex_pair = false;
};
inline Crossings crossings(const MultiplierCounts& a, const MultiplierCounts& b) {
  const int dp = b.beyond_plus_one - a.beyond_plus_one;
  const int dm = b.beyond_minus_one - a.beyond_minus_one;
  const int dc = b.complex_outside - a.complex_outside;
  Crossings best;
  int fewest = std::numeric_limits<int>::max(), fewest_collisions = 0;
  // A collision moves a pair for two reals: never more collisions than multipliers (P <= 16).
  constexpr int kMost = 8;
  for (int kp = -kMost; kp <= kMost; ++kp) {
    for (int km = -kMost; km <= kMost; ++km) {
      const int cp = dp - 2 * kp, cm = dm - 2 * km, cc = dc + kp + km;
      const int crossed = std::abs(cp) + std::abs(cm) + std::abs(cc);
      const int collisions = std::abs(kp) + std::abs(km);
      if (crossed < fewest || (crossed == fewest && collisions < fewest_collisions)) {
        fewest = crossed, fewest_collisions = collisions;
        best = Crossings{cp != 0, cm != 0, cc != 0};
      }
    }
  }
  return best;
}

inline std::complex<double> nearest(const Floquet& f, std::complex<double> target,
                                    bool complex_only) {
  std::complex<double> best = 0.0;
  double distance = std::numeric_limits<double>::infinity();
  for (const std::complex<double> m : f.multipliers) {
    if (complex_only && (!is_complex(m) || m.imag() < 0)) continue;
    const double d = complex_only ? std::abs(std::abs(m) - 1.0) : std::abs(m - target);
    if (d < distance) distance = d, best = m;
  }
  return best;
}

template <class R>
class Continuation {
 public:
  using Dyn = detail::Dynamics<R>;
  using Vector = typename Dyn::Vector;
  static constexpr int P = static_cast<int>(Dyn::kPeriodic.size());

  Continuation(const Case& c, const BranchOptions& o, const Field& field)
      : base_(c), o_(o), field_(field), sq_(std::abs(o.to - o.from)) {}

  // The first orbit of a branch: where its section lies, the state there and the scales of the
  // unknowns.
  struct Start {
    double section = 0.0;           // the section t0, in excitation periods since the start [-]
    Vector reference{};             // the state at the section (on the orbit, or near it)
    Phase phase = Phase::stick;     // the phase at the section
    int multiplicity = 1;           // p: the orbit repeats every p excitation periods
    std::array<double, P> scale{};  // of each periodic component (its range over the orbit)
  };

  // The branch from the steady state simulate() finds at `from` (a roller of the registry,
  // src/roller/rollers.hpp).
  Branch run();
  // The branch from `start` (corrected at `from` first): for a roller type without simulate(),
  // e.g. the textbook oscillators of the tests.
  Branch run_from(const Start& start);

  // A period doubling passed on the branch: where, the orbit there and the direction of the
  // multiplier -1, and the side of it on which the period-p orbit is unstable.
  struct Doubling {
    double q = 0.0, section = 0.0;
    Phase phase = Phase::stick;
    Vector state{};
    VectorXd direction;  // eigenvector of M for the multiplier nearest -1 (scaled components)
    double unstable_side = 1.0;  // +1: beyond q in increasing q
    int index = -1;              // of the bifurcation in the parent's list
  };
  const std::vector<Doubling>& doublings() const { return doublings_; }
  // Where a period-p branch (p even) turned back at its orbit's collapse onto a period-p/2 orbit:
  // the period doubling of that orbit, met from the period-p side. The orbit there is (within
  // the location's tolerance) the period-p/2 orbit.
  struct Halving {
    double q = 0.0, section = 0.0;
    Phase phase = Phase::stick;
    Vector state{};
    int index = -1;  // of the bifurcation in the parent's list
  };
  const std::optional<Halving>& halving() const { return halving_; }
  // The period-p/2 branch from the collapse `h`, followed towards the end of the range the
  // parent was heading for.
  Branch halve_at(const Halving& h, const std::array<double, P>& scale);
  // The period-2p branch born at `d`, followed to the end of the range on its side.
  Branch switch_at(const Doubling& d, const std::array<double, P>& scale);
  const std::array<double, P>& scale() const { return scale_; }
  void set_multiplicity(int p) { p_ = p; }

 private:
  // One period map P^p from (y, q): the residual F = P^p(y) - y (scaled), and with
  // `sensitivities` the scaled Jacobian dF/dy (M - I); `ok` false when the flow failed, the phase
  // at the section changed or a switch grazed (the message says which).
  struct Map {
    bool ok = false;
    std::string why;
    VectorXd F;
    MatrixXd A;  // scaled dF/dy
    MatrixXd M;  // unscaled monodromy on the periodic components
    std::string sequence;
    std::vector<Event> switches;  // of the period map, in time order
    double min_N = 0.0;
    bool grazing = false;
  };
  // A point of the corrector: the scaled unknowns v = (y / s, q / sq), its map and tangent.
  struct Solution {
    VectorXd v;
    Map map;
    VectorXd tangent;
  };

  Case case_at(double q) const {
    Case c = base_;
    set_varied(c, field_, q, o_.MMd_fraction);
    return c;
  }
  Vector full_state(const VectorXd& v) const {
    Vector x = reference_;
    for (int i = 0; i < P; ++i) x[Dyn::kPeriodic[i]] = v[i] * scale_[i];
    return x;
  }
  double parameter(const VectorXd& v) const { return v[P] * sq_; }
  // "key = value unit" for the messages (SI: the unit of the field table), with the value in the
  // unit people read it in where that is another ("soil.G = 1.4e+08 Pa (140 MN/m^2)": the CLI's
  // table and bifurcations say MN/m^2, and the end of the branch said Pa alone).
  std::string at_value(double q, const char* format = nullptr) const {
    return std::string(field_.key) + " = " +
           (format ? detail::format(format, q) : detail::shortest(q)) +
           (field_.unit[0] != '\0' && std::string_view(field_.unit) != "-"
                ? " " + std::string(field_.unit)
                : std::string()) +
           (field_.display_unit ? " (" + detail::shortest(q / field_.display_scale) + " " +
                                      field_.display_unit + ")"
                                : std::string());
  }
  Map map(const VectorXd& v, bool sensitivities);
  std::optional<VectorXd> dF_dq(const VectorXd& v, const Map& at);
  std::optional<VectorXd> tangent(const VectorXd& v, const Map& at, const VectorXd& previous);
  // `reach`: the step that made the prediction (the corrector must stay within a fraction of it).
  std::optional<Solution> correct(const VectorXd& predicted, const VectorXd& direction,
                                  int* iterations, double reach);
  static constexpr double kMaxDrift = 0.5;
  BranchPoint point(const Solution& s, double arclength, int iterations);
  void locate(Branch& branch, const Solution& a, const Solution& b, double ds,
              const BranchPoint& pa, const BranchPoint& pb);
  bool resection(Solution& s);
  // Is the orbit of `s` (on a period-p branch, p even) the period-p/2 orbit, which the branch
  // through `before` has shrunk onto? Its P^(p/2) residual is small, and small against before's;
  // or, at a turn that no multiplier crossed +1 through (`symmetric`: the same number beyond +1
  // on both sides, where a saddle-node's stability changes), smaller than before's.
  bool collapses(const Solution& s, const Solution& before, bool symmetric);
  // The scaled residual of P^(p/2) at s (infinity where the map fails).
  double half_residual(const Solution& s);
  static bool has_flight(const std::string& sequence) {
    return sequence.find(to_string(Phase::flight)) != std::string::npos;
  }
  // The corrector failed down to the smallest step beyond `cur` (the prediction reached q_fail):
  // when the contact is unilateral and the orbit's smallest normal force is what ends it, locate
  // the point where it reaches zero and end the branch there as lift_off.
  std::optional<Branch> end_at_lift_off(Branch& branch, const Solution& cur, double q_fail,
                                        std::chrono::steady_clock::time_point start_time);
  bool cancelled() const { return o_.cancelled && o_.cancelled(); }
  std::string contact_ends(const Branch& branch, double q_fail) const;

  Case base_;
  BranchOptions o_;
  const Field& field_;
  double sq_;
  int p_ = 1;
  // The section, in excitation periods since the start (t0 = section_ / f): a fixed phase of the
  // excitation M0 sin(nu t) whatever the parameter does to f.
  double section_ = 0.0;
  Phase phase_ = Phase::stick;
  Vector reference_{};
  std::array<double, P> scale_{};
  long maps_ = 0;
  std::string last_failure_;
  std::vector<Doubling> doublings_;
  std::optional<Halving> halving_;
  // What o_.from is where it is not the user's start (a child branch's): for the messages.
  std::string from_what_;
  // The continuation from an accepted first solution to the end of the range.
  Branch follow(Branch branch, Solution cur, int iterations,
                std::chrono::steady_clock::time_point start_time);
  Branch finish(Branch& branch, BranchEnd end, std::string message,
                std::chrono::steady_clock::time_point start_time) const;
  // The branch from the first orbit `start`: corrected at `from`, then followed.
  Branch begin(Branch branch, const Start& start, std::chrono::steady_clock::time_point start_time);
};

template <class R>
typename Continuation<R>::Map Continuation<R>::map(const VectorXd& v, bool sensitivities) {
  Map out;
  std::optional<Model> model;
  try {
    model.emplace(case_at(parameter(v)));
  } catch (const Error& e) {
    out.why = e.what();
    return out;
  }
  FlowOptions fo = FlowOptions::from(*model);
  fo.cancelled = o_.cancelled;
  BasicFlow<R> flow(*model, fo);
  const Dyn dyn(*model, fo.baumgarte);
  const Vector z = dyn.consistent(full_state(v), phase_);
  const double t0 = section_ * model->period();
  flow.reset(t0, R::State::from_array(z), phase_);
  const double t_end = t0 + p_ * model->period();
  ++maps_;
  FlowStop stop;
  std::vector<Event> switches;
  detail::MonodromyObserver<R> mono(*model, fo.baumgarte,
                                    model->period() / detail::kMonodromyStepsPerPeriod);
  if (sensitivities) {
    mono.reset();
    stop = flow.advance(t_end, &mono);
    switches = mono.switches();
    out.grazing = mono.grazing();
  } else {
    struct Switches : BasicFlowObserver<R> {
      std::vector<Event> events;
      bool on_event(const Event& e, const typename R::State&, const typename R::State&) override {
        events.push_back(e);
        return true;
      }
    } obs;
    stop = flow.advance(t_end, &obs);
    switches = obs.events;
  }
  if (stop != FlowStop::reached) {
    out.why = std::string("the period map stopped: ") + flow.message();
    return out;
  }
  if (flow.phase() != phase_) {
    out.why = std::string("the phase at the section changed over a period (") + to_string(phase_) +
              " -> " + to_string(flow.phase()) + ")";
    return out;
  }
  // The phases of one period as a cycle (the section's phase, then after each switch; the last
  // is the section's again), written from its smallest rotation: the same orbit gives the same
  // text wherever the section lies.
  std::vector<std::string> cycle = {to_string(phase_)};
  for (const Event& e : switches) cycle.push_back(to_string(e.to));
  if (cycle.size() > 1) cycle.pop_back();
  std::vector<std::string> best = cycle;
  for (std::size_t k = 1; k < cycle.size(); ++k) {
    std::rotate(cycle.begin(), cycle.begin() + 1, cycle.end());
    best = std::min(best, cycle);
  }
  for (const std::string& name : best) out.sequence += (out.sequence.empty() ? "" : ">") + name;
  out.switches = std::move(switches);
  out.min_N = flow.counters().min_N;
  const Vector end = flow.state().to_array();
  out.F.resize(P);
  for (int i = 0; i < P; ++i) {
    const int c = Dyn::kPeriodic[i];
    out.F[i] = (end[c] - z[c]) / scale_[i];
  }
  if (sensitivities) {
    const auto G = dyn.section_jacobian(full_state(v), phase_);
    const typename Dyn::Matrix phi = G ? typename Dyn::Matrix(mono.phi() * *G) : mono.phi();
    out.M.resize(P, P);
    out.A.resize(P, P);
    for (int i = 0; i < P; ++i)
      for (int j = 0; j < P; ++j) {
        out.M(i, j) = phi(Dyn::kPeriodic[i], Dyn::kPeriodic[j]);
        out.A(i, j) = out.M(i, j) * scale_[j] / scale_[i] - (i == j ? 1.0 : 0.0);
      }
  }
  out.ok = true;
  return out;
}

// dF/dq by a forward difference in the scaled parameter (the step 1e-6 of the range: the period
// maps are accurate to ~1e-9 of the scales, so the derivative to ~1e-3, ample for a predictor and
// for the corrector's convergence, which only the residual decides). When the map beside the
// orbit has another cycle of phases (a switching boundary lies between q and q + h: a phase
// appears there, e.g. lift-off as the smallest normal force reaches zero), the forward difference
// measures the jump to the other side, not the derivative: a backward difference is taken instead
// if it stays on the orbit's side.
template <class R>
std::optional<VectorXd> Continuation<R>::dF_dq(const VectorXd& v, const Map& at) {
  constexpr double h = 1e-6;
  VectorXd w = v;
  w[P] += h;
  const Map m = map(w, false);
  if (!m.ok) return std::nullopt;
  if (m.sequence != at.sequence) {
    w[P] = v[P] - h;
    const Map b = map(w, false);
    if (b.ok && b.sequence == at.sequence) return VectorXd((at.F - b.F) / h);
  }
  return VectorXd((m.F - at.F) / h);
}

// The unit null vector of [A, dF/dq], oriented along `previous` (the bordered system
// [A dF/dq; previous^T] t = [0; 1]).
template <class R>
std::optional<VectorXd> Continuation<R>::tangent(const VectorXd& v, const Map& at,
                                                 const VectorXd& previous) {
  const std::optional<VectorXd> fq = dF_dq(v, at);
  if (!fq) return std::nullopt;
  MatrixXd B(P + 1, P + 1);
  B.topLeftCorner(P, P) = at.A;
  B.topRightCorner(P, 1) = *fq;
  B.bottomRows(1) = previous.transpose();
  VectorXd rhs = VectorXd::Zero(P + 1);
  rhs[P] = 1.0;
  VectorXd t = B.fullPivLu().solve(rhs);
  if (!t.allFinite() || t.norm() == 0.0) return std::nullopt;
  return VectorXd(t / t.norm());
}

// Newton on F(v) = 0, direction . (v - predicted) = 0 from `predicted`.
template <class R>
std::optional<typename Continuation<R>::Solution> Continuation<R>::correct(
    const VectorXd& predicted, const VectorXd& direction, int* iterations, double reach) {
  const double tol = 1e-2 * base_.numerics.steady_tol;  // as shooting's Newton (kNewtonTol)
  VectorXd v = predicted;
  for (int k = 0; k < 10; ++k) {
    if (cancelled()) return std::nullopt;
    Map m = map(v, true);
    if (!m.ok) {
      last_failure_ = m.why;
      return std::nullopt;
    }
    if (m.grazing) {
      last_failure_ = "a switch grazes its switching surface";
      return std::nullopt;
    }
    if (m.F.cwiseAbs().maxCoeff() < tol) {
      // A corrector that wandered far from its prediction has found another branch (or another
      // part of this one): not the next point (the step is halved).
      if ((v - predicted).norm() > kMaxDrift * std::max(reach, 1e-3)) {
        last_failure_ = "the corrector left the neighbourhood of its prediction";
        return std::nullopt;
      }
      *iterations = k;
      return Solution{v, std::move(m), VectorXd()};
    }
    const std::optional<VectorXd> fq = dF_dq(v, m);
    if (!fq) {
      last_failure_ = "the period map failed beside an iterate";
      return std::nullopt;
    }
    MatrixXd B(P + 1, P + 1);
    B.topLeftCorner(P, P) = m.A;
    B.topRightCorner(P, 1) = *fq;
    B.bottomRows(1) = direction.transpose();
    VectorXd rhs(P + 1);
    rhs.head(P) = -m.F;
    rhs[P] = -direction.dot(v - predicted);
    const VectorXd dv = B.fullPivLu().solve(rhs);
    if (!dv.allFinite()) {
      last_failure_ = "the corrector's matrix is singular";
      return std::nullopt;
    }
    v += dv;
  }
  last_failure_ = "the corrector did not converge in 10 steps";
  return std::nullopt;
}

template <class R>
BranchPoint Continuation<R>::point(const Solution& s, double arclength, int iterations) {
  BranchPoint pt;
  pt.parameter = parameter(s.v);
  pt.arclength = arclength;
  pt.multiplicity = p_;
  pt.phase = phase_;
  const Vector x = full_state(s.v);
  pt.state.assign(x.begin(), x.end());
  pt.section_time = section_ * Model(case_at(pt.parameter)).period();
  Eigen::EigenSolver<MatrixXd> eig(s.map.M, false);
  std::vector<std::complex<double>> mu(eig.eigenvalues().begin(), eig.eigenvalues().end());
  pt.floquet = classify_multipliers(std::move(mu));
  for (const std::complex<double> m : pt.floquet.multipliers)
    pt.unstable += std::abs(m) > 1.0 + kNeutral;
  pt.dq_ds = s.tangent.size() == P + 1 ? s.tangent[P] : 0.0;
  pt.min_N = s.map.min_N;
  pt.sequence = s.map.sequence;
  pt.corrector_iterations = iterations;
  // Metrics need the roller's sample columns (Dynamics<R>::sample); a roller type without them
  // (a test's textbook oscillator) has none.
  if constexpr (requires(const Dyn& d, Samples& samples) {
                  d.sample(0.0, Vector{}, Phase::stick, samples);
                }) {
    if (o_.metrics) {
      // The orbit sampled from its section and measured as a steady state (compute_metrics).
      try {
        const Model model(case_at(pt.parameter));
        BasicFlow<R> flow(model);
        const Dyn dyn(model, flow.options().baumgarte);
        flow.reset(section_ * model.period(), R::State::from_array(dyn.consistent(x, phase_)),
                   phase_);
        Result r;
        r.frequency = model.parameters().roller.f;
        r.diagnostics.multiplicity = p_;
        if (detail::sample_periods(flow, p_, model.parameters().numerics.samples_per_period, r,
                                   false) == FlowStop::reached) {
          r.status = Status::steady_state;
          pt.metrics = compute_metrics(model, r, o_.harmonics);
        }
      } catch (const Error&) {
        pt.metrics = Metrics::unavailable();
      }
    }
  }
  return pt;
}

// Between accepted solutions a and the next (arclength ds apart along a's tangent) a test changed:
// bisect along the branch (corrector from a + s t_a on t_a's hyperplane) until the bracket in q
// is below the tolerance, and report each change.
template <class R>
void Continuation<R>::locate(Branch& branch, const Solution& a, const Solution& b, double ds,
                             const BranchPoint& pa, const BranchPoint& pb) {
  const MultiplierCounts ca = count_multipliers(pa.floquet), cb = count_multipliers(pb.floquet);
  const Crossings crossed = crossings(ca, cb);
  // A fold: the unit tangent's parameter component changes sign. One of round-off size (1e-19 at
  // the gross-slip limit, where the branch ends with the stick interval shrinking to nothing)
  // has no sign: its sign flipped with a last-bit change of the excitation's sine.
  constexpr double kNoSign = 1e-9;
  const bool fold =
      pa.dq_ds * pb.dq_ds < 0.0 && std::abs(pa.dq_ds) > kNoSign && std::abs(pb.dq_ds) > kNoSign;
  struct Test {
    BifurcationKind kind;
    bool changed;
  };
  const Test tests[] = {
      {BifurcationKind::fold, fold},
      {BifurcationKind::branch_point, !fold && crossed.plus_one},
      {BifurcationKind::period_doubling, crossed.minus_one},
      {BifurcationKind::neimark_sacker, crossed.complex_pair},
      {BifurcationKind::grazing, pa.sequence != pb.sequence},
  };
  const double q_tol = o_.tolerance * sq_;
  for (const Test& test : tests) {
    if (!test.changed) continue;
    const bool crossing = test.kind == BifurcationKind::branch_point ||
                          test.kind == BifurcationKind::period_doubling ||
                          test.kind == BifurcationKind::neimark_sacker;
    // The band that counts a multiplier as on the unit circle (kNeutral) detects a crossing; the
    // crossing itself is where the modulus passes 1, not the band's edge 1 + 1e-6 (the doubling
    // of docs/bifurcations.md's log-spiral study, where |mu| moves by 3.5e-4 per MN/m^2, was
    // reported 2.8 kPa from it with a tolerance of 65 Pa). It is located without the band where
    // the two ends are on different sides of the circle itself (else, a modulus within the band
    // at an end, with it).
    double neutral = kNeutral;
    // The side a test is on at a solution.
    auto side = [&](const Solution& s, const BranchPoint& p) -> long {
      switch (test.kind) {
        case BifurcationKind::fold:
          return p.dq_ds > 0 ? 1 : 0;
        case BifurcationKind::branch_point:
          return count_multipliers(p.floquet, neutral).beyond_plus_one;
        case BifurcationKind::period_doubling:
          return count_multipliers(p.floquet, neutral).beyond_minus_one;
        case BifurcationKind::neimark_sacker:
          return count_multipliers(p.floquet, neutral).complex_outside;
        case BifurcationKind::grazing:
        case BifurcationKind::lift_off:
          return static_cast<long>(std::hash<std::string>{}(s.map.sequence));
      }
      return 0;
    };
    if (crossing) {
      neutral = 0.0;
      if (side(a, pa) == side(b, pb)) neutral = kNeutral;
    }
    const long side_a = side(a, pa);
    double lo = 0.0, hi = ds;
    double q_lo = pa.parameter, q_hi = pb.parameter;
    BranchPoint last = pb;
    const Solution* last_solution = &b;
    std::optional<Solution> kept;
    // Why the bisection stopped short of the tolerance (empty: it did not).
    std::string short_of = "40 bisections";
    for (int k = 0; k < 40; ++k) {
      if (std::abs(q_hi - q_lo) <= q_tol) {
        short_of.clear();
        break;
      }
      const double mid = 0.5 * (lo + hi);
      int iterations = 0;
      std::optional<Solution> s = correct(a.v + mid * a.tangent, a.tangent, &iterations, mid);
      if (!s) {
        short_of = "the corrector failed inside the bracket";
        break;
      }
      if (test.kind == BifurcationKind::fold) {
        const std::optional<VectorXd> t = tangent(s->v, s->map, a.tangent);
        if (!t) {
          short_of = "no tangent inside the bracket";
          break;
        }
        s->tangent = *t;
      }
      BranchPoint pm = point(*s, 0.0, iterations);
      if (side(*s, pm) == side_a) {
        lo = mid, q_lo = pm.parameter;
      } else {
        hi = mid, q_hi = pm.parameter, last = pm;
        kept = std::move(*s);
        last_solution = &*kept;
      }
    }
    Bifurcation bif;
    bif.kind = test.kind;
    bif.after_point = static_cast<int>(branch.points.size()) - 1;
    bif.parameter = 0.5 * (q_lo + q_hi);
    bif.tolerance = 0.5 * std::abs(q_hi - q_lo);
    if (crossing) {
      // The crossing of the modulus 1 by the secant from the located point (the rate of the
      // critical multiplier's modulus from the two points around it): where the bisection ran
      // without the band this moves it within its bracket; where an end lay within the band
      // (small steps pass the circle itself between earlier points) it moves the band's edge to
      // the circle. A modulus is known to the band kNeutral only (the integration's tolerances),
      // so the crossing lies within the parameter change that moves it by that much, whatever
      // the bracket.
      const auto modulus = [&](const BranchPoint& p) {
        return std::abs(
            test.kind == BifurcationKind::period_doubling ? nearest(p.floquet, -1.0, false)
            : test.kind == BifurcationKind::branch_point  ? nearest(p.floquet, 1.0, false)
                                                          : nearest(p.floquet, 0.0, true));
      };
      const double slope = (modulus(pb) - modulus(pa)) / (pb.parameter - pa.parameter);
      if (slope != 0.0 && std::isfinite(slope)) {
        const double shift = (1.0 - modulus(last)) / slope, band = kNeutral / std::abs(slope);
        if (std::abs(shift) <= 2.0 * band) bif.parameter = last.parameter + shift;
        bif.tolerance = std::max(bif.tolerance, band);
      }
    }
    const std::string unit = std::string(" ") + field_.unit;
    switch (test.kind) {
      case BifurcationKind::fold:
        bif.multiplier = nearest(last.floquet, 1.0, false);
        bif.description = "the branch turns back in " + std::string(field_.key) +
                          " (saddle-node: a stable and an unstable orbit meet)";
        if (p_ % 2 == 0 && collapses(*last_solution, a,
                                     count_multipliers(pa.floquet, 0.0).beyond_plus_one ==
                                         count_multipliers(pb.floquet, 0.0).beyond_plus_one)) {
          // The period-p orbit has shrunk onto a period-p/2 orbit: P^p's multiplier +1 there is
          // -1 of P^(p/2), and beyond it the branch returns through its own orbits shifted by
          // p/2 periods (the turn of a pitchfork of P^p, not a saddle-node: the orbits on both
          // sides are the same).
          bif.kind = BifurcationKind::period_doubling;
          bif.description =
              "the period-" + std::to_string(p_) + " orbit shrinks onto a period-" +
              std::to_string(p_ / 2) + " orbit: its period doubling, met from the period-" +
              std::to_string(p_) +
              " side (the multiplier +1 of this branch's map is -1 of the period-" +
              std::to_string(p_ / 2) +
              " orbit's); beyond it this branch turns back through its own orbits, shifted by " +
              std::to_string(p_ / 2) + (p_ / 2 == 1 ? " period" : " periods");
          Halving h;
          h.q = last.parameter;
          h.section = section_;
          h.phase = phase_;
          h.state = full_state(last_solution->v);
          h.index = static_cast<int>(branch.bifurcations.size());
          halving_ = h;
        }
        break;
      case BifurcationKind::branch_point:
        bif.multiplier = nearest(last.floquet, 1.0, false);
        bif.description = "a real multiplier crosses +1 without a turn (branch point)";
        break;
      case BifurcationKind::period_doubling: {
        bif.multiplier = nearest(last.floquet, -1.0, false);
        // For the switch onto the period-2p branch: the orbit beyond the point and the direction
        // of its multiplier -1 (the eigenvector's real part, in scaled components).
        Eigen::EigenSolver<MatrixXd> eig(last_solution->map.M, true);
        int critical = 0;
        for (int i = 1; i < P; ++i)
          if (std::abs(eig.eigenvalues()[i] + 1.0) < std::abs(eig.eigenvalues()[critical] + 1.0))
            critical = i;
        VectorXd dir(P);
        for (int i = 0; i < P; ++i) dir[i] = eig.eigenvectors()(i, critical).real() / scale_[i];
        Doubling d;
        d.q = last.parameter;
        d.section = section_;
        d.phase = phase_;
        d.state = full_state(last_solution->v);
        d.direction = dir.normalized();
        d.unstable_side =
            (cb.beyond_minus_one > ca.beyond_minus_one) == (pb.parameter > pa.parameter) ? 1.0
                                                                                         : -1.0;
        d.index = static_cast<int>(branch.bifurcations.size());
        doublings_.push_back(d);
      }
        bif.description = "a real multiplier crosses -1: an orbit of period " +
                          std::to_string(2 * p_) + " T branches off (flip)";
        break;
      case BifurcationKind::neimark_sacker:
        bif.multiplier = nearest(last.floquet, 0.0, true);
        bif.description = "a complex pair crosses the unit circle (Neimark-Sacker: a torus)";
        break;
      case BifurcationKind::grazing:
        bif.description = "the switching sequence changes: " + pa.sequence + " -> " + pb.sequence;
        break;
      case BifurcationKind::lift_off:  // not a test between points (see end_at_lift_off)
        break;
    }
    if (!short_of.empty() && std::abs(q_hi - q_lo) > q_tol)
      bif.description += "; located within a bracket of " +
                         detail::format("%.3g", std::abs(q_hi - q_lo)) + unit + " only (" +
                         short_of + "), wider than the tolerance's " +
                         detail::format("%.3g", q_tol) + unit;
    branch.bifurcations.push_back(bif);
  }
}

// The section t0 must stay away from the orbit's switches: the unknowns are the state at t0 in
// the phase there, and a switch that moves through t0 changes that phase (the period map is then
// not the same map). When the nearest switch is closer to t0 than a quarter of t0's phase
// interval, the section moves to the middle of the orbit's longest phase interval: the state there
// (one integration from the old section) becomes the unknowns, the tangent is recomputed in them
// and oriented as before in the parameter. False: it could not be moved (then nothing changed).
template <class R>
bool Continuation<R>::resection(Solution& s) {
  const std::vector<Event>& e = s.map.switches;
  if (e.empty()) return true;  // no switch: any section is as good
  const Model model(case_at(parameter(s.v)));
  const double T = p_ * model.period(), t0 = section_ * model.period();
  // Phase intervals over one period from t0, the first and the last joined (the same phase).
  std::vector<double> starts = {t0}, ends;
  for (const Event& x : e) ends.push_back(x.t), starts.push_back(x.t);
  ends.push_back(t0 + T);
  const double first = (ends.front() - starts.front()) + (ends.back() - starts.back());
  const double near = std::min(ends.front() - t0, t0 + T - starts.back());
  if (near > 0.25 * first) return true;
  std::size_t best = 0;
  double longest = first;
  for (std::size_t i = 1; i + 1 < starts.size(); ++i)
    if (ends[i] - starts[i] > longest) longest = ends[i] - starts[i], best = i;
  // The middle of the longest interval (of the joined first/last one: its middle, wrapped).
  double t_new;
  if (best == 0) {
    t_new = starts.back() + 0.5 * first;
    if (t_new >= t0 + T) t_new -= T;
  } else {
    t_new = 0.5 * (starts[best] + ends[best]);
  }
  BasicFlow<R> flow(model);
  const Dyn dyn(model, flow.options().baumgarte);
  flow.reset(t0, R::State::from_array(dyn.consistent(full_state(s.v), phase_)), phase_);
  if (t_new > t0 && flow.advance(t_new) != FlowStop::reached) return false;
  const double old_section = section_;
  const Phase old_phase = phase_;
  const Vector old_reference = reference_;
  if (t_new > t0) {
    reference_ = flow.state().to_array();
    phase_ = flow.phase();
    section_ = t_new / model.period();
  }
  VectorXd v = s.v;
  for (int i = 0; i < P; ++i) v[i] = reference_[Dyn::kPeriodic[i]] / scale_[i];
  Map m = map(v, true);
  std::optional<VectorXd> t;
  if (m.ok && !m.grazing) {
    VectorXd along = VectorXd::Zero(P + 1);
    along[P] = s.tangent[P] >= 0 ? 1.0 : -1.0;
    // Orient by the old tangent's parameter component; near a fold (where it vanishes) by the
    // whole old tangent's state part is not comparable, so by the parameter alone.
    t = tangent(v, m, std::abs(s.tangent[P]) > 1e-3 ? along : along);
  }
  if (!t) {
    section_ = old_section, phase_ = old_phase, reference_ = old_reference;
    return false;
  }
  s.v = v;
  s.map = std::move(m);
  s.tangent = *t;
  return true;
}

template <class R>
Branch Continuation<R>::finish(Branch& branch, BranchEnd end, std::string message,
                               std::chrono::steady_clock::time_point start_time) const {
  branch.end = end;
  branch.message = std::move(message);
  branch.period_maps = maps_;
  branch.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return branch;
}

template <class R>
Branch Continuation<R>::run() {
  const auto start_time = std::chrono::steady_clock::now();
  Branch branch;
  branch.key = field_.key;
  branch.unit = field_.unit;
  // The first point: the steady state at `from`, found by shooting.
  Case c0 = case_at(o_.from);
  c0.numerics.method = SteadyMethod::shooting;
  const Model m0(c0);
  const Result r0 = simulate(m0, nullptr, o_.cancelled);
  if (r0.status == Status::cancelled)
    return finish(branch, BranchEnd::cancelled, "cancelled at the start", start_time);
  if (!ok(r0.status) || r0.samples.size() == 0)
    return finish(branch, BranchEnd::start_failed,
                  "no steady state at " + at_value(o_.from) +
                      " to start from: " + to_string(r0.status) + " (" + r0.message + ")",
                  start_time);
  Start start;
  start.multiplicity = std::max(1, r0.diagnostics.multiplicity);
  start.section = r0.samples.t[0] / m0.period();
  start.reference = Dyn::sampled_state(r0.samples, 0);
  start.phase = flow_phase(m0.friction(), r0.samples.phase[0]);
  // Scales: each periodic component's range over the sampled orbit (at least 1e-6 of the largest
  // and an absolute floor, so that a component at rest does not divide by zero).
  {
    std::array<double, P> lo, hi;
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    for (std::size_t j = 0; j < r0.samples.size(); ++j) {
      const Vector x = Dyn::sampled_state(r0.samples, j);
      for (int i = 0; i < P; ++i) {
        lo[i] = std::min(lo[i], x[Dyn::kPeriodic[i]]);
        hi[i] = std::max(hi[i], x[Dyn::kPeriodic[i]]);
      }
    }
    double largest = 0.0;
    for (int i = 0; i < P; ++i) largest = std::max(largest, hi[i] - lo[i]);
    for (int i = 0; i < P; ++i) start.scale[i] = std::max({hi[i] - lo[i], 1e-6 * largest, 1e-12});
  }
  return begin(std::move(branch), start, start_time);
}

template <class R>
Branch Continuation<R>::run_from(const Start& start) {
  const auto start_time = std::chrono::steady_clock::now();
  Branch branch;
  branch.key = field_.key;
  branch.unit = field_.unit;
  return begin(std::move(branch), start, start_time);
}

template <class R>
Branch Continuation<R>::begin(Branch branch, const Start& start,
                              std::chrono::steady_clock::time_point start_time) {
  p_ = start.multiplicity;
  branch.multiplicity = p_;
  section_ = start.section;
  reference_ = start.reference;
  phase_ = start.phase;
  scale_ = start.scale;
  VectorXd v(P + 1);
  for (int i = 0; i < P; ++i) v[i] = reference_[Dyn::kPeriodic[i]] / scale_[i];
  v[P] = o_.from / sq_;
  int iterations = 0;
  VectorXd along = VectorXd::Zero(P + 1);
  along[P] = o_.to > o_.from ? 1.0 : -1.0;
  std::optional<Solution> first = correct(v, along, &iterations, 1.0);  // q fixed at `from`
  if (!first)
    return finish(
        branch, BranchEnd::start_failed,
        "the steady state at the start does not solve the shooting problem: " + last_failure_,
        start_time);
  const std::optional<VectorXd> t = tangent(first->v, first->map, along);
  if (!t) return finish(branch, BranchEnd::start_failed, "no tangent at the start", start_time);
  first->tangent = *t;
  return follow(std::move(branch), std::move(*first), iterations, start_time);
}

// The period-2p orbit born at a period doubling (supercritical: on the side where the period-p
// orbit is unstable; subcritical: on the other) lies about sqrt(|q - q*|) from the period-p
// orbit along the eigenvector of the multiplier -1 (Seydel 2010, branch switching). From
// q* + 1e-3 of the range on either side, Newton on P^2p(z) = z starts from the period-p orbit
// displaced along that eigenvector by a few sizes; a solution that is a fixed point of P^p
// already is the period-p orbit, not the new one, and is refused.
template <class R>
Branch Continuation<R>::switch_at(const Doubling& d, const std::array<double, P>& scale) {
  const auto start_time = std::chrono::steady_clock::now();
  const int parent_p = p_;
  Branch branch;
  branch.key = field_.key;
  branch.unit = field_.unit;
  p_ = 2 * parent_p;
  branch.multiplicity = p_;
  section_ = d.section;
  phase_ = d.phase;
  reference_ = d.state;
  scale_ = scale;
  const double lo_q = std::min(o_.from, o_.to), hi_q = std::max(o_.from, o_.to);
  for (const double side : {d.unstable_side, -d.unstable_side}) {
    const double q = std::clamp(d.q + side * 1e-3 * sq_, lo_q, hi_q);
    for (const double size : {0.05, 0.2, 0.01}) {
      VectorXd v(P + 1);
      for (int i = 0; i < P; ++i) v[i] = reference_[Dyn::kPeriodic[i]] / scale_[i];
      v.head(P) += size * d.direction;
      v[P] = q / sq_;
      VectorXd along = VectorXd::Zero(P + 1);
      along[P] = side;
      int iterations = 0;
      std::optional<Solution> first = correct(v, along, &iterations, 10.0);
      if (!first) continue;
      // Not the period-p orbit: one period map of it must not close.
      p_ = parent_p;
      const Map once = map(first->v, false);
      p_ = 2 * parent_p;
      if (once.ok && once.F.cwiseAbs().maxCoeff() < 1e-4) continue;
      const std::optional<VectorXd> t = tangent(first->v, first->map, along);
      if (!t) continue;
      first->tangent = *t;
      // Follow it to the end of the range on its side.
      o_.from = d.q;
      o_.to = side > 0 ? hi_q : lo_q;
      from_what_ = "the period doubling it was switched on at";
      return follow(std::move(branch), std::move(*first), iterations, start_time);
    }
  }
  return finish(branch, BranchEnd::start_failed,
                "no period-" + std::to_string(2 * parent_p) +
                    " orbit found beside the period "
                    "doubling at " +
                    at_value(d.q) + ": " + last_failure_,
                start_time);
}

// Where a branch in contact ends because the drum lifts off: its orbits' smallest normal force
// falls to zero, and the corrector fails down to the smallest step there (its iterates and the
// difference quotients reach across lift-off, where the orbit that lifts off is another one: in
// pure rolling the release of the tangential force at lift-off makes the change finite,
// docs/lift-off.md). min N of an orbit is a smooth function of q near the point (the minimum in
// time of a smooth N(t, q), dN/dt = 0 there), so its zero is found by the secant through the last
// two orbits: q* = q_n + N_n (q_n - q_{n-1}) / (N_{n-1} - N_n). The point lies between the last
// orbit in contact and q* (reported as q* with that distance as its tolerance). It is taken to be
// the end only when q* lies within the located tolerance (or a few failed steps) of the last orbit
// and the period map from the last orbit at a q as far beyond q* lifts off (a flight phase
// appears); otherwise (the contact cannot open, min N is not falling to zero there, the map beyond
// keeps contact) nothing: the failure has another cause.
template <class R>
std::optional<Branch> Continuation<R>::end_at_lift_off(
    Branch& branch, const Solution& cur, double q_fail,
    std::chrono::steady_clock::time_point start_time) {
  if (!base_.contact.unilateral || has_flight(cur.map.sequence) || branch.points.size() < 2)
    return std::nullopt;
  const BranchPoint& last = branch.points.back();
  const BranchPoint& before = branch.points[branch.points.size() - 2];
  const double dN = before.min_N - last.min_N;
  if (!(last.min_N >= 0.0) || !(dN > 0.0)) return std::nullopt;
  const double q_star = last.parameter + last.min_N * (last.parameter - before.parameter) / dN;
  const double reach = std::abs(q_star - last.parameter);
  const double q_tol = o_.tolerance * sq_;
  if (!(reach <= std::max(q_tol, 10.0 * std::abs(q_fail - last.parameter)))) return std::nullopt;
  VectorXd beyond = cur.v;
  beyond[P] =
      (q_star + (q_star - last.parameter) + (q_star >= last.parameter ? 1.0 : -1.0) * q_tol) / sq_;
  const std::string failure = last_failure_;
  const Map probe = map(beyond, false);
  if (!probe.ok || !has_flight(probe.sequence)) {
    last_failure_ = failure;
    return std::nullopt;
  }
  Bifurcation bif;
  bif.kind = BifurcationKind::lift_off;
  bif.after_point = static_cast<int>(branch.points.size()) - 1;
  bif.parameter = q_star;
  bif.tolerance = reach;
  bif.description =
      detail::format("the smallest normal force reaches zero (%.3g N at ", last.min_N) +
      at_value(last.parameter, "%.9g") +
      "): the drum lifts off, and no orbit in contact continues the branch beyond";
  branch.bifurcations.push_back(bif);
  return finish(branch, BranchEnd::lift_off,
                "at " + at_value(q_star, "%.9g") +
                    " the drum lifts off (the orbit's smallest normal force reaches zero); the "
                    "orbit beyond, with flight, is not on this branch (oscidrum diagram or run "
                    "show the motion there)",
                start_time);
}

// Where the orbits' smallest normal force falls to zero at the failed step (extrapolated from the
// last two points, as end_at_lift_off does) in permanent contact: the reason the branch ends (it
// said "no tangent at the new point" at the lift-off frequency, 65.726 Hz, without a word of
// contact).
template <class R>
std::string Continuation<R>::contact_ends(const Branch& branch, double q_fail) const {
  if (base_.contact.unilateral || branch.points.size() < 2) return "";
  const BranchPoint& last = branch.points.back();
  const BranchPoint& before = branch.points[branch.points.size() - 2];
  const double dN = before.min_N - last.min_N;
  if (!(last.min_N >= 0.0) || !(dN > 0.0)) return "";
  const double q_star = last.parameter + last.min_N * (last.parameter - before.parameter) / dN;
  const double reach = std::abs(q_star - last.parameter);
  if (!(reach <= std::max(o_.tolerance * sq_, 10.0 * std::abs(q_fail - last.parameter)))) return "";
  return detail::format("; the orbits' smallest normal force falls to zero there (%.3g N at ",
                        last.min_N) +
         at_value(last.parameter, "%.9g") +
         "): the drum loses contact, which the model in permanent contact does not follow "
         "(contact.unilateral = true follows it into flight)";
}

template <class R>
bool Continuation<R>::collapses(const Solution& s, const Solution& before, bool symmetric) {
  const double r_at = half_residual(s), r_away = half_residual(before);
  // The located turn need not be close to the collapse in the orbit: the parameter is quadratic
  // in the arclength there, the residual linear, so the bisection's bracket in q closes around
  // the turn long before the residual falls (a vibratory drum's period-2 branch turned at
  // 25.736014 Hz with a residual of 0.0063 against 0.041 at the last point, 2e-4 Hz before it,
  // and was reported as a saddle-node: the stable orbits on both sides were the same).
  return r_at < 1e-2 && (r_at < 0.1 * r_away || (symmetric && r_at < r_away));
}

template <class R>
double Continuation<R>::half_residual(const Solution& s) {
  const int p = p_;
  p_ = p / 2;
  const Map at = map(s.v, false);
  p_ = p;
  return at.ok ? at.F.cwiseAbs().maxCoeff() : std::numeric_limits<double>::infinity();
}

template <class R>
Branch Continuation<R>::halve_at(const Halving& h, const std::array<double, P>& scale) {
  Start start;
  start.section = h.section;
  start.reference = h.state;
  start.phase = h.phase;
  start.multiplicity = p_ / 2;
  start.scale = scale;
  o_.from = h.q;
  from_what_ = "the period doubling it started at";
  const auto start_time = std::chrono::steady_clock::now();
  Branch branch;
  branch.key = field_.key;
  branch.unit = field_.unit;
  return begin(std::move(branch), start, start_time);
}

template <class R>
Branch Continuation<R>::follow(Branch branch, Solution cur, int iterations,
                               std::chrono::steady_clock::time_point start_time) {
  resection(cur);
  double s = 0.0;
  branch.points.push_back(point(cur, s, iterations));
  if (o_.on_point)
    o_.on_point(static_cast<int>(branch.points.size()), branch.points.back().parameter);
  double ds = o_.initial_step;
  const double lo_q = std::min(o_.from, o_.to), hi_q = std::max(o_.from, o_.to);
  while (true) {
    if (cancelled()) return finish(branch, BranchEnd::cancelled, "cancelled", start_time);
    if (static_cast<int>(branch.points.size()) >= o_.max_points)
      return finish(branch, BranchEnd::max_points,
                    "stopped after " + std::to_string(o_.max_points) + " points (max_points)",
                    start_time);
    std::optional<Solution> next = correct(cur.v + ds * cur.tangent, cur.tangent, &iterations, ds);
    if (next) {
      const std::optional<VectorXd> t = tangent(next->v, next->map, cur.tangent);
      if (!t)
        next.reset(), last_failure_ = "no tangent at the new point";
      else
        next->tangent = *t;
    }
    if (!next) {
      if (cancelled()) return finish(branch, BranchEnd::cancelled, "cancelled", start_time);
      ds *= 0.5;
      if (ds < o_.min_step) {
        if (std::optional<Branch> lifted =
                end_at_lift_off(branch, cur, parameter(cur.v + 2.0 * ds * cur.tangent), start_time))
          return *lifted;
        return finish(branch, BranchEnd::step_too_small,
                      "the corrector failed down to the smallest step at " +
                          at_value(branch.points.back().parameter) + ": " + last_failure_ +
                          contact_ends(branch, parameter(cur.v + 2.0 * ds * cur.tangent)),
                      start_time);
      }
      continue;
    }
    double q = parameter(next->v);
    // A step past the end of the range: the last point is the orbit at `to` itself (the
    // corrector with the parameter fixed there, from the previous point's tangent), not one up to
    // a step beyond it, with bifurcations located past the range.
    const bool past_end = o_.to > o_.from ? q > hi_q : q < lo_q;
    if (past_end && cur.tangent[P] != 0.0) {
      const double to_v = o_.to / sq_;
      const double ds_end = (to_v - cur.v[P]) / cur.tangent[P];
      VectorXd predicted = cur.v + ds_end * cur.tangent;
      predicted[P] = to_v;
      VectorXd fixed = VectorXd::Zero(cur.v.size());
      fixed[P] = 1.0;
      int end_iterations = iterations;
      std::optional<Solution> end = correct(predicted, fixed, &end_iterations, std::abs(ds_end));
      if (end) {
        const std::optional<VectorXd> t = tangent(end->v, end->map, cur.tangent);
        if (t) {
          end->tangent = *t;
          next = std::move(end);
          iterations = end_iterations;
          ds = std::abs(ds_end);
          q = parameter(next->v);
        }
      }
    }
    // An even-period branch whose next point is an orbit of half its period: at the period
    // doubling, where its own orbits turn back onto those of P^(p/2), the step landed on the
    // period-p/2 orbits that pass through the point (a vibratory drum's period-2 branch went on
    // as the flip-unstable period-1 orbits, labelled period 2 with the squares of their
    // multipliers, the crossing read as a grazing). The branch ends there.
    if (p_ % 2 == 0 && !halving_) {
      const double half = half_residual(*next);
      if (half < kHalfOrbit)
        return finish(
            branch, BranchEnd::period_halved,
            "at " + at_value(q) + " the next point is an orbit of period " +
                std::to_string(p_ / 2) + " (it repeats after " + std::to_string(p_ / 2) +
                (p_ / 2 == 1 ? " period" : " periods") + " to " + detail::format("%.2g", half) +
                "): the continuation crossed from the period-" + std::to_string(p_) +
                " orbits onto those at their period doubling; the branch ends at its "
                "last period-" +
                std::to_string(p_) + " point, " + at_value(branch.points.back().parameter),
            start_time);
    }
    s += ds;
    BranchPoint pt = point(*next, s, iterations);
    if (past_end && std::abs(pt.parameter - o_.to) <= 1e-12 * std::abs(o_.to)) pt.parameter = o_.to;
    locate(branch, cur, *next, ds, branch.points.back(), pt);
    branch.points.push_back(std::move(pt));
    if (o_.on_point) o_.on_point(static_cast<int>(branch.points.size()), q);
    if (halving_) {
      // The orbits beyond the collapse are this branch's own again (shifted by p/2 periods): the
      // branch ends there, and its child follows the period-p/2 orbit on towards `to`.
      const Bifurcation& at = branch.bifurcations[static_cast<std::size_t>(halving_->index)];
      return finish(
          branch, BranchEnd::period_halved,
          "at " + at_value(at.parameter, "%.9g") + " the period-" + std::to_string(p_) +
              " orbit shrinks onto the period-" + std::to_string(p_ / 2) +
              " orbit (its period doubling); beyond it the branch returns through its own "
              "orbits",
          start_time);
    }
    cur = std::move(*next);
    // Slip without a switch over the whole period: the stick phase has vanished and the drum
    // spins (gross slip). Its orbits form a continuum (phi' is free: a multiplier stays at +1)
    // and beyond it phi' grows: no periodic orbit to follow.
    if (cur.map.switches.empty() &&
        (phase_ == Phase::slip_positive || phase_ == Phase::slip_negative)) {
      return finish(branch, BranchEnd::gross_slip,
                    "at " + at_value(q) +
                        " the drum slips throughout the period (gross slip): no periodic orbit "
                        "beyond",
                    start_time);
    }
    resection(cur);
    if (past_end || q > hi_q || q < lo_q) {
      const bool at_end = past_end;
      return finish(branch, at_end ? BranchEnd::reached_end : BranchEnd::left_range,
                    at_end ? "reached " + at_value(o_.to)
                    : from_what_.empty()
                        ? "the branch turned back and left the range at " + at_value(o_.from)
                        : "the branch turned back to " + from_what_ + ", " + at_value(o_.from) +
                              ", where its range begins (its orbits beyond the turn are not "
                              "followed; a continuation started at a value among them follows "
                              "them)",
                    start_time);
    }
    if (iterations <= 3) ds = std::min(ds * 1.5, o_.max_step);
  }
}

}  // namespace oscidrum::detail::branching
