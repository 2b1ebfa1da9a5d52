// Internal: one steady period recorded piece by piece for the steady metrics
// (src/drivers/steady_metrics.cpp). On each piece (an integrator step in one phase, cut at the
// period's ends) every quantity the metrics read (x_M'', z_M'' from (18), delta, phi, T/N, the
// friction power, the gap) is replaced by its Chebyshev interpolant in t through kDegree + 1
// evaluations on the flow's dense output. compute_metrics integrates the period again from the
// first sample and records it; a shooting orbit's sampling records its first period on the way
// (the same trajectory from the same restart, so the same pieces; src/drivers/sampling.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "metrics/piece_interpolant.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/result.hpp"
#include "roller/dynamics.hpp"

namespace oscidrum::detail::recording {

// Chebyshev interpolant per piece: kDegree + 1 RHS evaluations. 8: within 1e-12 of the direct
// evaluation (test_steady_metrics); 6 is not, on pure rolling; 10 (used before) cost a tenth
// more of a study's case for nothing the metrics show (1e-10 of psi_xz on the product sweep).
inline constexpr int kDegree = 12;

using Interpolant = ChebyshevInterpolant<kDegree>;

// The quantities interpolated on each piece, as the roller's Dynamics::quantities returns them.
// kVerticalForce: the soil's vertical force on the drum F_v (25); kZ: z_M (14).
enum Quantity {
  kDdx,
  kDdz,
  kDelta,
  kPhi,
  kTraction,
  kFrictionPower,
  kGap,
  kVerticalForce,
  kZ,
  kQuantities
};

// One piece of the steady period (an integrator step in one phase, cut at the period's ends):
// every quantity as its Chebyshev interpolant in t.
struct Piece {
  double a, b;  // [s]
  Phase phase;
  std::array<Interpolant, kQuantities> f;
  std::array<std::array<double, Interpolant::kNodes>, kQuantities> values;  // at the nodes
  Interpolant dx, dz;  // d/dt of x_M'' and z_M'' [m/s^3]
};

// One steady period recorded piece by piece: [t_begin, t_end] of the trajectory the flow took
// from `start` in `phase`, restarted at t_begin.
struct Recording {
  std::vector<Piece> pieces;
  int lift_offs = 0;                  // lift-offs in the period
  double landing_speed = 0.0;         // the largest approach speed at a landing [m/s]
  double t_begin = 0.0, t_end = 0.0;  // [s]
  std::vector<double> start;          // the state at t_begin (Dynamics<R>::Vector)
  Phase phase = Phase::stick;         // the flow's phase there
  // Not of the period: how shooting got there. The contraction of the residual by a warm start's
  // first chord step (WarmStart::contraction, for the next case of a chain; negative: none).
  double chord_contraction = -1.0;
};

// Empties a recording but keeps the storage of its pieces for the next one (a study reuses one
// recording per thread: some 300 kB a case otherwise allocated, touched and returned).
inline void clear(Recording& r) {
  std::vector<Piece> pieces = std::move(r.pieces);
  pieces.clear();
  r = Recording{};
  r.pieces = std::move(pieces);
}

// Records the pieces of [t_begin, t_end] (the caller sets the Recording's start and phase).
template <class R>
class Recorder : public BasicFlowObserver<R> {
 public:
  using Dyn = Dynamics<R>;
  /// `storage`: the pieces of an earlier recording, whose storage is reused (emptied first).
  Recorder(const Model& model, double baumgarte, double t_begin, double t_end,
           std::vector<Piece> storage = {})
      : dynamics_(model, baumgarte), t_begin_(t_begin), t_end_(t_end) {
    out.t_begin = t_begin;
    out.t_end = t_end;
    out.pieces = std::move(storage);
    out.pieces.clear();
    out.pieces.reserve(256);  // a steady period has some 50 to 200 (growing copies ~1.4 kB each)
  }

  bool on_event(const Event& event, const typename R::State&, const typename R::State&) override {
    if (event.t < t_begin_ || event.t >= t_end_) return true;
    if (event.kind == EventKind::lift_off) ++out.lift_offs;
    if (event.kind == EventKind::landing)
      out.landing_speed = std::max(out.landing_speed, event.speed);
    return true;
  }

  bool on_step(const BasicStepView<R>& step) override {
    const double a = std::max(step.t0(), t_begin_), b = std::min(step.t1(), t_end_);
    if (!(b > a)) return true;
    Piece& piece = out.pieces.emplace_back();  // filled in place (a Piece is ~1.4 kB)
    piece.a = a;
    piece.b = b;
    piece.phase = step.phase();
    typename Dyn::Vector end_state{};
    std::array<double, kQuantities> end_values{};
    for (int k = 0; k < Interpolant::kNodes; ++k) {
      // The end nodes exactly at a and b (the one-sided limits at a switch).
      const double t = k == 0 ? b : k == kDegree ? a : Interpolant::node(a, b, k);
      const typename Dyn::Vector q = step.state(t).to_array();
      // A piece that continues the last one (no switch between them) starts where it ended:
      // the same time, state and phase, so the same values.
      const bool same =
          k == kDegree && have_end_ && t == end_t_ && step.phase() == end_phase_ && q == end_state_;
      const auto v = same ? end_values_ : dynamics_.quantities(t, q, step.phase());
      for (int m = 0; m < kQuantities; ++m) piece.values[m][k] = v[m];
      if (k == 0) end_state = q, end_values = v;
    }
    have_end_ = true;
    end_t_ = b;
    end_phase_ = step.phase();
    end_state_ = end_state;
    end_values_ = end_values;
    for (int m = 0; m < kQuantities; ++m) piece.f[m] = Interpolant(a, b, piece.values[m]);
    piece.dx = piece.f[kDdx].derivative_interpolant();
    piece.dz = piece.f[kDdz].derivative_interpolant();
    return true;
  }
  Recording out;

 private:
  const Dyn dynamics_;
  const double t_begin_, t_end_;
  // The values at the end of the last piece (node 0).
  bool have_end_ = false;
  double end_t_ = 0.0;
  Phase end_phase_ = Phase::stick;
  typename Dyn::Vector end_state_{};
  std::array<double, kQuantities> end_values_{};
};

}  // namespace oscidrum::detail::recording

namespace oscidrum::detail {

/// compute_metrics(model, result, n_max), reading `recorded` (may be null) instead of integrating
/// the period again when it is that period recorded from the same restart (its span, start state
/// and phase; the same pieces, so the same numbers bit for bit); otherwise as compute_metrics.
Metrics compute_metrics(const Model& model, const Result& result, int n_max,
                        const recording::Recording* recorded);

/// The steady period of `result` as compute_metrics reads it: `recorded` when it is that period
/// (as above), else the period integrated again from the first sample and recorded. Throws
/// oscidrum::Error as compute_metrics does.
recording::Recording steady_period(const Model& model, const Result& result,
                                   const recording::Recording* recorded);

}  // namespace oscidrum::detail
