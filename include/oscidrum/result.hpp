// oscidrum/result.hpp: what a simulation returns. Inputs and outputs never share a struct.
#pragma once

#include <string>
#include <vector>

#include "oscidrum/state.hpp"

namespace oscidrum {

/// How a simulation ended.
enum class Status {
  steady_state,         ///< the response repeats; the steady state was sampled
  max_periods_reached,  ///< no steady state within Numerics::max_periods (last periods sampled)
  contact_lost,         ///< N <= 0: lift-off, which the model does not cover
  chattering,           ///< too many stick/slip switches in a vanishing time
  non_finite,           ///< a NaN or infinity appeared in the state
  invalid_geometry,     ///< trough curvature radius fell to the drum radius (f5 <= 0)
  gross_slip,           ///< the drum spins: the driving torque exceeds what friction can hold
  budget_exceeded,      ///< more steps in one period than Numerics::max_steps_per_period
  cancelled,            ///< stopped by the caller (progress callback, cancellation, Ctrl-C)
};

/// "steady_state", "max_periods_reached", ...
const char* to_string(Status status);

/// Process exit-style classification: true only for Status::steady_state.
inline bool ok(Status status) { return status == Status::steady_state; }

enum class EventKind {
  stick_to_slip,  ///< |T| reached mu N
  slip_to_stick,  ///< v_rel reached 0 and the stick solution stays in the friction cone
  slip_reversal,  ///< v_rel reached 0, stick not sustainable: slip on with the opposite sign
  contact_lost,   ///< N reached 0
};
const char* to_string(EventKind kind);

struct Event {
  double t = 0.0;  ///< [s]
  EventKind kind = EventKind::stick_to_slip;
  Phase from = Phase::stick;
  Phase to = Phase::stick;
};

/// Counters of the run.
struct Diagnostics {
  int periods_simulated = 0;   ///< excitation periods integrated before sampling [-]
  int periods_to_steady = -1;  ///< period index at which the steady state was found (-1: never)
  int multiplicity = 0;        ///< steady period in excitation periods (0: none found)
  double final_change = 0.0;   ///< last period-to-period change (scaled, see docs) [-]
  long steps = 0;              ///< accepted integrator steps
  long rejected_steps = 0;     ///< rejected trial steps (from the RHS count: 6 per attempt)
  long rhs_evaluations = 0;    ///< right-hand-side evaluations
  long events = 0;             ///< located events
  long switches = 0;           ///< stick/slip phase changes
  long reversals = 0;          ///< slip -> slip reversals (rare, see docs/model.md section 6)
  long inconsistent_slip_ends = 0;   ///< slip ends where neither stick nor a reversal is
                                     ///< consistent (docs/model.md); stick is taken
  double switches_per_period = 0.0;  ///< in the sampled steady state
  double max_slip_residual = 0.0;    ///< max |(39)| / W during slip, W = m g + Fz [-]
  double min_N = 0.0;                ///< smallest normal force seen [N]
};

/// The sampled steady state: uniform samples over Result::sample_periods excitation periods,
/// t_j = t0 + j / (f samples_per_period), j = 0 ... n-1 (the end point is not repeated).
struct Samples {
  std::vector<double> t;       ///< time [s]
  std::vector<double> delta;   ///< position angle [rad]
  std::vector<double> phi;     ///< drum rotation [rad]
  std::vector<double> x_A;     ///< trough horizontal displacement [m]
  std::vector<double> s_A;     ///< trough vertical displacement (down) [m]
  std::vector<double> ddelta;  ///< delta' [rad/s]
  std::vector<double> dphi;    ///< phi' [rad/s]
  std::vector<double> dx_A;    ///< x_A' [m/s]
  std::vector<double> ds_A;    ///< s_A' [m/s]
  std::vector<double> x_M;     ///< drum centre horizontal displacement [m]
  std::vector<double> z_M;     ///< drum centre vertical displacement (down) [m]
  std::vector<double> ddx_M;   ///< drum centre horizontal acceleration [m/s^2]
  std::vector<double> ddz_M;   ///< drum centre vertical acceleration (down) [m/s^2]
  std::vector<double> N;       ///< normal contact force [N]
  std::vector<double> T;       ///< tangential contact force [N]
  std::vector<double> v_rel;   ///< slip velocity [m/s]
  std::vector<double> torque;  ///< excitation MM(t) [N m]
  std::vector<Phase> phase;    ///< contact phase

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
  double stick_time = 0.0;          ///< time in stick within the sampled window [s]
  double slip_positive_time = 0.0;  ///< time in slip+ within the sampled window [s]
  double slip_negative_time = 0.0;  ///< time in slip- within the sampled window [s]
};

}  // namespace oscidrum
