// Internal: the periodic steady state by shooting, a driver on the flow (docs/periodic.md).
// Newton's method on the period map P over one excitation period, P(z) = z, on the reduced state
// z = (delta, x_A, s_A, delta', x_A', s_A', phi') (phi is cyclic: no right-hand side depends on
// it), with the monodromy matrix from the variational equations (src/flow/monodromy.hpp).
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "oscidrum/floquet.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum::detail {

struct ShootingOutcome {
  /// True: a periodic orbit was found; the flow stands at its section t0 (a period boundary)
  /// on the orbit, ready for sampling.
  bool converged = false;
  /// Set when the short transient itself ended (contact lost, chattering, cancelled, ...): the
  /// transient method would meet the same end, so it is the run's status (no fallback).
  bool terminal = false;
  Status status = Status::steady_state;
  std::string message;        ///< why it converged or failed
  int transient_periods = 0;  ///< plain periods integrated from the start before Newton
  /// Excitation periods integrated in all (short transient, period maps of P^p counted p times,
  /// the search for a subharmonic orbit), the share of numerics.max_periods shooting spent.
  int periods_integrated = 0;
  /// The run stopped because the next integration would exceed its budget of periods
  /// (ShootingStart::budget, numerics.max_periods): no fallback has periods left either.
  bool budget_exhausted = false;
  /// Excitation periods per period of the orbit: 1, or p when the period-1 orbit is unstable and
  /// a stable orbit of P^p was found instead (or when ShootingStart::multiplicity asked for it).
  int multiplicity = 1;
  int newton_iterations = 0;  ///< Newton steps taken (each one period with sensitivities)
  int period_maps = 0;        ///< period maps evaluated with sensitivities (incl. trials)
  int plain_maps = 0;         ///< period maps evaluated without them (chord steps)
  double final_change = 0.0;  ///< scaled |P(z) - z| at the last evaluated iterate [-]
  /// The last Newton step was taken without evaluating the period map at its result (its
  /// predicted residual was far below the threshold); the caller's plain integration of the
  /// sampled periods from the orbit confirms it.
  bool predicted_last_step = false;
  double phi_drift = 0.0;         ///< (phi(t0 + p T) - phi(t0)) / p on the orbit [rad]
  long jacobian_evaluations = 0;  ///< evaluations of the phase Jacobians
  Floquet floquet;                ///< the multipliers of P^p at the orbit (p = multiplicity)
  /// The multipliers of the unstable period-1 orbit when a P^p orbit (p > 1) replaced it.
  Floquet period1_floquet;
  std::array<double, 8> scale{};  ///< scale of each component (its range over a period)
  double t0 = 0.0;                ///< the section [s]
  State orbit;                    ///< the orbit's state at t0
  /// Largest |(39)| / W and smallest N [N] at the step ends of the short transient from rest (a
  /// trajectory of the run; Newton's iterates are not): Diagnostics::max_slip_residual, min_N.
  double transient_max_slip_residual = 0.0;
  double transient_min_N = std::numeric_limits<double>::infinity();
  Phase phase = Phase::stick;
  std::vector<Event> recent_events;  ///< for a terminal end: the events before it
};

/// Where shooting starts: from `flow`'s current state after a short transient (the default), or
/// directly from a supplied state (a neighbouring case's orbit).
struct ShootingStart {
  bool from_state = false;
  State state;
  Phase phase = Phase::stick;
  /// Excitation periods this run may integrate (0: numerics.max_periods).
  int budget = 0;
  /// Solve P^p(z) = z for this p directly, without the period-1 orbit first, and accept a
  /// period-1 orbit as its solution (tests: P^2 of a stable period-1 orbit is that orbit).
  int multiplicity = 1;
};

/// Run the short transient (from the flow's current state, reset by the caller at t = 0) and
/// Newton. Never throws for numerical trouble.
ShootingOutcome shoot_periodic_orbit(Flow& flow, const ProgressCallback& progress,
                                     const ShootingStart& start = {});

/// Scaled distance between two states at a period boundary, as the transient search measures
/// the period-to-period change: the largest over (delta, x_A, s_A, delta', x_A', s_A', phi') of
/// the difference over the scale of that component.
double scaled_change(const State& a, const State& b, const std::array<double, 8>& scale);

}  // namespace oscidrum::detail
