// Model: validation of a Case and its derived constants.
#include "oscidrum/model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/soil.hpp"
#include "util/format.hpp"
#include "util/lanes.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {
namespace {

using detail::shortest;
std::string num(double v) { return shortest(v); }

// Every field against its rule in the field table, then the rules that tie fields together.
void validate(const Case& c) {
  for (const Field& f : fields()) {
    const double value = f.get(c);
    std::string problem = check_field(f, value);
    if (!problem.empty()) throw Error(problem, f.key, value);
  }
  const Roller& R = c.roller;
  const double Fz = R.P0 - R.m * R.g;
  if (Fz < 0)
    throw Error(
        "roller.P0 must be >= roller.m * roller.g (Fz = P0 - m g >= 0, (7)) [N]; got P0 = " +
            num(R.P0) + " < m g = " + num(R.m * R.g),
        "roller.P0", R.P0);
  check_fit(c.trough.shape, R.r);
  if (R.type == RollerType::vibratory && !(R.static_moment > 0.0))
    throw Error(
        "roller.static_moment must be > 0 [kg m] with roller.type = vibratory (the unbalance's "
        "m_u e_u, force amplitude m_u e_u nu^2); got " +
            num(R.static_moment),
        "roller.static_moment", R.static_moment);
  if (c.contact.law == FrictionChoice::regularised && !c.contact.pure_rolling &&
      c.contact.mu_static != -1.0 && c.contact.mu_static != c.contact.mu)
    throw Error(
        "contact.mu_static must be -1 (or equal to contact.mu) with contact.law = regularised: "
        "the regularised law has one coefficient and no stick; got mu_static = " +
            num(c.contact.mu_static),
        "contact.mu_static", c.contact.mu_static);
  if (c.contact.mu_static >= 0.0 ? c.contact.mu_static < c.contact.mu : c.contact.mu_static != -1.0)
    throw Error(
        "contact.mu_static must be >= contact.mu (static friction is at least the kinetic), or "
        "-1 (equal to contact.mu); got mu_static = " +
            num(c.contact.mu_static) + ", mu = " + num(c.contact.mu),
        "contact.mu_static", c.contact.mu_static);
  // The sampled steady state is kept in memory: 21 columns of doubles per sample.
  const double samples = static_cast<double>(c.numerics.samples_per_period) *
                         c.numerics.output_periods * c.numerics.max_multiplicity;
  if (samples > 1e7)
    throw Error(
        "numerics.samples_per_period * numerics.output_periods * "
        "numerics.max_multiplicity must be <= 1e7 (the most samples a run may keep, "
        "about 1.7 GB); got " +
            num(samples),
        "numerics.samples_per_period");
  if (!c.contact.pure_rolling && c.soil.input == SoilInput::coefficients && c.soil.csh <= 0)
    throw Error("soil.csh must be > 0 [N s/m] (the slip coupling (53) divides by it); got " +
                    num(c.soil.csh),
                "soil.csh", c.soil.csh);
}

// The drum's fastest linear rate on its supports, against the excitation: the damping rates
// (cd + csh) / m, (cd + csv) / m and the circular frequencies sqrt((kd + ksh) / m),
// sqrt((kd + ksv) / m) [1/s], each times the period T. An explicit integrator (Dormand-Prince
// 8(5,3)) needs about that many steps per period over its stability bound of about 6.4, so a case
// far beyond any roller (the paper's on G = 25 MN/m^2: 5.0, sqrt((kd + ksv) / m); the stiffest soil
// the fields admit, G = 1e11 Pa through Appendix B, a few hundred) takes minutes or fails: it is
// refused, naming the field that makes it so stiff. roller.cd = 1e9 N s/m (330 000 times the
// paper's buffers, 1.4e4) still ran in about a second with Dormand-Prince 5(4); 2e9 (2.8e4) ran
// 44 s into numerics.max_periods.
constexpr double kMaxRatePerPeriod = 2e4;

void check_time_scales(const Case& c, const SoilCoefficients& s) {
  const Roller& R = c.roller;
  const double T = 1.0 / R.f;
  struct Rate {
    double value;      // [1/s]
    const char* what;  // the formula
    const char* key;   // the field that dominates it
  };
  const bool soil_given = c.soil.input == SoilInput::coefficients;
  const auto dominant = [&](double roller_part, const char* roller_key, double soil_part,
                            const char* soil_key) {
    return roller_part >= soil_part ? roller_key : soil_key;
  };
  const Rate rates[] = {
      {(R.cd + s.csh) / R.m, "(roller.cd + csh) / roller.m",
       dominant(R.cd, "roller.cd", s.csh, "soil.csh")},
      {(R.cd + s.csv) / R.m, "(roller.cd + csv) / roller.m",
       dominant(R.cd, "roller.cd", s.csv, "soil.csv")},
      {std::sqrt((R.kd + s.ksh) / R.m), "sqrt((roller.kd + ksh) / roller.m)",
       dominant(R.kd, "roller.kd", s.ksh, "soil.ksh")},
      {std::sqrt((R.kd + s.ksv) / R.m), "sqrt((roller.kd + ksv) / roller.m)",
       dominant(R.kd, "roller.kd", s.ksv, "soil.ksv")},
  };
  for (const Rate& r : rates) {
    if (!(r.value * T > kMaxRatePerPeriod)) continue;
    // A tiny drum mass makes every rate fast: then the mass is the field to name.
    const bool mass = R.m < 1.0;
    const std::string head =
        std::string("the case is too stiff to integrate: ") + r.what +
        detail::format(
            " = %.3g 1/s is %.3g times roller.f, which must be at most "
            "%.3g (the paper's roller on G = 25 MN/m^2: 5.0; an explicit integrator needs "
            "about %.3g steps per period); ",
            r.value, r.value * T, kMaxRatePerPeriod, r.value * T / 3.3);
    // A soil coefficient that Table 2 or Appendix B gives dominates: the soil's inputs make it
    // so, not the roller's key beside it (the paper's roller.cd = 3000 was named for soil.nu =
    // 0.49999999999).
    if (!mass && std::string_view(r.key).starts_with("soil.") && !soil_given) {
      const std::string coefficient(std::string_view(r.key).substr(5));
      const std::string from = c.soil.input == SoilInput::table2
                                   ? "paper Table 2 at soil.G = " + num(c.soil.G) + " Pa"
                                   : "Appendix B (42)-(45) at soil.G = " + num(c.soil.G) +
                                         " Pa, soil.nu = " + num(c.soil.nu) +
                                         ", soil.rho = " + num(c.soil.rho) + " kg/m^3";
      // Appendix B's vertical dashpot grows without bound as nu approaches 1/2 (incompressible
      // soil: sqrt(2 (1 - nu) / (1 - 2 nu))); the springs and csh do not.
      const bool nu_near_half =
          c.soil.input == SoilInput::modulus && c.soil.nu > 0.49 && coefficient == "csv";
      throw Error(head + "the soil's " + coefficient + " = " +
                      detail::format("%.4g", coefficient == "csh"   ? s.csh
                                             : coefficient == "csv" ? s.csv
                                             : coefficient == "ksh" ? s.ksh
                                                                    : s.ksv) +
                      " from " + from + " makes it so, at roller.f = " + num(R.f) +
                      " Hz: give a plausible soil" +
                      (nu_near_half ? " (soil.nu near 1/2: soils have about 0.2-0.45)" : ""),
                  nu_near_half ? "soil.nu" : "soil.G", nu_near_half ? c.soil.nu : c.soil.G);
    }
    const std::string key = mass ? "roller.m" : r.key;
    const double value = find_field(key)->get(c);
    throw Error(head + key + " = " + num(value) + " makes it so: give a plausible value", key,
                value);
  }
}

}  // namespace

Model::Model(const Case& c) : case_(c) {
  validate(c);
  const Roller& R = c.roller;
  geometry_ = TroughGeometry{c.trough.shape, R.r};
  friction_ = friction_law(c.contact);
  cone_ = cone_coefficient(friction_);
  phases_ = oscidrum::friction_phases(friction_);
  // The one conversion of the soil input (Table 2, Appendix B or as given) into the coefficients.
  SoilCoefficients s = soil_coefficients(c.soil, R);
  check_time_scales(c, s);
  ksh_ = s.ksh;
  ksv_ = s.ksv;
  csh_ = s.csh;
  csv_ = s.csv;
  Fz_ = R.P0 - R.m * R.g;  // (7)
  W_ = R.m * R.g + Fz_;    // the vertical load on the drum, = P0
  // The trough must be measurably larger than the drum: with a clearance (curvature radius at
  // the bottom minus r) far below the static soil deflection, the rolling relation (11)
  // degenerates (f5(0) = curvature radius / r - 1 -> 0 divides the stick equation) and no
  // integrator can follow the drum. 1 % of the deflection W / (ksv + kd) is far below any trough a
  // drum digs (the paper's smallest clearance, 3 mm, is over 10 times the deflection).
  const double clearance = curvature_radius_at_bottom(geometry_.shape) - R.r;
  const double deflection = W_ / (s.ksv + R.kd);
  if (clearance < 0.01 * deflection)
    throw Error("trough: the clearance between trough and drum, " +
                std::string(curvature_radius_formula(geometry_.shape)) + " - roller.r = " +
                num(clearance) + " m, must be at least 1 % of the static soil deflection W / " +
                "(ksv + kd) = " + num(deflection) + " m (W = roller.P0 = " + num(W_) +
                " N, ksv = " + num(s.ksv) + " N/m, kd = roller.kd = " + num(R.kd) +
                " N/m: is one of them in the wrong unit?): a trough of the drum's own size makes "
                "the rolling relation (11) degenerate");
  nu_ = 2.0 * M_PI * R.f;
  // The vibratory drum has no oscillation moment: its excitation is the unbalance force.
  const bool vibratory = R.type == RollerType::vibratory;
  M0_ = vibratory ? 0.0 : oscillation_moment(R);
  F0_ = vibratory ? R.static_moment * nu_ * nu_ : 0.0;
  // Each input finite, their product not (roller.unbalance = 1e308 gave M0 = inf and a run that
  // ended non_finite, exit 1).
  if (!std::isfinite(M0_))
    throw Error("roller.unbalance = " + num(R.unbalance) + " kg m^2 at roller.f = " + num(R.f) +
                    " Hz gives M0 = 4 m_u e_u e_w nu^2 (5) beyond double precision; real "
                    "oscillation rollers have about 0.1-0.5 kg m^2 (the paper's 0.22877)",
                "roller.unbalance", R.unbalance);
  if (!std::isfinite(F0_))
    throw Error("roller.static_moment = " + num(R.static_moment) + " kg m at roller.f = " +
                    num(R.f) + " Hz gives the force F0 = m_u e_u nu^2 beyond double precision",
                "roller.static_moment", R.static_moment);
  // Default (the paper): kd acts on z_M measured from t = 0, so at rest the suspension carries
  // part of the load. Variant: measure it from the static equilibrium s_A = W / ksv.
  z_ref_ = c.numerics.suspension_from_static ? W_ / ksv_ : 0.0;
  ramp_end_ = c.numerics.start_ramp_periods / R.f;
}

// The bodies of torque() and excitation_angle(), inlined into excitation()'s loop as well.
inline double Model::torque_at(double t) const {
  // (5), (6); without an oscillating torque (the vibratory drum: M0 = 0) no sine to evaluate.
  // sin(nu t) with the phase in turns, f t (util/small_angle.hpp).
  const double MM = (M0_ == 0.0 ? 0.0 : M0_ * detail::sin_turns(case_.roller.f * t)) + case_.MMd;
  if (!(t < ramp_end_)) return MM;
  // A gentler start from rest: the excitation ramped in (docs/periodic.md).
  return MM * 0.5 * (1.0 - std::cos(M_PI * t / ramp_end_));
}

inline double Model::excitation_angle_at(double t) const {
  // In turns, as the excitation itself (torque): f t - floor(f t) is exact, so only f t and the
  // final product are rounded (about 1e-13 rad after a thousand periods, as fmod(nu t, 2 pi)
  // gives, at a fifth of fmod's cost in every output row).
  const double turns = case_.roller.f * t;
  const double angle = (turns - std::floor(turns)) * (2.0 * M_PI);
  return angle < 2.0 * M_PI ? angle : 0.0;  // a fraction just below 1 may round up to 2 pi
}

double Model::torque(double t) const { return torque_at(t); }

double Model::excitation_angle(double t) const { return excitation_angle_at(t); }

void Model::excitation(const double* t, int n, double* MM, double* angle, CentreLoad* load) const {
  // Lanes of kLanes times (util/lanes.hpp): the reductions of torque_at's and
  // excitation_angle_at's turns and both series in every lane, the quarter's choice per lane;
  // the same operations as theirs, so the same bits. A single time, times at or before 0, in the
  // start ramp, of more than 2^51 turns, or of an exciter's load take the scalar functions.
  constexpr int kLanes = 8;
  constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52: round_to_integer's
  constexpr double kHalfPi = 0.5 * 3.14159265358979323846;
  using L = detail::Lanes<kLanes>;
  const double f = case_.roller.f;
  for (int i0 = 0; i0 < n; i0 += kLanes) {
    const int m = std::min(kLanes, n - i0);
    L turns;
    bool lanes = m > 1 && M0_ != 0.0 && F0_ == 0.0;  // one time (a single sample): scalar
    for (int j = 0; j < kLanes; ++j) {
      const double tj = t[i0 + std::min(j, m - 1)];
      turns[j] = f * tj;
      lanes = lanes && tj > 0.0 && !(tj < ramp_end_) && turns[j] < 2251799813685248.0;
    }
    if (!lanes) {
      for (int i = i0; i < i0 + m; ++i) {
        MM[i] = torque_at(t[i]);
        angle[i] = excitation_angle_at(t[i]);
        load[i] = F0_ == 0.0 ? CentreLoad{0.0, W_} : centre_load(t[i]);
      }
      continue;
    }
    const L nearest = (turns + kShift) - kShift;  // round_to_integer
    const L quarters = 4.0 * (turns - nearest);   // turns_series::reduce
    const L q = (quarters + kShift) - kShift;
    const L x = (quarters - q) * kHalfPi;
    const L sine = detail::turns_series::sin_series(x),
            cosine = detail::turns_series::cos_series(x);
    for (int j = 0; j < m; ++j) {
      const int quarter = static_cast<int>(q[j]);  // sin_turns' choice
      const double sin_nu_t = quarter == 0    ? sine[j]
                              : quarter == 1  ? cosine[j]
                              : quarter == -1 ? -cosine[j]
                                              : -sine[j];
      MM[i0 + j] = M0_ * sin_nu_t + case_.MMd;
      // floor(turns) from the nearest integer: exact below 2^51 turns (turns > 0 here).
      const double below = nearest[j] > turns[j] ? nearest[j] - 1.0 : nearest[j];
      const double a = (turns[j] - below) * (2.0 * M_PI);
      angle[i0 + j] = a < 2.0 * M_PI ? a : 0.0;
      load[i0 + j] = CentreLoad{0.0, W_};
    }
  }
}

CentreLoad Model::centre_load(double t) const {
  if (F0_ == 0.0) return {0.0, W_};
  double scale = F0_;
  if (t < ramp_end_) scale *= 0.5 * (1.0 - std::cos(M_PI * t / ramp_end_));
  const Exciter e = case_.roller.exciter;
  // The unbalance's angle nu t from +x towards +z, in turns.
  const auto [s, c] = detail::sincos_turns(case_.roller.f * t);
  const double Fx = e == Exciter::vertical ? 0.0 : c * scale;
  return {e == Exciter::circular_reversed ? -Fx : Fx, W_ + s * scale};
}

State Model::initial_state() const {
  State q;
  // At rest at the bottom (delta = 0, z_roll = 0): (ksv + kd) s_A = W + kd z_ref, from (31).
  q.s_A = (W_ + kd() * z_ref_) / (ksv_ + kd());
  return q;
}

}  // namespace oscidrum
