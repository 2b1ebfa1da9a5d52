// oscidrum/outputs.hpp: the one description of every output. Each list below is an X-macro: one
// entry per output with its type, name, unit and description. The result structs (Samples,
// Diagnostics, Metrics, RecordMetrics) and the Status enum are generated from these lists, and the
// same lists drive the CSV and JSON writers, the Python attributes, the run summary and the
// tables of docs/outputs.md (`oscidrum outputs --format markdown`). Adding an output is one entry
// here plus its computation.
//
// Entry forms (every macro argument X is applied to each entry):
//   samples, metrics:  X(type, name, unit, label, description)
//   diagnostics:       X(type, name, initial value, unit, label, description)
//   statuses:          X(name, description)
// `label` is the short text for people (the run summary); `description` says what the number is,
// with the paper's equation numbers. Units are SI; "-" for dimensionless.
#pragma once

// ------------------------------------------------------------------------------------------------
// How a simulation ended (Result::status). Only steady_state carries steady-state metrics.
#define OSCIDRUM_STATUSES(X)                                                                    \
  X(steady_state, "the response repeats; the steady state was sampled")                         \
  X(max_periods_reached,                                                                        \
    "no steady state within numerics.max_periods (the last periods are sampled, but they are "  \
    "no steady state)")                                                                         \
  X(contact_lost,                                                                               \
    "N <= 0 (lift-off, which the model does not cover), singular slip equations, or the drum "  \
    "left its trough (|delta| >= pi/2, or in flight beyond its clearance)")                     \
  X(chattering, "too many stick/slip switches in a vanishing time")                             \
  X(non_finite, "a NaN or infinity appeared in the state")                                      \
  X(invalid_geometry,                                                                           \
    "the trough's curvature radius fell to the drum radius (f5 below 1e-3 of its value at the " \
    "bottom)")                                                                                  \
  X(gross_slip, "the drum spins: the driving torque exceeds what friction can hold")            \
  X(budget_exceeded, "more steps in one period than numerics.max_steps_per_period")             \
  X(cancelled, "stopped by the caller (progress callback, cancellation, Ctrl-C)")               \
  X(aperiodic,                                                                                  \
    "no periodic steady state: the motion, examined after numerics.max_periods, is "            \
    "quasi-periodic or chaotic (diagnostics motion, lyapunov_exponent; docs/bifurcations.md)")  \
  X(invalid, "the case of a study was refused before it ran (its parameters; the error says why)")

// ------------------------------------------------------------------------------------------------
// The sampled steady state (Samples, the steady-state CSV), one column per entry, in file order.
// SampleValues is std::vector<double>, SamplePhases std::vector<Phase>.
#define OSCIDRUM_SAMPLE_COLUMNS(X)                                                                 \
  X(SampleValues, t, "s", "t", "time since the start of the excitation")                           \
  X(SampleValues, delta, "rad", "delta", "position angle of the drum in the trough (0: bottom)")   \
  X(SampleValues, phi, "rad", "phi", "total drum rotation")                                        \
  X(SampleValues, x_A, "m", "x_A", "horizontal displacement of the trough (soil point A)")         \
  X(SampleValues, s_A, "m", "s_A", "vertical displacement of the trough, down positive")           \
  X(SampleValues, ddelta, "rad/s", "delta'", "delta'")                                             \
  X(SampleValues, dphi, "rad/s", "phi'", "phi' (in stick: f5 delta', the rolling condition (12))") \
  X(SampleValues, dx_A, "m/s", "x_A'", "x_A'")                                                     \
  X(SampleValues, ds_A, "m/s", "s_A'", "s_A'")                                                     \
  X(SampleValues, x_M, "m", "x_M", "drum centre, horizontal (14)")                                 \
  X(SampleValues, z_M, "m", "z_M", "drum centre, vertical, down positive (14)")                    \
  X(SampleValues, ddx_M, "m/s^2", "x_M''", "drum centre horizontal acceleration (18)")             \
  X(SampleValues, ddz_M, "m/s^2", "z_M''",                                                         \
    "drum centre vertical acceleration, down positive (18)")                                       \
  X(SampleValues, N, "N", "N", "normal contact force (26)")                                        \
  X(SampleValues, T, "N", "T", "tangential contact force (24, 25)")                                \
  X(SampleValues, v_rel, "m/s", "v_rel", "slip velocity (13); 0 in stick and in flight")           \
  X(SampleValues, gap, "m", "gap",                                                                 \
    "gap between drum and trough along the normal at the trough's nearest point (contact."         \
    "unilateral; 0 in contact)")                                                                   \
  X(SampleValues, dgap, "m/s", "gap'", "rate of the gap (0 in contact)")                           \
  X(SampleValues, torque, "N m", "MM", "excitation MM(t) = M0 sin(nu t) + MMd (5, 6)")             \
  X(SampleValues, alpha, "rad", "alpha",                                                           \
    "angle of the excitation, nu t wrapped to [0, 2 pi): the vibratory drum's unbalance force "    \
    "has the downward component F0 sin(alpha) (every roller.exciter; alpha is the angle of a "     \
    "circular exciter's unbalance from +x towards +z), the oscillation drum's moment is M0 "       \
    "sin(alpha) (5); `analyze --unbalance-col alpha` reads it for kb")                             \
  X(SamplePhases, phase, "-", "phase",                                                             \
    "contact phase: 0 stick, 1 slip with v_rel > 0, -1 slip with v_rel < 0, 2 flight "             \
    "(contact.unilateral: the drum off the soil) (regularised friction: the apparent phase, "      \
    "stick while |v_rel| <= 4 v_eps)")

// ------------------------------------------------------------------------------------------------
// Counters of a run (Diagnostics), in output order.
#define OSCIDRUM_DIAGNOSTICS(X)                                                                   \
  X(int, periods_simulated, 0, "-", "periods simulated",                                          \
    "excitation periods integrated, the sampled ones included (shooting: every period map, P^p "  \
    "counting p, and of the sampled periods the orbit's p, which the others repeat); all but "    \
    "the sampled ones count against numerics.max_periods")                                        \
  X(int, periods_to_steady, -1, "-", "steady after (periods)",                                    \
    "period index at which the steady state was found (-1: never)")                               \
  X(int, multiplicity, 0, "-", "multiplicity",                                                    \
    "steady period in excitation periods (0: none found)")                                        \
  X(double, final_change, 0.0, "-", "final change",                                               \
    "last period-to-period change of the state, scaled by its range over a period (see "          \
    "numerics.steady_tol; empty when the run ended before two period boundaries)")                \
  X(long, steps, 0, "-", "integrator steps", "accepted integrator steps")                         \
  X(long, rejected_steps, 0, "-", "rejected steps", "rejected trial steps")                       \
  X(long, rhs_evaluations, 0, "-", "RHS evaluations", "right-hand-side evaluations")              \
  X(long, events, 0, "-", "events", "located events")                                             \
  X(long, switches, 0, "-", "switches", "stick/slip phase changes")                               \
  X(long, reversals, 0, "-", "slip reversals", "slip -> slip reversals (docs/model.md)")          \
  X(long, inconsistent_slip_ends, 0, "-", "inconsistent slip ends",                               \
    "slip ends where neither stick nor a reversal is consistent (docs/model.md); stick is taken") \
  X(double, switches_per_period, 0.0, "-", "switches per period",                                 \
    "stick/slip switches per excitation period in the sampled window (empty without one)")        \
  X(double, max_slip_residual, 0.0, "-", "max slip residual (39)",                                \
    "largest |residual of the slip coupling (39)| / W at the step ends in slip, W = m g + Fz = "  \
    "P0 (a force ratio), over the result's trajectory: the run from rest and the sampled "        \
    "periods (shooting: its short transient from rest and the sampled periods of the orbit, "     \
    "not Newton's iterates; a study's warm-started case, warm_start 1, has no run from rest: "    \
    "its sampled periods only, so its value can differ from the same case run alone)")            \
  X(double, min_N, 0.0, "N", "min N",                                                             \
    "smallest normal force (26) of the same trajectory: at the step ends and the events and, "    \
    "where N has its minimum inside a step, the minimum of the parabola through the step's "      \
    "start, middle and end (docs/model.md section 9); 0 where N reached 0 (contact lost, or a "   \
    "lift-off); N's value where a landing's contact pulled and the drum lifted off again at "     \
    "once (section 13)")                                                                          \
  X(SteadyMethod, method, SteadyMethod::transient, "-", "method",                                 \
    "what produced the steady state: transient (integrated from rest until it repeats) or "       \
    "shooting (solved for by Newton's method on the period map, docs/periodic.md)")               \
  X(int, newton_iterations, 0, "-", "Newton iterations",                                          \
    "shooting: Newton steps (0 for the transient method)")                                        \
  X(long, jacobian_evaluations, 0, "-", "Jacobian evaluations",                                   \
    "shooting: evaluations of the phase Jacobians (0 for the transient method)")                  \
  X(double, period_equivalents, 0.0, "-", "period-equivalents",                                   \
    "cost in plain excitation periods: (right-hand-side evaluations + the Jacobian evaluations "  \
    "weighted by their cost) / the right-hand-side evaluations of one sampled period")            \
  X(double, phi_drift, 0.0, "rad", "phi drift per period",                                        \
    "(phi(t0 + p T) - phi(t0)) / p on a steady state repeating every p periods (phi(t0 + T) - "   \
    "phi(t0) for p = 1): the net slip per excitation period over r (gross_slip: over the last "   \
    "period integrated; empty for any other status)")                                             \
  X(std::string, fallback, "", "-", "shooting fell back",                                         \
    "why shooting fell back to the transient method (empty if it did not)")                       \
  X(std::string, contact_mode, "", "-", "contact mode",                                           \
    "how the steady state uses its contact: permanent contact, periodic lift-off (every "         \
    "period), lift-off every period, repeating every p periods (a subharmonic with one lift-off " \
    "in each of its periods), lift-off every p periods, or n lift-offs every p periods (any "     \
    "other count: a subharmonic with periods of permanent contact, or with two lift-offs in "     \
    "some period); aperiodic for a run with lift-offs that reaches no steady state "              \
    "(max_periods_reached, aperiodic); empty otherwise (a run that ends contact_lost, "           \
    "gross_slip, ... whatever its lift-offs before)")                                             \
  X(std::string, operating_mode, "", "-", "operating mode",                                       \
    "the vibratory drum's contact mode by the literature's names (docs/model.md section 14): "    \
    "continuous contact, partial uplift (lift-off, period 1), double jump (lift-off, period 2), " \
    "lift-off with period p (p > 2), chaotic or quasi-periodic (no periodic steady state, by "    \
    "the examined motion); empty for the oscillation drum, where contact_mode is empty and "      \
    "where the motion got no verdict")                                                            \
  X(int, start_ramp_periods, 0, "-", "start ramp (periods)",                                      \
    "periods over which the excitation was ramped in from rest: numerics.start_ramp_periods, or " \
    "20 when the start from rest lost contact before a steady state and the run was retried "     \
    "with a ramp (0: the paper's start)")                                                         \
  X(int, warm_start, 0, "-", "warm start (continuation)",                                         \
    "continuation in a study (numerics.continuation, shooting only): 1 the steady state was "     \
    "found from the neighbouring case's steady state, -1 that start failed and the case started " \
    "from rest, 0 the case started from rest")                                                    \
  X(std::string, motion, "", "-", "motion",                                                       \
    "a run without a periodic steady state, examined over 400 further periods: quasi_periodic, "  \
    "chaotic, periodic (its stroboscopic points recur: reached slowly), converging, undecided; "  \
    "empty otherwise (docs/bifurcations.md)")                                                     \
  X(double, lyapunov_exponent, 0.0, "1/s", "largest Lyapunov exponent",                           \
    "of the motion examined for `motion` (Benettin's estimate from the variational equations; 0 " \
    "when not examined)")

// ------------------------------------------------------------------------------------------------
// Metrics of the drum-centre accelerations, for simulated steady states (Metrics) and measured
// records (RecordMetrics) alike. Spectrum is std::vector<Harmonic> (n = 0 ... n_max); in CSV a
// spectrum `<s>_harmonics` becomes the columns `<s>_A1` ... `<s>_AN` (amplitudes).
#define OSCIDRUM_ACCELERATION_METRICS(X)                                                           \
  X(double, ddx_max, "m/s^2", "x_M'' max", "largest x_M'' (paper Fig. 9)")                         \
  X(double, ddx_min, "m/s^2", "x_M'' min", "smallest x_M''")                                       \
  X(double, ddz_max, "m/s^2", "z_M'' max", "largest z_M'' (down positive)")                        \
  X(double, ddz_min, "m/s^2", "z_M'' min", "smallest z_M''")                                       \
  X(Spectrum, ddx_harmonics, "m/s^2", "x_M'' harmonics",                                           \
    "harmonics A_n sin(n nu t + theta_n) of x_M'', n = 0 ... N, t absolute (paper Figs. 14, "      \
    "19)")                                                                                         \
  X(Spectrum, ddz_harmonics, "m/s^2", "z_M'' harmonics",                                           \
    "harmonics of z_M'' (paper Figs. 15, 20)")                                                     \
  X(double, psi_xz, "rad", "lag psi_xz",                                                           \
    "lag between x_M'' and z_M'': theta_2(z_M'') - 2 theta_1(x_M'') wrapped to (-pi, pi]; > 0: "   \
    "the 2f component of z_M'' leads (paper Fig. 12); NaN when either component is absent "        \
    "(below 1e-6 of the two signals' largest component: a drum without horizontal motion, a "      \
    "record's constant channel)")                                                                  \
  X(double, area, "m^2/s^4", "area z_M''(x_M'')",                                                  \
    "area enclosed by the z_M''-over-x_M'' figure over one steady period (non-zero winding: "      \
    "both lobes of a figure eight count; paper Figs. 16, 22)")                                     \
  X(double, ddx_A2_A1, "-", "x_M'' A(2f)/A(f)", "harmonic ratio A_2/A_1 of x_M''")                 \
  X(double, ddx_A3_A1, "-", "x_M'' A(3f)/A(f)",                                                    \
    "harmonic ratio A_3/A_1 of x_M'' (odd overtones: slip, paper Fig. 19)")                        \
  X(double, ddz_A2_A1, "-", "z_M'' A(2f)/A(f)", "harmonic ratio A_2/A_1 of z_M'' (paper Fig. 20)") \
  X(double, ddz_A3_A1, "-", "z_M'' A(3f)/A(f)", "harmonic ratio A_3/A_1 of z_M''")                 \
  X(double, cmv, "-", "CMV-type value",                                                            \
    "300 A_2/A_1 of z_M'': the compaction meter value's formula applied to the oscillation "       \
    "drum's vertical acceleration")                                                                \
  X(double, rmv, "-", "RMV-type value",                                                            \
    "A(f/2)/A(f) of z_M'': the resonance meter value's ratio (the subharmonic of a period-2 "      \
    "motion, 0 for a period-1 one)")                                                               \
  X(double, ccv, "-", "CCV-type value",                                                            \
    "100 [A(f/2) + A(3f/2) + A(2f) + A(5f/2) + A(3f)] / [A(f/2) + A(f)] of z_M'': the compaction " \
    "control value's ratio")                                                                       \
  X(double, ddx_thd, "-", "x_M'' THD",                                                             \
    "total harmonic distortion of x_M'': sqrt(sum_{k>=2} A_k^2) / A_1 (a steady state of "         \
    "period p > 1: its subharmonics k f / p count too)")

// Metrics only a simulation has: the drum's rotation and the contact.
#define OSCIDRUM_MOTION_METRICS(X)                                                              \
  X(double, delta_max, "rad", "delta max", "largest position angle delta (paper Fig. 8a)")      \
  X(double, delta_min, "rad", "delta min", "smallest position angle delta")                     \
  X(double, phi_lag, "pi rad", "lag torque -> phi",                                             \
    "lag between the excitation M0 sin(nu t) and phi: theta_1 of phi (drift removed) wrapped "  \
    "to (-2, 0], in units of pi (paper Fig. 10); NaN without an oscillating torque (the "       \
    "vibratory drum)")                                                                          \
  X(double, phi_amplitude, "rad", "phi amplitude", "amplitude A_1 of phi (drift removed)")      \
  X(double, stick_fraction, "-", "stick fraction", "share of the sampled time in stick")        \
  X(double, slip_positive_fraction, "-", "slip+ fraction",                                      \
    "share of the sampled time in slip with v_rel > 0")                                         \
  X(double, slip_negative_fraction, "-", "slip- fraction",                                      \
    "share of the sampled time in slip with v_rel < 0")                                         \
  X(double, slip_fraction, "-", "slip fraction",                                                \
    "share of the sampled time in slip (either sign)")                                          \
  X(double, mu_required, "-", "mu required",                                                    \
    "max |T|/N over the steady period: the friction coefficient rolling without slip needs "    \
    "(equals mu when the drum slips; NaN with lift-off, where N reaches 0) (24-26)")            \
  X(double, friction_work, "J", "friction work per period",                                     \
    "work dissipated by sliding friction per excitation period: integral of |T v_rel| dt over " \
    "the sampled window / its periods (13, 27)")                                                \
  X(double, flight_fraction, "-", "flight fraction",                                            \
    "share of the time in flight, the drum off the trough (contact.unilateral; 0 with "         \
    "permanent contact)")                                                                       \
  X(double, liftoffs_per_period, "-", "lift-offs per period",                                   \
    "lift-offs per excitation period on the steady state (contact.unilateral)")                 \
  X(double, gap_max, "m", "largest gap",                                                        \
    "largest gap between drum and trough over the steady period (contact.unilateral)")          \
  X(double, landing_velocity, "m/s", "landing velocity",                                        \
    "largest speed at which the gap closes at a landing, -g' (contact.unilateral)")             \
  X(double, kb, "N/m", "Kb-type soil stiffness",                                                \
    "Re(F_v(f) / z_M(f)): the soil's vertical force on the drum, F_v = N cos(delta) + T "       \
    "sin(delta) (25), in phase with the drum centre's vertical displacement z_M, at the "       \
    "excitation frequency, over that displacement's amplitude (the k_s of Anderegg and "        \
    "Kaufmann 2004 from the contact force itself; docs/outputs.md); NaN for the oscillation "   \
    "drum, which has no vertical excitation force: there it is m nu^2 - kd whatever the soil")  \
  X(double, evib, "Pa", "Evib-type vibration modulus",                                          \
    "the Young's modulus under which Lundberg's rigid cylinder (radius roller.r, length "       \
    "roller.b, the soil's Poisson's ratio) settles as the drum does on the loading branch of "  \
    "F_v over z_M (Kroeber, Floss and Wallrath 2001, BOMAG's Evib; vibratory drum only; "       \
    "docs/outputs.md)")

// Quantities of the least-squares fit of a measured record.
#define OSCIDRUM_RECORD_FIT(X)                                                                \
  X(double, cycles, "-", "periods spanned", "excitation periods the record spans")            \
  X(double, residual_x, "-", "fit residual x_M''",                                            \
    "RMS of record minus fit, relative to the RMS of x_M'' about its mean")                   \
  X(double, residual_z, "-", "fit residual z_M''", "the same for z_M''")                      \
  X(double, fitted_periods, "-", "periods of the fitted signal",                              \
    "excitation periods p after which the fitted signal repeats: 1, or 2, 3 or 4 where the "  \
    "record's subharmonics f/p, 2f/p, ... explain most of what the harmonics of f leave (a "  \
    "period-2 response, the 'double jump' RMV marks; period 3 or 4 in the windows of "        \
    "periodic motion beyond a drum's lift-off): the fit then holds every harmonic of f/p, "   \
    "the residuals are its, and the peaks and the area are of the p-period figure, as `run` " \
    "gives them for a period-p state (docs/cli.md, \"Period-2 and longer records\")")

// What a record gives with the roller's case and its unbalance angle (`analyze --case
// --unbalance-col`): the drum's vertical balance (20) in place of the contact force.
#define OSCIDRUM_RECORD_DRUM(X)                                                                   \
  X(double, kb, "N/m", "Kb-type soil stiffness",                                                  \
    "Re(F_v(f) / z_M(f)) as for a simulated state, with F_v(f) = F0 e^{i phi_u} + (m nu^2 - kd "  \
    "- i nu cd) z_M(f) from the drum's vertical balance (20), z_M(f) = -z_M''(f) / nu^2: kb = m " \
    "nu^2 - kd - F0 nu^2 cos(phi_u - theta_1) / A_1 with A_1, theta_1 of z_M'' and phi_u the "    \
    "unbalance's phase (vibratory drum: m, kd, F0 = m_u e_u nu^2 from the case; NaN without "     \
    "the case or the unbalance angle; docs/outputs.md)")

// Metrics of a simulated steady state (Metrics), in output order.
#define OSCIDRUM_METRICS(X)        \
  OSCIDRUM_ACCELERATION_METRICS(X) \
  OSCIDRUM_MOTION_METRICS(X)

// Metrics of a measured record (RecordMetrics), in output order.
#define OSCIDRUM_RECORD_METRICS(X) \
  OSCIDRUM_RECORD_FIT(X)           \
  OSCIDRUM_ACCELERATION_METRICS(X) \
  OSCIDRUM_RECORD_DRUM(X)
