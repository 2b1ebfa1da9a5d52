// Identification of the soil from measured accelerations (identify.hpp, docs/identify.md): the
// start, the fit (solver.hpp) of the problem (problem.hpp), and what the fit says about the
// unknowns (statistics.hpp).
#include "oscidrum/identify.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "identify/problem.hpp"
#include "identify/solver.hpp"
#include "identify/statistics.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/record_reader.hpp"
#include "oscidrum/soil.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

using detail::Problem;
using detail::Unknown;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
std::string num(double v) { return detail::shortest(v); }

void check_input(const MeasuredResponse& data, const IdentifyOptions& o) {
  detail::check_gain_uncertainty(o.gain_uncertainty);
  if (!(std::isfinite(data.f) && data.f > 0))
    throw Error("identify: f must be > 0 [Hz]; got " + num(data.f));
  if (o.harmonics < 1 || static_cast<int>(data.ddx.size()) < o.harmonics ||
      static_cast<int>(data.ddz.size()) < o.harmonics)
    throw Error("identify: the harmonics compared (harmonics, --compare) must be in [1, " +
                std::to_string(std::min(data.ddx.size(), data.ddz.size())) +
                "] (the harmonics measured in the window: --harmonics, by default as many as "
                "its sampling resolves); got " +
                std::to_string(o.harmonics));
  // A channel with no signal and no noise at all: one value in every sample of the window.
  const auto dead = [](const std::vector<std::complex<double>>& c, double noise) {
    return noise == 0.0 &&
           std::all_of(c.begin(), c.end(), [](std::complex<double> v) { return v == 0.0; });
  };
  for (const bool x : {true, false})
    if (!((x ? data.sigma_x : data.sigma_z) > 0) &&
        dead(x ? data.ddx : data.ddz, x ? data.noise_x : data.noise_z))
      throw Error("identify: " + detail::dead_channel(x, "the window"));
  if (!(data.sigma_x > 0 && data.sigma_z > 0))
    throw Error("identify: the uncertainties of the measured harmonics must be > 0");
}

// The point p with its soil unknowns (G, or ksh and ksv) at the soil of shear modulus G [Pa].
Eigen::VectorXd soil_point(const Problem& pr, const IdentifyOptions& o, Eigen::VectorXd p,
                           double G) {
  if (o.modulus) {
    p[0] = std::log(G);
  } else {
    const SoilCoefficients s =
        soil_coefficients(G, pr.base().soil.nu, pr.base().soil.rho, pr.base().roller);
    p[0] = std::log(s.ksh);
    p[1] = std::log(s.ksv);
  }
  return p;
}

// A poor fit may be a local minimum of the misfit: the x_M'' of a stiff soil hardly depends on G
// (a record of G = 200 MN/m^2 fitted as 11 MN/m^2 from the start's grid, which ends at 128). The
// whole of a wide grid, G = 2, 4, ..., 1024 MN/m^2 (within the unknowns' bounds), with the fit's
// other unknowns: the best point that beats the fit, or nothing.
std::optional<Eigen::VectorXd> better_grid_point(Problem& pr, const IdentifyOptions& o,
                                                 const detail::Fit& fit) {
  std::optional<Eigen::VectorXd> best;
  double best_S = fit.S;
  for (double G = 2e6; G <= 1024e6; G *= 2.0) {
    const Eigen::VectorXd p = soil_point(pr, o, fit.p, G);
    bool inside = true;
    for (Eigen::Index j = 0; j < (o.modulus ? 1 : 2); ++j)
      inside = inside && p[j] >= pr.bounds()[static_cast<std::size_t>(j)].lo &&
               p[j] <= pr.bounds()[static_cast<std::size_t>(j)].hi;
    if (!inside) continue;
    Eigen::VectorXd r;
    if (!pr.residual(p, r)) continue;
    if (r.squaredNorm() < best_S) {
      best_S = r.squaredNorm();
      best = p;
    }
  }
  return best;
}

// The start: the previous window's estimate, else the best of a coarse scan of the soil.
Eigen::VectorXd start_point(Problem& pr, const IdentifyOptions& o, const Identification* start) {
  Eigen::VectorXd p0 = pr.internal_of(start ? start->fitted : pr.base());
  if (start && o.fit_mu && start->fitted.contact.pure_rolling) p0 = pr.internal_of(pr.base());
  if (start) return p0;
  double best = std::numeric_limits<double>::infinity();
  Eigen::VectorXd best_p = p0;
  // With mu unknown, the scan is made at the case's mu and at the largest mu (a drum that
  // does not slip): a record of a rolling drum is far from any slipping response.
  std::vector<Eigen::VectorXd> starts{p0};
  for (std::size_t j = 0; j < pr.unknowns().size(); ++j) {
    if (pr.unknowns()[j] != Unknown::mu) continue;
    Eigen::VectorXd p = p0;
    p[static_cast<Eigen::Index>(j)] = pr.bounds()[j].hi;
    starts.push_back(p);
  }
  // The grid G = 4, 8, ..., 128 MN/m^2 walked downhill from 16 and 32 MN/m^2 (downhill_on_grid):
  // the grid's best point wherever its residuals have one minimum on it, without the runs from
  // rest on the far side (a run at 128 MN/m^2 took 3.7 times the steps of one at 4 in
  // bench_identify: the stiffer soil's faster modes).
  constexpr std::array<double, 6> kGrid{4e6, 8e6, 16e6, 32e6, 64e6, 128e6};
  for (const Eigen::VectorXd& p_start : starts) {
    auto point = [&](std::size_t k) { return soil_point(pr, o, p_start, kGrid[k]); };
    const detail::GridMinimum m = detail::downhill_on_grid(kGrid.size(), [&](std::size_t j) {
      Eigen::VectorXd r;
      return pr.residual(point(j), r) ? r.squaredNorm() : std::numeric_limits<double>::infinity();
    });
    if (m.S < best) {
      best = m.S;
      best_p = point(m.k);
    }
  }
  if (!std::isfinite(best))
    throw Error("identify: the model fails for every start (G = 4 ... 128 MN/m^2)");
  return best_p;
}

std::string poor_fit_warning(const Identification& id, const IdentifyOptions& o) {
  return "poor fit: reduced chi^2 " + num(std::round(id.reduced_chi2 * 10) / 10) + " > " +
         num(o.max_reduced_chi2) + " (relative residual " +
         num(std::round(id.relative_residual * 1000) / 1000) +
         "): the model does not reproduce the measured harmonics to their noise, and the "
         "estimates are biased by what it lacks" +
         (o.diagnose ? std::string(" (the next warning names the likely cause)")
                     : std::string(" (an unknown not fitted, such as mu or MMd, or a case that "
                                   "does not describe the roller)"));
}

// A poor fit: what causes it? Each cause that can be checked is fitted from the same coarse start
// (no profile): an axis read the other way round (x_M'', z_M'' or both negated), G on the other
// scale, the accelerations in another unit (g for m/s^2 or the other way round), the two axes
// exchanged (with either sign), and mu and MMd fitted when they are not. One that fits (a reduced
// chi^2 within the limit, or ten times below the fit's) is named with what to change; otherwise the
// warning lists what was checked and what remains (the roller, the window's own fit). Costs a few
// fits, only when the fit is poor.
std::vector<std::string> diagnosis(const Case& base, const MeasuredResponse& data,
                                   const IdentifyOptions& o, double s2, long steps) {
  struct Alternative {
    bool x = false, z = false, other_scale = false, mu = false, MMd = false;
    double units = 1.0;  // the record's accelerations times this (g: it was in g)
    bool swap = false;   // x_M'' and z_M'' exchanged (before x and z are negated)
  };
  std::vector<Alternative> alternatives = {
      {false, true, false}, {true, false, false}, {true, true, false}, {false, false, true},
      {false, true, true},  {true, false, true},  {true, true, true}};
  // The unit of the accelerations (a logger's g read as m/s^2, or m/s^2 read as g), alone and with
  // the axes a logger in g often has the other way round.
  for (const double u : {kStandardGravity, 1.0 / kStandardGravity})
    for (const auto& [x, z] : {std::pair{false, false}, {false, true}, {true, true}})
      alternatives.push_back({x, z, false, false, false, u});
  // A logger's milli-g read as m/s^2 (`--units mg` reads it; without a unit in its header the
  // record read 102 times too large and the diagnosis named no cause).
  alternatives.push_back({false, false, false, false, false, 1e-3 * kStandardGravity});
  // The two axes exchanged (a logger turned by 90 degrees about the axle, or its columns named
  // the other way round: the record's x_M'' then holds the even harmonics of z_M''), with each
  // sign the turn may leave.
  for (const auto& [x, z] : {std::pair{false, false}, {false, true}, {true, false}, {true, true}})
    alternatives.push_back({x, z, false, false, false, 1.0, true});
  if (!o.fit_mu) alternatives.push_back({false, false, false, true, false});
  if (!o.fit_MMd) alternatives.push_back({false, false, false, false, true});
  auto describe = [&](const Alternative& a) {
    std::string what, advice;
    // Each axis the other way from how it was read.
    const std::string x_to = o.x_read_backward ? "forward" : "backward",
                      x_was = o.x_read_backward ? "backward" : "forward",
                      z_to = o.z_read_up ? "down" : "up", z_was = o.z_read_up ? "up" : "down";
    if (a.x && a.z) {
      what = "x_M'' and z_M'' negated";
      advice = "both axes of the record point the other way (x " + x_to + ", z " + z_to + ", not " +
               x_was + " and " + z_was + " as read): read it with --x-positive " + x_to +
               " --z-positive " + z_to + " (Python: x_positive='" + x_to + "', z_positive='" +
               z_to + "')";
    } else if (a.z) {
      what = "z_M'' negated";
      advice = "the record's z axis points " + z_to + ", not " + z_was +
               " as read: read it with --z-positive " + z_to + " (Python: z_positive='" + z_to +
               "')";
    } else if (a.x) {
      what = "x_M'' negated";
      advice = "the record's x axis points " + x_to + ", not " + x_was +
               " as read: read it with --x-positive " + x_to + " (Python: x_positive='" + x_to +
               "')";
    }
    if (a.swap) {
      what = "x_M'' and z_M'' exchanged" + (what.empty() ? "" : " and " + what);
      advice =
          "the record's x and z channels are the other way round (a logger turned by 90 "
          "degrees about the axle, or its columns named so): read it with --x-col and "
          "--z-col naming each other's column (Python: pass ddx_M and ddz_M the other way "
          "round)" +
          (advice.empty() ? "" : "; then " + advice);
    }
    if (a.units != 1.0) {
      const bool in_g = a.units > 1.0, in_mg = a.units < 0.05;
      what = std::string(in_mg  ? "the accelerations read as mg (x 0.00980665)"
                         : in_g ? "the accelerations read as g (x 9.80665)"
                                : "the accelerations read as m/s^2 (/ 9.80665)") +
             (what.empty() ? "" : " and " + what);
      advice = std::string(in_mg  ? "the record's accelerations are in mg (thousandths of g), not "
                                    "m/s^2: read it with --units mg (Python: multiply them by "
                                    "0.00980665)"
                           : in_g ? "the record's accelerations are in g, not m/s^2: read it with "
                                    "--units g (Python: multiply them by 9.80665)"
                                  : "the record's accelerations are in m/s^2, not g: read it "
                                    "with --units m/s2 (Python: divide them by 9.80665)") +
               (advice.empty() ? "" : "; " + advice);
    }
    if (a.other_scale) {
      what += std::string(what.empty() ? "" : " and ") + "G on the other soil scale";
      advice += std::string(advice.empty() ? "" : "; ") +
                (o.soil_scale == SoilScale::formulas
                     ? "the soil is a Table 2 soil (what run --G simulates): --soil-scale table2"
                     : "the soil follows Appendix B's formulas: --soil-scale formulas");
    }
    if (a.mu) {
      what = "mu fitted too";
      advice = "the friction coefficient is not the case's mu = " + num(base.contact.mu) +
               (base.contact.pure_rolling ? " (pure rolling)" : "") +
               ": estimate it with --fit-mu (Python: fit_mu=True)";
    }
    if (a.MMd) {
      what = "MMd fitted too";
      advice = "the driving torque is not the case's MMd = " + num(base.MMd) +
               " N m: estimate it with --fit-MMd (Python: fit_MMd=True)";
    }
    return std::pair{what, advice};
  };
  auto sig3 = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return std::string(buf);
  };
  double best = std::max(o.max_reduced_chi2, s2 / 10.0);
  std::string found, found_change, found_advice;
  std::vector<std::pair<double, std::string>> checked;  // reduced chi^2, what was changed
  for (const Alternative& a : alternatives) {
    if (a.other_scale && !o.modulus) continue;
    IdentifyOptions o2 = o;
    o2.profile = false;
    o2.fit_mu = o.fit_mu || a.mu;
    o2.fit_MMd = o.fit_MMd || a.MMd;
    if (a.other_scale)
      o2.soil_scale = o.soil_scale == SoilScale::formulas ? SoilScale::table2 : SoilScale::formulas;
    const auto [what, advice] = describe(a);
    try {
      const MeasuredResponse read_so =
          detail::scaled(detail::flipped(a.swap ? detail::swapped(data) : data, a.x, a.z), a.units);
      Problem pr(base, read_so, o2);
      pr.count_steps_in(steps);  // the refits share the window's budget with its fit
      const int dof = pr.rows() - static_cast<int>(pr.unknowns().size()) - 1;
      if (dof < 1) continue;
      const std::vector<bool> all(pr.unknowns().size(), true);
      detail::Fit fit =
          detail::levenberg_marquardt(pr, start_point(pr, o2, nullptr), all, o2.max_iterations);
      // Compared as the window's own fit was (identify()): a window sampled in step is fitted
      // with the model sampled at its times too, the better kept. Its raw samples alias, and
      // the harmonics alone would leave a poor fit where the change named fits exactly.
      if (std::isfinite(fit.S) && detail::has_sampling_map(read_so, o2.harmonics)) {
        std::optional<Problem> sampled;
        sampled.emplace(base, read_so, o2, detail::Comparison::sampled);
        sampled->count_steps_in(steps);
        (void)detail::keep_the_better(sampled, fit, all, o2.max_iterations);
      }
      const double chi2 = fit.S / dof;
      // The list of what was checked: each single change (x alone is a time shift, see below).
      if (std::isfinite(chi2) && (a.x ? a.z && !a.other_scale : !(a.z && a.other_scale)) &&
          ((a.units == 1.0 && !a.swap) || (!a.x && !a.z)))
        checked.push_back({chi2, what});
      // The alternatives come simplest first (one change, then two, three); a later one must fit
      // clearly better (half the chi^2) to replace an earlier: with no driving torque, negating
      // x_M'' is the same as shifting time by half a period, and x alone changes nothing. mu and
      // MMd come last: an unknown more always fits a little better.
      if (std::isfinite(chi2) && chi2 < (found.empty() ? best : 0.5 * best)) {
        best = chi2;
        found_change = "the fit is far better with " + what + " (reduced chi^2 " + sig3(chi2) +
                       " against " + sig3(s2) + ")";
        found_advice = advice;
        found = found_change + ": " + advice;
      }
    } catch (const Error&) {
      // an alternative the model cannot fit says nothing
    }
  }
  // What was checked, most likely first (the lowest chi^2), and what remains.
  std::sort(checked.begin(), checked.end());
  std::string list;
  for (const auto& [chi2, what] : checked)
    list += (list.empty() ? "" : "; ") + what + ": " + sig3(chi2);
  std::string remaining =
      "a roller that differs from the case (its unbalance, axle load, buffers: calibrate it on "
      "records of known soil with oscidrum calibrate)";
  // The window's own fit: a residual that is a sizeable part of the signal means harmonics
  // beyond those fitted, or a signal that is not periodic at f (a soil or a frequency that
  // changes within the window).
  double signal2 = 0;
  for (const auto& c : data.ddx) signal2 += 0.5 * std::norm(c);
  for (const auto& c : data.ddz) signal2 += 0.5 * std::norm(c);
  const double noise2 = data.noise_x * data.noise_x + data.noise_z * data.noise_z;
  if (signal2 > 0 && noise2 > 0) {
    const double ratio = std::sqrt(noise2 / signal2);
    remaining +=
        "; the window's fit of " + std::to_string(data.ddx.size()) +
        " harmonics leaves a residual of " + sig3(100 * ratio) + " % of the signal's RMS" +
        (ratio > 0.1 ? " (a large part: more harmonics than fitted (--harmonics), or a soil or "
                       "frequency that changes within the window: a shorter --window)"
                     : " (small: the window's signal is periodic at f and well resolved)");
  }
  if (!found.empty() && best <= o.max_reduced_chi2) return {found};
  // Still poor with the change: it need not be the cause (a roller that differs from the case
  // fits better with mu fitted too, and the advice said the case's mu was wrong, where it was
  // the truth).
  if (!found.empty())
    return {found_change + ", but it still fits poorly (reduced chi^2 " + sig3(best) + " > " +
            num(o.max_reduced_chi2) + "), so that alone does not explain the record (were it " +
            "the cause: " + found_advice + "): checked, best first: " + list +
            ". Other causes: " + remaining};
  if (checked.empty())  // every refit failed: the window's budget spent, or no model fits
    return {"no cause of the poor fit could be checked: the model failed on every refit (" +
            std::string(steps < detail::kMaxStepsPerWindow
                            ? "no steady state for any of them"
                            : "the window's model runs had used up their budget of " +
                                  std::to_string(detail::kMaxStepsPerWindow) +
                                  " integration steps: the model hardly settles for "
                                  "this roller; check its parameters") +
            "). Remaining causes: " + remaining};
  return {
      "none of the causes checked explains the poor fit (reduced chi^2 with each, best "
      "first: " +
      list + "). Remaining causes: " + remaining};
}

// The estimate of unknown j with its linearised uncertainty and its profile interval.
Estimate estimate_of(Problem& pr, const detail::Fit& fit, std::size_t j, double se, double c,
                     double s2, bool profile, std::vector<std::string>& warnings) {
  const Unknown kind = pr.unknowns()[j];
  const double pj = fit.p[static_cast<Eigen::Index>(j)];
  Estimate e;
  e.name = detail::name_of(kind);
  e.unit = detail::unit_of(kind);
  e.value = detail::to_physical(kind, pj, pr.M0());
  e.standard_uncertainty = kind == Unknown::MMd ? se * pr.M0() : e.value * se;  // d exp(p)
  e.lower = e.upper = kNaN;
  if (!profile) return e;
  if (!std::isfinite(se)) {
    // No effect on the fit: nothing to profile; the parameter is not identifiable.
    e.lower_open = e.upper_open = true;
    return e;
  }
  for (const int side : {-1, 1}) {
    const detail::ProfileLimit limit = detail::profile_limit(pr, fit, j, side, se, c, s2);
    if (limit.model_fails) {
      // Where the model fails, the data have not excluded anything: that is no limit.
      const double at = detail::to_physical(kind, limit.last_good, pr.M0());
      warnings.push_back("no 95 % " + std::string(side < 0 ? "lower" : "upper") + " limit of " +
                         e.name + ": the profile stays below it up to " + e.name + " = " + num(at) +
                         " and the model fails beyond (" +
                         (limit.failure.empty() ? std::string("no steady state") : limit.failure) +
                         ")");
    } else if (std::isfinite(limit.at)) {
      (side < 0 ? e.lower : e.upper) = detail::to_physical(kind, limit.at, pr.M0());
    }
    if (limit.open) {
      (side < 0 ? e.lower_open : e.upper_open) = true;
      warnings.push_back("flat profile: " + e.name +
                         (side < 0 ? " has no lower" : " has no upper") +
                         " 95 % limit within its range; it is not identifiable from these data");
    }
  }
  return e;
}

}  // namespace

const char* to_string(SoilScale scale) {
  switch (scale) {
    case SoilScale::formulas:
      return "formulas";
    case SoilScale::table2:
      return "table2";
  }
  return "";
}

SoilScale soil_scale_from(const std::string& name, const std::string& what) {
  if (name == "formulas") return SoilScale::formulas;
  if (name == "table2") return SoilScale::table2;
  throw Error(what + " must be formulas (Appendix B (42)-(45)) or table2 (the paper's Table 2, " +
                  "interpolated); got '" + name + "'",
              what);
}

Soil soil_on_scale(double G, SoilScale scale, const Soil& base) {
  const double lo = scale == SoilScale::table2 ? kTable2InterpolatedMin : 1e5;
  const double hi = scale == SoilScale::table2 ? kTable2InterpolatedMax : 2e9;
  if (!(G >= lo && G <= hi))
    throw Error("G must be in [" + num(lo / 1e6) + ", " + num(hi / 1e6) + "] MN/m^2 on the " +
                    to_string(scale) + " scale; got " + num(G / 1e6) + " MN/m^2",
                "G", G);
  Soil s = base;
  s.G = G;
  if (scale == SoilScale::table2) {
    const SoilCoefficients k = table2_coefficients(G);
    s.input = SoilInput::coefficients;
    s.ksh = k.ksh;
    s.ksv = k.ksv;
    s.csh = k.csh;
    s.csv = k.csv;
  } else {
    s.input = SoilInput::modulus;
  }
  return s;
}

namespace {

// identify() with the window's model runs counted in `steps` (kMaxStepsPerWindow), when given:
// the refits of readings left open share the window's budget with its fit, as the diagnosis's
// refits do. (A roller whose model hardly settles spends the budget on the fit as read; each
// reading then fails at once instead of spending a budget of its own.)
Identification identify_in(const Case& base, const MeasuredResponse& data, const IdentifyOptions& o,
                           const Identification* start, long* steps) {
  check_input(data, o);
  Problem plain(base, data, o);
  if (steps != nullptr) plain.count_steps_in(*steps);
  const std::size_t q = plain.unknowns().size();
  const int dof = plain.rows() - static_cast<int>(q) - 1;  // - 1: the time shift
  if (dof < 1)
    throw Error("identify: " + std::to_string(plain.rows()) + " measured values are too few for " +
                std::to_string(q) + " unknowns and the time shift; use more --harmonics");
  const std::vector<bool> all(q, true);

  detail::Fit fit =
      detail::levenberg_marquardt(plain, start_point(plain, o, start), all, o.max_iterations);
  if (!std::isfinite(fit.S)) throw Error("identify: " + fit.message);
  if (fit.S / dof > o.max_reduced_chi2) {
    if (const auto p = better_grid_point(plain, o, fit)) {
      detail::Fit again = detail::levenberg_marquardt(plain, *p, all, o.max_iterations);
      if (again.S < fit.S) fit = std::move(again);
    }
  }
  // A window sampled in step with the excitation (data.alias_t): its raw samples alias the
  // harmonics above those fitted onto the compared ones the same way in every period, a bias of
  // about 1e-3 of A_1 at 64 samples a period (G off by 0.06-1.6 % and the fit poor, noise-free:
  // tests/identify, ARecordSampledInStepWithTheExcitation), which a logger's anti-aliasing filter
  // would have removed. Which of the two the record is, its fit tells: the model sampled at the
  // record's times is fitted too, from the estimate, and the better fit kept (the same estimate
  // to within the noise where the aliases are below it).
  std::optional<Problem> sampled;
  int other_simulations = 0;  // of a sampled comparison not kept
  if (detail::has_sampling_map(data, o.harmonics)) {
    sampled.emplace(base, data, o, detail::Comparison::sampled);
    sampled->count_steps_in(plain.steps_counter());
    other_simulations = detail::keep_the_better(sampled, fit, all, o.max_iterations);
  }
  Problem& pr = sampled ? *sampled : plain;

  Identification id;
  id.model_sampled = sampled.has_value();
  id.f = data.f;
  id.measured = data;
  id.converged = fit.converged;
  id.message = fit.message;
  id.iterations = fit.iterations;
  double phi = 0;
  Eigen::VectorXd r;
  pr.residual(fit.p, r, phi);
  // The model's harmonics times e^{i n phi} are the measured ones about t_ref: record time
  // t_ref + s is model time s + phi / (2 pi f), i.e. record time = model time + tau with
  // tau = t_ref - phi / (2 pi f), taken in [0, 1/f).
  const double T = 1.0 / data.f;
  const double tau = std::fmod(data.t_ref, T) - phi / (2.0 * M_PI * data.f);
  id.time_shift = tau - T * std::floor(tau / T);
  const double s2 = fit.S / dof;
  id.reduced_chi2 = s2;
  id.fitted = pr.case_at(fit.p);
  id.simulated = pr.simulate_at(fit.p).metrics;
  std::vector<std::complex<double>> cx, cz;
  pr.compared(pr.simulate_at(fit.p), phi, cx, cz);
  const detail::HarmonicMisfit misfit = detail::harmonic_misfit(cx, cz, data, o.harmonics);
  id.rms_residual = misfit.rms;
  id.relative_residual = misfit.relative;
  if (s2 > o.max_reduced_chi2 && (o.z_open || o.units_open)) {
    // Nothing said which way the record's z axis points (an accelerometer mounted z up whose
    // gravity the logger removed; most mounts point up), or in what unit its accelerations are
    // (columns without one, read as m/s^2; loggers often write g), and as read the model misses
    // them: the readings left open are fitted too, simplest first, and the first that fits is
    // taken, with a warning.
    struct Reading {
      bool z_negated = false;
      bool in_g = false;
    };
    std::vector<Reading> readings;
    if (o.z_open) readings.push_back({true, false});
    if (o.units_open) readings.push_back({false, true});
    if (o.z_open && o.units_open) readings.push_back({true, true});
    IdentifyOptions as_given = o;
    as_given.z_open = false;
    as_given.units_open = false;
    as_given.diagnose = false;
    int simulations =
        plain.simulations() + (sampled ? sampled->simulations() : 0) + other_simulations;
    for (const Reading& rd : readings) {
      try {
        Identification other =
            identify_in(base,
                        detail::scaled(detail::flipped(data, false, rd.z_negated),
                                       rd.in_g ? kStandardGravity : 1.0),
                        as_given, start, &plain.steps_counter());
        simulations += other.simulations;
        if (!(other.reduced_chi2 <= o.max_reduced_chi2)) continue;
        other.z_negated = rd.z_negated;
        other.read_in_g = rd.in_g;
        other.simulations = simulations;
        other.warnings.insert(
            other.warnings.begin(),
            detail::open_reading_warning(rd.z_negated, rd.in_g, other.reduced_chi2, s2, ""));
        return other;
      } catch (const Error&) {
        // a reading the model cannot fit: the next one
      }
    }
  }
  // The uncertainties grow with the residual (s^2 below), but a bias does not show in them.
  if (s2 > o.max_reduced_chi2) {
    id.warnings.push_back(poor_fit_warning(id, o));
    if (o.diagnose)
      for (std::string& why : diagnosis(base, data, o, s2, pr.steps()))
        id.warnings.push_back(std::move(why));
  }

  // Covariance s^2 (J^T J)^-1, condition number and correlations of the column-scaled Jacobian.
  Eigen::MatrixXd J;
  Eigen::VectorXd se = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(q), kNaN);
  const bool have_J = fit.J.rows() == r.size() && fit.last_step < 1e-3;  // close enough: reuse
  if (have_J) J = fit.J;
  if (have_J || detail::jacobian(pr, fit.p, r, all, J)) {
    std::vector<std::string> names;
    for (const Unknown k : pr.unknowns()) names.push_back(detail::name_of(k));
    detail::LinearisedUncertainty u =
        detail::linearised_uncertainty(J, s2, names, o.max_condition, o.max_correlation);
    id.condition = u.condition;
    se = u.se;
    id.warnings.insert(id.warnings.end(), u.warnings.begin(), u.warnings.end());
  } else {
    id.warnings.push_back("the model fails next to the estimate: no uncertainties");
  }

  // Profile intervals: S_profile(p_j) = S_min + s^2 t^2 (two-sided 95 %, dof degrees of freedom).
  const double c = detail::t_quantile(dof);
  for (std::size_t j = 0; j < q; ++j)
    id.estimates.push_back(
        estimate_of(pr, fit, j, se[static_cast<Eigen::Index>(j)], c, s2, o.profile, id.warnings));
  // The channels' gain uncertainty (a sensor's calibration): each channel's gain one standard
  // uncertainty off, refitted from the estimate; the changes, in quadrature over the two
  // independent channels, widen the standard uncertainty and the interval in quadrature. The
  // interval is widened in the fit's coordinates (ln G, ln mu, MMd / M0), where the profile
  // limits are found too, and ends at the unknown's bound: in G itself, 5 % of gain on a short
  // window (G shifted by 65 %) put the lower end at -9.8 MN/m^2.
  int gain_simulations = 0;
  if (o.gain_uncertainty > 0.0) {
    const double g = 1.0 + o.gain_uncertainty;
    std::vector<double> shift2(q, 0.0), shift2_internal(q, 0.0);
    bool ok = true;
    for (const bool x : {true, false}) {
      Problem off(base, detail::scaled_channels(data, x ? g : 1.0, x ? 1.0 : g), o,
                  sampled ? detail::Comparison::sampled : detail::Comparison::harmonics);
      off.count_steps_in(plain.steps_counter());
      const detail::Fit refit = detail::levenberg_marquardt(off, fit.p, all, o.max_iterations);
      gain_simulations += off.simulations();
      if (!std::isfinite(refit.S)) {
        ok = false;
        break;
      }
      for (std::size_t j = 0; j < q; ++j) {
        const Unknown kind = pr.unknowns()[j];
        const auto jj = static_cast<Eigen::Index>(j);
        const double d = detail::to_physical(kind, refit.p[jj], pr.M0()) -
                         detail::to_physical(kind, fit.p[jj], pr.M0());
        shift2[j] += d * d;
        const double di = refit.p[jj] - fit.p[jj];
        shift2_internal[j] += di * di;
      }
    }
    if (!ok) {
      id.warnings.push_back("the model fails with a channel's gain " + num(o.gain_uncertainty) +
                            " off: the gain uncertainty is not counted in the uncertainties");
    } else {
      for (std::size_t j = 0; j < q; ++j) {
        Estimate& e = id.estimates[j];
        const double ug = std::sqrt(shift2[j]);
        e.gain_uncertainty = ug;
        e.standard_uncertainty = std::hypot(e.standard_uncertainty, ug);
        // The gains' part of a 95 % interval, in the fit's coordinates.
        const Unknown kind = pr.unknowns()[j];
        const detail::Bounds& range = pr.bounds()[j];
        const double wide = c * std::sqrt(shift2_internal[j]);
        const double v = fit.p[static_cast<Eigen::Index>(j)];
        const auto internal = [&](double x) { return detail::to_internal(kind, x, pr.M0()); };
        const auto physical = [&](double p) { return detail::to_physical(kind, p, pr.M0()); };
        // An open end (the profile flat to the parameter's bound) stays the bound; an end the
        // gains widen beyond the bound becomes an open end at the bound.
        if (std::isfinite(e.lower) && !e.lower_open) {
          const double lo = v - std::hypot(v - internal(e.lower), wide);
          e.lower_open = lo <= range.lo;
          e.lower = physical(std::max(lo, range.lo));
        }
        if (std::isfinite(e.upper) && !e.upper_open) {
          const double hi = v + std::hypot(internal(e.upper) - v, wide);
          e.upper_open = hi >= range.hi;
          e.upper = physical(std::min(hi, range.hi));
        }
      }
    }
  }
  // mu of a drum that does not slip: every mu above the friction the steady state needs gives
  // the same response, whatever the Jacobian or the profile (within the budget) saw.
  const detail::Simulated& at_estimate = pr.simulate_at(fit.p);
  for (Estimate& e : id.estimates) {
    if (e.name != "mu" || !at_estimate.rolling) continue;
    e.upper = kNaN;
    e.upper_open = true;
    id.warnings.push_back(
        "mu is not identifiable: the drum does not slip in the fitted steady "
        "state, which needs mu >= " +
        num(std::round(at_estimate.friction_ratio * 1000) / 1000) +
        "; every larger mu gives the same response");
  }
  id.simulations = plain.simulations() + (sampled ? sampled->simulations() : other_simulations) +
                   gain_simulations;
  // The window's estimator (a few hundred kB) is not kept with each window of a pass.
  id.measured.alias_t.clear();
  id.measured.alias_t.shrink_to_fit();
  id.measured.alias_w.clear();
  id.measured.alias_w.shrink_to_fit();
  return id;
}

}  // namespace

Identification identify(const Case& base, const MeasuredResponse& data, const IdentifyOptions& o,
                        const Identification* start) {
  return identify_in(base, data, o, start, nullptr);
}

std::vector<IdentifiedUnknown> identified_unknowns(const IdentifyOptions& options) {
  std::vector<Unknown> kinds;
  if (options.modulus) {
    kinds = {Unknown::G};
  } else {
    kinds = {Unknown::ksh, Unknown::ksv};
  }
  if (options.fit_mu) kinds.push_back(Unknown::mu);
  if (options.fit_MMd) kinds.push_back(Unknown::MMd);
  std::vector<IdentifiedUnknown> out;
  for (Unknown k : kinds) out.push_back({detail::name_of(k), detail::unit_of(k)});
  return out;
}

}  // namespace oscidrum
