// oscidrum/result.hpp: what a simulation returns. Inputs and outputs never share a struct.
#pragma once

#include <string>
#include <vector>

#include "oscidrum/floquet.hpp"
#include "oscidrum/outputs.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/state.hpp"

namespace oscidrum {

/// How a simulation ended: steady_state, max_periods_reached, contact_lost, chattering,
/// non_finite, invalid_geometry, gross_slip, budget_exceeded, cancelled (descriptions in
/// OSCIDRUM_STATUSES, oscidrum/outputs.hpp).
enum class Status {
#define OSCIDRUM_ENUMERATOR(name, description) name,
  OSCIDRUM_STATUSES(OSCIDRUM_ENUMERATOR)
#undef OSCIDRUM_ENUMERATOR
};

/// "steady_state", "max_periods_reached", ...
const char* to_string(Status status);

/// Process exit-style classification: true only for Status::steady_state.
inline bool ok(Status status) { return status == Status::steady_state; }

enum class EventKind {
  stick_to_slip,  ///< |T| reached mu N
  slip_to_stick,  ///< v_rel reached 0 and the stick solution stays in the friction cone
  slip_reversal,  ///< v_rel reached 0, stick not sustainable: slip on with the opposite sign
  contact_lost,   ///< N reached 0 (permanent contact: the run stops), or slip became singular
  lift_off,       ///< N reached 0 with contact.unilateral: the drum leaves the trough (flight)
  landing,        ///< the gap closed: contact resumes in stick or slip
};
const char* to_string(EventKind kind);

struct Event {
  double t = 0.0;  ///< [s]
  EventKind kind = EventKind::stick_to_slip;
  Phase from = Phase::stick;
  Phase to = Phase::stick;
  /// A landing: the speed at which the gap closed, -g' [m/s] (0 for every other event).
  double speed = 0.0;
};

/// Counters of the run: one member per entry of OSCIDRUM_DIAGNOSTICS (oscidrum/outputs.hpp), with
/// its type, initial value, unit and description there (periods_simulated, periods_to_steady,
/// multiplicity, final_change, steps, ..., max_slip_residual, min_N [N]).
struct Diagnostics {
#define OSCIDRUM_MEMBER(type, name, initial, unit, label, description) type name = initial;
  OSCIDRUM_DIAGNOSTICS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
};

using SampleValues = std::vector<double>;  ///< one column of samples
using SamplePhases = std::vector<Phase>;   ///< the contact phase per sample

/// The sampled steady state: uniform samples over Result::sample_periods excitation periods,
/// t_j = t0 + j / (f samples_per_period), j = 0 ... n-1 (the end point is not repeated). One
/// member per column of OSCIDRUM_SAMPLE_COLUMNS (oscidrum/outputs.hpp): t [s], delta [rad], phi,
/// x_A [m], s_A, ddelta [rad/s], dphi, dx_A [m/s], ds_A, x_M [m], z_M, ddx_M [m/s^2], ddz_M, N [N],
/// T, v_rel [m/s], torque [N m], phase.
struct Samples {
#define OSCIDRUM_MEMBER(type, name, unit, label, description) type name;
  OSCIDRUM_SAMPLE_COLUMNS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER

  std::size_t size() const { return t.size(); }
};

struct Result {
  Status status = Status::steady_state;
  std::string message;  ///< human-readable explanation of the status
  Diagnostics diagnostics;
  double frequency = 0.0;      ///< excitation frequency f [Hz]
  int sample_periods = 0;      ///< excitation periods covered by `samples` [-]
  int samples_per_period = 0;  ///< [-]
  Samples samples;
  std::vector<Event> events;        ///< every event of the run (time order)
  double stick_time = 0.0;          ///< time in stick within the sampled window [s] (NaN: none)
  double slip_positive_time = 0.0;  ///< time in slip+ within the sampled window [s]
  double slip_negative_time = 0.0;  ///< time in slip- within the sampled window [s]
  double flight_time = 0.0;         ///< time in flight within the sampled window [s]
  /// Floquet multipliers of the steady state (shooting only; Stability::unknown otherwise).
  Floquet floquet;
  /// The multipliers of the unstable period-1 orbit when shooting replaced it by a stable orbit
  /// repeating every p > 1 periods (a period doubling: a real multiplier beyond -1).
  /// Stability::unknown otherwise, and for a study's case that Newton started on P^p from its
  /// neighbour's orbit (the period-1 orbit is then not computed).
  Floquet period1_floquet;
};

}  // namespace oscidrum
