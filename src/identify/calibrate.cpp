// Calibration of the roller on reference records of known soil (calibrate.hpp,
// docs/identify.md): one least-squares problem over all references, each reference's residual
// that of the identification (problem.hpp) with its soil known and its own time shift, the
// unknowns chosen fields of the case on a log scale. Solver and statistics are identify's.
#include "oscidrum/calibrate.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "identify/problem.hpp"
#include "identify/solver.hpp"
#include "identify/statistics.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/record_reader.hpp"
#include "oscidrum/soil.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
std::string num(double v) { return detail::shortest(v); }
std::string sig(double v, int digits) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}
std::string sig3(double v) { return sig(v, 3); }

// The field behind a key of CalibrateOptions::parameters, checked: a real roller, contact or
// trough parameter whose range and value in `base` are positive and that takes effect.
const Field& calibrated_field(const Case& base, const std::string& key) {
  (void)get_field(base, key);  // an unknown key: the field table's message, with a suggestion
  const Field& f = *find_field(key);
  const std::string k = "calibrate: parameter " + key;
  if (key.rfind("soil.", 0) == 0)
    throw Error(k + " is given by each reference (its known soil), not fitted", "parameters");
  if (key == "roller.f")
    throw Error(k + " is each record's own excitation frequency, not fitted", "parameters");
  if (key == "roller.m_f")
    throw Error(k + " enters the Appendix A transmissibility only (oscidrum transmissibility), "
                    "not the drum's motion: it cannot be fitted to records",
                "parameters");
  if (key == "roller.g" || !(key.rfind("roller.", 0) == 0 || key.rfind("contact.", 0) == 0 ||
                             key.rfind("trough.", 0) == 0))
    throw Error(k + " is not a parameter of the roller, the contact or the trough", "parameters");
  if (f.type != FieldType::real)
    throw Error(k + " is not a real number (" + field_rule(f) + ")", "parameters");
  if (f.min < 0)
    throw Error(k + " may be negative (" + field_rule(f) +
                    "); only parameters > 0 are fitted (on a log scale)",
                "parameters");
  if (!key_in_effect(base, key)) throw Error("calibrate: " + key_not_in_effect(base, key));
  if (!(f.get(base) > 0))
    throw Error(k + " is " + num(f.get(base)) + " in the case; its start value must be > 0",
                "parameters");
  return f;
}

// The calibration as a least-squares problem: the unknowns are ln of the fields; the residual
// stacks each reference's weighted residual of the harmonics (problem.hpp), each aligned by its
// own time shift.
class Calibrating : public detail::LeastSquares {
 public:
  struct Point {
    bool ok = false;
    std::string message;
    Eigen::VectorXd r;
    std::vector<ReferenceFit> fits;  // f, tau, misfit and chi^2 share of each reference
  };

  /// `sampled`: the references sampled in step with the excitation (MeasuredResponse::alias_t)
  /// compare the model sampled at their times (Comparison::sampled), the others its harmonics.
  Calibrating(const Case& base, std::span<const Reference> refs, const CalibrateOptions& o,
              bool sampled = false)
      : base_(base), refs_(refs), o_(o), sampled_(sampled) {
    for (const std::string& key : o.parameters) {
      const Field& f = calibrated_field(base, key);
      for (const Field* g : fields_)
        if (g == &f) throw Error("calibrate: parameter " + key + " is given twice", "parameters");
      fields_.push_back(&f);
      const double v = f.get(base);
      double lo = std::log(v / o.range), hi = std::log(v * o.range);
      if (f.min > 0) lo = std::max(lo, std::log(f.min) + (f.min_open ? 1e-12 : 0.0));
      if (std::isfinite(f.max)) hi = std::min(hi, std::log(f.max) - (f.max_open ? 1e-12 : 0.0));
      bounds_.push_back({lo, hi});
      start_.push_back(std::log(v));
    }
    rows_ = 4 * o.harmonics * static_cast<int>(refs.size());
  }

  int rows() const override { return rows_; }
  const std::vector<detail::Bounds>& bounds() const override { return bounds_; }
  bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) override {
    const Point& at = point(p);
    if (at.ok) r = at.r;
    return at.ok;
  }
  std::string failure(const Eigen::VectorXd& p) override { return point(p).message; }

  Eigen::VectorXd start() const {
    return Eigen::Map<const Eigen::VectorXd>(start_.data(),
                                             static_cast<Eigen::Index>(start_.size()));
  }
  const std::vector<const Field*>& fields() const { return fields_; }
  int simulations() const { return simulations_; }

  // The base case with the unknowns at p (throws oscidrum::Error for a value the field refuses).
  Case case_at(const Eigen::VectorXd& p) const {
    Case c = base_;
    for (std::size_t j = 0; j < fields_.size(); ++j)
      set_field(c, fields_[j]->key, std::exp(p[static_cast<Eigen::Index>(j)]));
    return c;
  }

  const Point& point(const Eigen::VectorXd& p) {
    std::vector<double> key(p.data(), p.data() + p.size());
    if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
    Point at;
    try {
      at = evaluate(p);
    } catch (const Error& e) {  // a trial the field table or the model refuses
      at.ok = false;
      at.message = e.what();
    }
    if (cache_.size() > 1024) cache_.clear();
    return cache_.emplace(std::move(key), std::move(at)).first->second;
  }

 private:
  Point evaluate(const Eigen::VectorXd& p) {
    const Case c = case_at(p);
    Point at;
    at.r.resize(rows_);
    Eigen::Index row = 0;
    long steps = 0;  // one budget (kMaxStepsPerWindow) for the runs of one trial point
    for (const Reference& ref : refs_) {
      // The reference's known soil as the discrete coefficients (any soil.input), so that the
      // identification's problem evaluates it as it stands.
      Case ci = c;
      ci.soil = ref.soil;
      const SoilCoefficients s = soil_coefficients(ci.soil, ci.roller);
      ci.soil.input = SoilInput::coefficients;
      ci.soil.ksh = s.ksh;
      ci.soil.ksv = s.ksv;
      ci.soil.csh = s.csh;
      ci.soil.csv = s.csv;
      IdentifyOptions io;
      io.modulus = false;
      io.harmonics = o_.harmonics;
      io.profile = false;
      io.diagnose = false;
      io.model_tolerance = o_.model_tolerance;
      io.shooting = o_.shooting;
      const bool sampled = sampled_ && detail::has_sampling_map(ref.data, o_.harmonics);
      detail::Problem pr(ci, ref.data, io,
                         sampled ? detail::Comparison::sampled : detail::Comparison::harmonics);
      pr.count_steps_in(steps);
      const Eigen::VectorXd soil = pr.internal_of(pr.base());
      Eigen::VectorXd ri;
      double phi = 0;
      const bool ok = pr.residual(soil, ri, phi);
      simulations_ += pr.simulations();
      if (!ok) {
        at.ok = false;
        at.message = "reference " + ref.name + ": " + pr.failure(soil);
        return at;
      }
      at.r.segment(row, ri.size()) = ri;
      row += ri.size();
      ReferenceFit fit;
      fit.name = ref.name;
      fit.f = ref.data.f;
      // As identify: record time = model time + tau, tau = t_ref - phi / (2 pi f) in [0, 1/f).
      const double T = 1.0 / ref.data.f;
      const double tau = std::fmod(ref.data.t_ref, T) - phi / (2.0 * M_PI * ref.data.f);
      fit.time_shift = tau - T * std::floor(tau / T);
      std::vector<std::complex<double>> cx, cz;
      pr.compared(pr.simulate_at(soil), phi, cx, cz);
      const detail::HarmonicMisfit m = detail::harmonic_misfit(cx, cz, ref.data, o_.harmonics);
      fit.rms_residual = m.rms;
      fit.relative_residual = m.relative;
      fit.reduced_chi2 = ri.squaredNorm() / static_cast<double>(ri.size() - 1);
      fit.model_sampled = sampled;
      at.fits.push_back(std::move(fit));
    }
    at.ok = true;
    return at;
  }

  Case base_;
  std::span<const Reference> refs_;
  CalibrateOptions o_;
  bool sampled_ = false;
  std::vector<const Field*> fields_;
  std::vector<detail::Bounds> bounds_;
  std::vector<double> start_;
  int rows_ = 0, simulations_ = 0;
  std::map<std::vector<double>, Point> cache_;
};

void check_input(std::span<const Reference> refs, const CalibrateOptions& o) {
  if (refs.empty()) throw Error("calibrate: give at least one reference record", "references");
  if (o.parameters.empty())
    throw Error("calibrate: give at least one parameter to fit (e.g. roller.M0)", "parameters");
  if (o.harmonics < 1 || o.harmonics > kMaxComparedHarmonics)
    throw Error("calibrate: harmonics must be in [1, " + std::to_string(kMaxComparedHarmonics) +
                    "]; got " + std::to_string(o.harmonics),
                "harmonics");
  if (!(o.range > 1.0 && std::isfinite(o.range)))
    throw Error("calibrate: range must be a finite number > 1; got " + num(o.range), "range");
  for (const Reference& ref : refs) {
    const MeasuredResponse& d = ref.data;
    if (!(std::isfinite(d.f) && d.f > 0))
      throw Error("calibrate: reference " + ref.name + ": f must be > 0 [Hz]; got " + num(d.f));
    if (static_cast<int>(std::min(d.ddx.size(), d.ddz.size())) < o.harmonics)
      throw Error("calibrate: reference " + ref.name + " has " + std::to_string(d.ddx.size()) +
                      " measured harmonics, fewer than the " + std::to_string(o.harmonics) +
                      " compared",
                  "harmonics");
    if (!(d.sigma_x > 0 && d.sigma_z > 0))
      throw Error("calibrate: reference " + ref.name +
                  ": the uncertainties of the measured harmonics must be > 0");
  }
}

}  // namespace

MeasuredResponse measure_record(std::span<const double> t, std::span<const double> ddx_M,
                                std::span<const double> ddz_M, const WindowOptions& windows,
                                const MeasureOptions& measure) {
  // Times from the first sample, as identify_pass takes them (a logger's clock keeps its digits).
  const double t0 = t.empty() ? 0.0 : t.front();
  std::vector<double> local(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) local[i] = t[i] - t0;
  WindowOptions wo = windows;
  wo.window_periods = 0.0;  // the whole record
  wo.hop_periods = 0.0;
  wo.time_origin += t0;     // the reasons quote the record's times
  wo.one_reference = true;  // and advise cutting the record, not window flags calibrate lacks
  const std::vector<RecordWindow> ws = analyze_windows(local, ddx_M, ddz_M, {}, wo);
  if (ws.empty()) throw Error("the record has no window to analyse");
  const RecordWindow& w = ws.front();
  if (!w.valid) throw Error("the record fails a quality gate: " + w.reason);
  detail::require_live_channels(ddx_M.subspan(w.first, w.count), ddz_M.subspan(w.first, w.count),
                                "the record");
  const std::span<const double> tw = std::span<const double>(local).subspan(w.first, w.count);
  MeasuredResponse d = measure_window(tw, ddx_M.subspan(w.first, w.count),
                                      ddz_M.subspan(w.first, w.count), w.f, measure);
  d.t_ref += t0;
  d.t_first += t0;
  d.t_last += t0;
  return d;
}

Calibration calibrate(const Case& base, std::span<const Reference> refs,
                      const CalibrateOptions& o) {
  check_input(refs, o);
  Calibrating plain(base, refs, o);
  const std::size_t q = plain.fields().size();
  // Degrees of freedom: every measured value less the unknowns and one time shift per reference.
  const int dof = plain.rows() - static_cast<int>(q) - static_cast<int>(refs.size());
  if (dof < 1)
    throw Error("calibrate: " + std::to_string(plain.rows()) + " measured values are too few for " +
                    std::to_string(q) + " parameters and " + std::to_string(refs.size()) +
                    " time shifts; compare more harmonics or add references",
                "harmonics");
  const std::vector<bool> all(q, true);
  Eigen::VectorXd r0;
  if (!plain.residual(plain.start(), r0))
    throw Error("calibrate: the model fails at the start values: " + plain.failure(plain.start()));
  detail::Fit fit = detail::levenberg_marquardt(plain, plain.start(), all, o.max_iterations);
  if (!std::isfinite(fit.S)) throw Error("calibrate: " + fit.message);
  // References sampled in step with the excitation alias as the model's harmonics do not (as in
  // identify): fitted again with the model sampled at their times, and the better fit kept.
  std::optional<Calibrating> sampled;
  int other_simulations = 0;
  if (std::any_of(refs.begin(), refs.end(), [&](const Reference& ref) {
        return detail::has_sampling_map(ref.data, o.harmonics);
      })) {
    sampled.emplace(base, refs, o, true);
    other_simulations = detail::keep_the_better(sampled, fit, all, o.max_iterations);
  }
  Calibrating& pr = sampled ? *sampled : plain;

  Calibration cal;
  cal.converged = fit.converged;
  cal.message = fit.message;
  cal.iterations = fit.iterations;
  const double s2 = fit.S / dof;
  cal.reduced_chi2 = s2;
  cal.calibrated = pr.case_at(fit.p);
  cal.references = pr.point(fit.p).fits;

  std::vector<std::string> names;
  for (const Field* f : pr.fields()) names.push_back(f->key);
  // A poor fit of references whose axis or unit nothing decided: read the other way, as identify
  // reads a window (IdentifyOptions::z_open, units_open), all open ones alike (one logger), the
  // simplest reading first; the first that fits is taken, with a warning.
  const auto open = [&](bool Reference::*flag) {
    return std::any_of(refs.begin(), refs.end(), [&](const Reference& ref) { return ref.*flag; });
  };
  if (s2 > o.max_reduced_chi2 && (open(&Reference::z_open) || open(&Reference::units_open))) {
    std::vector<std::pair<bool, bool>> readings;  // (z negated, in g)
    if (open(&Reference::z_open)) readings.emplace_back(true, false);
    if (open(&Reference::units_open)) readings.emplace_back(false, true);
    if (open(&Reference::z_open) && open(&Reference::units_open)) readings.emplace_back(true, true);
    int simulations = plain.simulations() + (sampled ? sampled->simulations() : other_simulations);
    for (const auto& [z, g] : readings) {
      std::vector<Reference> read = std::vector<Reference>(refs.begin(), refs.end());
      std::vector<std::pair<bool, bool>> applied;
      for (Reference& ref : read) {
        const bool negate = z && ref.z_open, in_g = g && ref.units_open;
        ref.data =
            detail::scaled(detail::flipped(ref.data, false, negate), in_g ? kStandardGravity : 1.0);
        ref.z_open = ref.units_open = false;
        applied.emplace_back(negate, in_g);
      }
      try {
        Calibration other = calibrate(base, read, o);
        simulations += other.simulations;
        if (!(other.reduced_chi2 <= o.max_reduced_chi2)) continue;
        std::string which;
        for (std::size_t k = 0; k < read.size(); ++k) {
          other.references[k].z_negated = applied[k].first;
          other.references[k].read_in_g = applied[k].second;
          if (applied[k].first || applied[k].second)
            which += (which.empty() ? "" : ", ") + read[k].name;
        }
        other.simulations = simulations;
        other.warnings.insert(other.warnings.begin(),
                              detail::open_reading_warning(z, g, other.reduced_chi2, s2, which));
        return other;
      } catch (const Error&) {
        // a reading the model cannot fit: the next one
      }
    }
  }
  // A poor fit, and the reference that makes it.
  int scale_simulations = 0;  // those of the check of the other soil scale
  if (s2 > o.max_reduced_chi2) {
    cal.warnings.push_back(
        "poor fit: reduced chi^2 " + sig3(s2) + " > " + num(o.max_reduced_chi2) +
        ": the calibrated model does not reproduce the references to their noise, and the "
        "estimates are biased by what it lacks (a parameter not fitted, a reference's soil or "
        "driving torque not what is assumed, the record's axis conventions)");
    // The references' G on the other soil scale (as identify's diagnosis checks a window's):
    // named when it fits, or ten times better; the calibration stays on the scale given.
    const SoilScale given = refs.front().scale;
    if (std::all_of(refs.begin(), refs.end(),
                    [&](const Reference& r) { return std::isfinite(r.G) && r.scale == given; })) {
      std::vector<Reference> other = std::vector<Reference>(refs.begin(), refs.end());
      try {
        for (Reference& r : other) {
          r.scale = r.scale == SoilScale::formulas ? SoilScale::table2 : SoilScale::formulas;
          r.soil = soil_on_scale(r.G, r.scale, r.soil);
          r.G = kNaN;  // checked once
        }
        CalibrateOptions o2 = o;
        o2.profile = false;
        const Calibration c2 = calibrate(base, other, o2);
        scale_simulations = c2.simulations;
        if (std::isfinite(c2.reduced_chi2) &&
            (c2.reduced_chi2 <= o.max_reduced_chi2 || c2.reduced_chi2 < s2 / 10.0))
          cal.warnings.push_back(
              "the fit is far better with the references' G on the other soil scale (reduced "
              "chi^2 " +
              sig3(c2.reduced_chi2) + " against " + sig3(s2) + "): " +
              (given == SoilScale::formulas
                   ? "their soils are Table 2 soils (what run --G simulates): --soil-scale table2 "
                     "(Python: soil_scale='table2')"
                   : "their soils follow Appendix B's formulas: --soil-scale formulas (Python: "
                     "soil_scale='formulas')"));
      } catch (const Error&) {
        // a G outside the other scale's range, or a calibration that fails there: nothing said
      }
    }
  }
  if (refs.size() > 1) {
    std::vector<double> shares;
    for (const ReferenceFit& r : cal.references) shares.push_back(r.reduced_chi2);
    std::vector<double> sorted = shares;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[(sorted.size() - 1) / 2];
    for (const ReferenceFit& r : cal.references)
      if (r.reduced_chi2 > o.max_reduced_chi2 && r.reduced_chi2 > 4.0 * median)
        cal.warnings.push_back("reference " + r.name + " fits far worse than the others (its " +
                               "reduced chi^2 " + sig3(r.reduced_chi2) + " against a median of " +
                               sig3(median) +
                               "): its soil, its driving torque or its record may not be what "
                               "is assumed");
  }

  // Covariance s^2 (J^T J)^-1, condition number and correlations of the column-scaled Jacobian.
  Eigen::VectorXd se = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(q), kNaN);
  Eigen::MatrixXd J;
  const bool have_J = fit.J.rows() == pr.rows() && fit.last_step < 1e-3;
  if (have_J) J = fit.J;
  if (have_J || detail::jacobian(pr, fit.p, fit.r, all, J)) {
    const detail::LinearisedUncertainty u =
        detail::linearised_uncertainty(J, s2, names, o.max_condition, o.max_correlation);
    cal.condition = u.condition;
    se = u.se;
    cal.warnings.insert(cal.warnings.end(), u.warnings.begin(), u.warnings.end());
  } else {
    cal.warnings.push_back("the model fails next to the estimate: no uncertainties");
  }

  const double c = detail::t_quantile(dof);
  for (std::size_t j = 0; j < q; ++j) {
    const Eigen::Index jj = static_cast<Eigen::Index>(j);
    Estimate e;
    e.name = names[j];
    e.unit = pr.fields()[j]->unit;
    e.value = std::exp(fit.p[jj]);
    e.standard_uncertainty = e.value * se[jj];  // d exp(p) = exp(p) dp
    e.lower = e.upper = kNaN;
    const detail::Bounds& b = pr.bounds()[j];
    if (fit.p[jj] - b.lo < 1e-3 || b.hi - fit.p[jj] < 1e-3)
      cal.warnings.push_back(e.name + " = " + sig(e.value, 6) +
                             " is at the edge of its search range [" + sig(std::exp(b.lo), 6) +
                             ", " + sig(std::exp(b.hi), 6) +
                             "]: the references want a value beyond it (check the case and the "
                             "references, or widen the range)");
    if (o.profile && std::isfinite(se[jj])) {
      for (const int side : {-1, 1}) {
        const detail::ProfileLimit limit = detail::profile_limit(pr, fit, j, side, se[jj], c, s2);
        if (std::isfinite(limit.at) && !limit.model_fails)
          (side < 0 ? e.lower : e.upper) = std::exp(limit.at);
        if (limit.model_fails)
          cal.warnings.push_back("no 95 % " + std::string(side < 0 ? "lower" : "upper") +
                                 " limit of " + e.name + ": the model fails beyond " +
                                 sig(std::exp(limit.last_good), 6) + " (" + limit.failure + ")");
        if (limit.open) {
          (side < 0 ? e.lower_open : e.upper_open) = true;
          cal.warnings.push_back("flat profile: " + e.name +
                                 (side < 0 ? " has no lower" : " has no upper") +
                                 " 95 % limit within its range; it is not identifiable from "
                                 "these references");
        }
      }
    } else if (o.profile) {
      e.lower_open = e.upper_open = true;
    }
    cal.estimates.push_back(e);
  }
  cal.simulations = plain.simulations() + (sampled ? sampled->simulations() : other_simulations) +
                    scale_simulations;
  return cal;
}

}  // namespace oscidrum
