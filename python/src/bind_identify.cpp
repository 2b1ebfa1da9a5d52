// Bindings of oscidrum/identify.hpp and the windows of oscidrum/record.hpp: the soil from measured
// accelerations (docs/identify.md). Results are lists of dicts with the keys of the CLI's CSV
// columns (without units), so that they read like `oscidrum identify --csv`.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/calibrate.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/identify.hpp"
#include "oscidrum/record.hpp"

namespace oscidrum::python {
namespace {

py::dict window_dict(const RecordWindow& w) {
  py::dict d;
  d["window"] = w.index;
  d["t_start"] = w.t_start;
  d["t_end"] = w.t_end;
  d["t"] = w.t_mid;
  d["position"] = w.position;
  d["samples"] = w.count;
  d["samples_per_period"] = w.samples_per_period;
  d["whole"] = w.whole;
  d["f"] = w.f;
  d["drift"] = w.drift;
  d["change"] = w.change;
  d["valid"] = w.valid;
  d["reason"] = w.reason;
  d["metrics"] = w.metrics;
  return d;
}

WindowOptions window_options(double f, double window, double hop, int n_max, double max_residual,
                             double max_drift, double clip_level, double max_gap,
                             double max_change) {
  WindowOptions o;
  o.f = f;
  o.window_periods = window;
  o.hop_periods = hop;
  o.n_max = n_max;
  o.gates.max_residual = max_residual;
  o.gates.max_drift = max_drift;
  o.gates.clip_level = clip_level;
  o.gates.max_gap = max_gap;
  o.gates.max_change = max_change;
  return o;
}

std::span<const double> optional_span(const std::optional<Array>& a, const char* name) {
  return a ? span_of(*a, name) : std::span<const double>();
}

// A window of analyze_windows (window_dict) back as the RecordWindow it was made from, with what
// record_kb reads: its samples of t (from t_start and samples), f, valid and metrics.
RecordWindow window_of(py::handle item, std::size_t i, std::span<const double> t) {
  const std::string where = "record_kb: windows[" + std::to_string(i) + "]";
  if (!py::isinstance<py::dict>(item))
    throw Error(where + " must be a dict of analyze_windows; got " + python_type_name(item));
  const py::dict d = py::reinterpret_borrow<py::dict>(item);
  for (const char* key : {"t_start", "samples", "f", "valid", "metrics"})
    if (!d.contains(key))
      throw Error(where + " has no key '" + key + "': pass the dicts analyze_windows returns");
  RecordWindow w;
  try {
    w.t_start = d["t_start"].cast<double>();
    w.count = d["samples"].cast<std::size_t>();
    w.f = d["f"].cast<double>();
    w.valid = d["valid"].cast<bool>();
    w.metrics = d["metrics"].cast<RecordMetrics>();
  } catch (const py::cast_error&) {
    throw Error(where +
                ": t_start, samples, f, valid or metrics is not of the type "
                "analyze_windows gives (float, int, float, bool, RecordMetrics)");
  }
  // A window within a pause of the record: no samples (its t_start no sample's), never valid.
  if (w.count == 0 && !w.valid) return w;
  const auto first = std::lower_bound(t.begin(), t.end(), w.t_start);
  if (first == t.end() || *first != w.t_start)
    throw Error(where + ": its t_start = " + std::to_string(w.t_start) +
                " s is no sample of t: pass the t the windows were analyzed from");
  w.first = static_cast<std::size_t>(first - t.begin());
  if (w.count == 0 || w.count > t.size() - w.first)
    throw Error(where + ": its " + std::to_string(w.count) +
                " samples from t_start run past "
                "the end of t: pass the t the windows were analyzed from");
  return w;
}

}  // namespace

void bind_identify(py::module_& m) {
  m.def(
      "estimate_frequency",
      [](const Array& t, const Array& ddx, const Array& ddz, double f_min, double f_max) {
        FrequencySearch s;
        s.f_min = f_min;
        s.f_max = f_max;
        return estimate_frequency(span_of(t, "t"), span_of(ddx, "ddx_M"), span_of(ddz, "ddz_M"), s);
      },
      py::arg("t"), py::arg("ddx_M"), py::arg("ddz_M"), py::arg("f_min") = 10.0,
      py::arg("f_max") = 100.0,
      "The excitation frequency [Hz] of a record: the peak of the harmonic-sum spectrum, refined "
      "by least squares on f.");
  m.def(
      "analyze_windows",
      [](const Array& t, const Array& ddx, const Array& ddz, const std::optional<Array>& position,
         double f, double window, double hop, Int n_max, double max_residual, double max_drift,
         double clip_level, double max_gap, double max_change) {
        const WindowOptions o = window_options(f, window, hop, n_max, max_residual, max_drift,
                                               clip_level, max_gap, max_change);
        const std::vector<RecordWindow> ws =
            analyze_windows(span_of(t, "t"), span_of(ddx, "ddx_M"), span_of(ddz, "ddz_M"),
                            optional_span(position, "position"), o);
        py::list out;
        for (const RecordWindow& w : ws) out.append(window_dict(w));
        return out;
      },
      py::arg("t"), py::arg("ddx_M"), py::arg("ddz_M"), py::arg("position") = py::none(),
      py::arg("f") = 0.0, py::arg("window") = 0.0, py::arg("hop") = 0.0, py::arg("n_max") = 0,
      py::arg("max_residual") = 0.5, py::arg("max_drift") = 0.002, py::arg("clip_level") = 0.0,
      py::arg("max_gap") = 0.5, py::arg("max_change") = 0.05,
      "The record in windows of `window` excitation periods (0: whole), each fitted and checked "
      "by the quality gates, as `oscidrum analyze`: a list of dicts (window, t_start, t_end, t, "
      "position, samples, samples_per_period, f, drift, change, valid, reason, metrics). f = 0: "
      "estimated; n_max = 0: as many harmonics as the sampling resolves (2 n_max + 1 samples per "
      "period), at most 10.");
  m.def(
      "record_kb",
      [](const py::list& windows, const Array& t, const std::optional<Array>& alpha,
         const std::optional<Case>& c) {
        const std::span<const double> ts = span_of(t, "t");
        const std::span<const double> as = optional_span(alpha, "alpha");
        if (alpha && as.size() != ts.size())
          throw Error("record_kb: alpha has " + std::to_string(as.size()) + " samples and t " +
                      std::to_string(ts.size()) + "; expected one angle per time of t");
        std::vector<RecordWindow> ws;
        ws.reserve(windows.size());
        for (std::size_t i = 0; i < windows.size(); ++i) ws.push_back(window_of(windows[i], i, ts));
        const std::string note = record_kb(ws, ts, as, c ? &*c : nullptr);
        for (std::size_t i = 0; i < ws.size(); ++i) {
          py::dict d = windows[i];
          d["metrics"] = py::cast(ws[i].metrics);
        }
        return note;
      },
      py::arg("windows"), py::arg("t"), py::arg("alpha"), py::arg("case"),
      "kb, the Kb-type soil stiffness [N/m], of every valid window of a vibratory drum's record, "
      "as `oscidrum analyze --case CASE --unbalance-col ALPHA` (RecordMetrics.kb; "
      "docs/outputs.md): kb = m nu^2 - kd - F0 nu^2 cos(phi_u - theta_1) / A_1 from the drum's "
      "vertical balance, with A_1, theta_1 the window's fitted fundamental of z_M'', phi_u the "
      "unbalance's phase over the window and m, kd, F0 = m_u e_u nu^2 the case's roller.\n\n"
      "Parameters\n----------\nwindows : list of dict\n    The windows analyze_windows "
      "returned for the record (t, ddx_M, ddz_M). Each dict's 'metrics' is replaced by a "
      "RecordMetrics with kb filled in (NaN for an invalid window).\n"
      "t : array of float\n    The record's times [s], the t given to analyze_windows.\n"
      "alpha : array of float or None\n    The unbalance's angle [rad] at each time of t: the "
      "unbalance force's downward component is F0 sin(alpha), alpha increasing as 2 pi f t (the "
      "column alpha of `oscidrum run --csv`, any multiple of 2 pi added). None: kb is NaN.\n"
      "case : Case or None\n    The vibratory drum's case (roller.type = 'vibratory': "
      "roller.m, roller.kd, roller.static_moment). None or the oscillation drum: kb is NaN.\n\n"
      "Returns\n-------\nstr\n    '' when kb was filled in, else in one line why every "
      "window's kb is NaN (no case, not a vibratory drum, no angle), as `analyze` reports it "
      "(kb_note).\n\n"
      "Raises\n------\noscidrum.Error\n    If t or alpha is not 1-D, alpha and t differ in "
      "length, or a window is not a dict of analyze_windows for this t (the message names the "
      "argument).");
  m.def(
      "identify_record",
      [](const Case& c, const Array& t, const Array& ddx, const Array& ddz,
         const std::optional<Array>& position, double f, std::optional<double> window, double hop,
         Int n_max, const std::string& estimate, bool fit_mu, bool fit_MMd, Int compare,
         bool use_peaks, bool use_area, bool profile, bool shooting, const std::string& soil_scale,
         bool z_open, bool units_open, double gain_uncertainty, bool x_read_backward,
         bool z_read_up) {
        if (estimate != "G" && estimate != "ks")
          throw Error("estimate must be 'G' or 'ks'; got '" + estimate + "'");
        // window=None: 40 periods, or the whole record when it is shorter.
        WindowOptions wo =
            window_options(f, window.value_or(40.0), hop, n_max, 0.5, 0.002, 0.0, 0.5, 0.05);
        wo.whole_if_shorter = !window.has_value();
        IdentifyOptions io;
        io.modulus = estimate == "G";
        io.soil_scale = soil_scale_from(soil_scale);
        io.fit_mu = fit_mu;
        io.fit_MMd = fit_MMd;
        io.harmonics = compare;
        io.use_peaks = use_peaks;
        io.use_area = use_area;
        io.profile = profile;
        io.shooting = shooting;
        io.z_open = z_open;
        io.units_open = units_open;
        io.x_read_backward = x_read_backward;
        io.z_read_up = z_read_up;
        io.gain_uncertainty = gain_uncertainty;
        io.measure.harmonics = n_max;
        // Ctrl-C between windows (a pass of a long record takes minutes; it could not be
        // interrupted): the main thread watches while the pass runs on a thread of its own.
        GuardedCalls calls;
        const std::span<const double> ts = span_of(t, "t"), xs = span_of(ddx, "ddx_M"),
                                      zs = span_of(ddz, "ddz_M"),
                                      ps = optional_span(position, "position");
        std::vector<PassEstimate> pass = run_watching_signals(calls, [&] {
          return identify_pass(c, ts, xs, zs, ps, wo, io,
                               [&](std::size_t, std::size_t) { return !calls.cancelled(); });
        });
        calls.rethrow();
        py::list out;
        for (const PassEstimate& p : pass) {
          py::dict d = window_dict(p.window);
          d["valid"] = p.valid;
          d["reason"] = p.reason;
          const Identification& id = p.identification;
          // Every unknown's keys in every window, NaN where it failed (as the CLI's CSV).
          for (const IdentifiedUnknown& u : identified_unknowns(io))
            for (const char* suffix : {"", "_u", "_lo", "_hi"}) d[py::str(u.name + suffix)] = NAN;
          for (const Estimate& e : id.estimates) {
            d[py::str(e.name)] = e.value;
            d[py::str(e.name + "_u")] = e.standard_uncertainty;
            d[py::str(e.name + "_lo")] = e.lower;
            d[py::str(e.name + "_hi")] = e.upper;
            if (io.gain_uncertainty > 0.0) d[py::str(e.name + "_u_gain")] = e.gain_uncertainty;
          }
          if (io.modulus) d["soil_scale"] = soil_scale;
          d["tau"] = p.valid ? id.time_shift : NAN;
          d["rms_residual"] = p.valid ? id.rms_residual : NAN;
          d["relative_residual"] = p.valid ? id.relative_residual : NAN;
          d["reduced_chi2"] = p.valid ? id.reduced_chi2 : NAN;
          d["condition"] = p.valid ? id.condition : NAN;
          d["iterations"] = id.iterations;
          d["simulations"] = id.simulations;
          d["warnings"] = id.warnings;
          d["model_sampled"] = p.valid && id.model_sampled;
          d["z_negated"] = p.valid && id.z_negated;
          d["read_in_g"] = p.valid && id.read_in_g;
          if (p.valid) d["fitted"] = id.fitted;
          out.append(d);
        }
        return out;
      },
      py::arg("case"), py::arg("t"), py::arg("ddx_M"), py::arg("ddz_M"),
      py::arg("position") = py::none(), py::arg("f") = 0.0, py::arg("window") = py::none(),
      py::arg("hop") = 0.0, py::arg("n_max") = 0, py::arg("estimate") = "G",
      py::arg("fit_mu") = false, py::arg("fit_MMd") = false, py::arg("compare") = 4,
      py::arg("use_peaks") = false, py::arg("use_area") = false, py::arg("profile") = true,
      py::arg("shooting") = true, py::arg("soil_scale") = "formulas", py::arg("z_open") = false,
      py::arg("units_open") = false, py::arg("gain_uncertainty") = 0.0,
      py::arg("x_read_backward") = false, py::arg("z_read_up") = false,
      "Identify the soil in each window of a record, as `oscidrum identify`: a list of dicts "
      "with the keys of its CSV columns (G, G_u, G_lo, G_hi [Pa], ..., tau, relative_residual, "
      "warnings) and 'fitted', the Case at the estimate. `case` gives the roller and everything "
      "not estimated; its M0 is scaled by (f / roller.f)^2 to the record's f. `window` [periods]: "
      "None (the default) is 40, or the whole record as one window when it is shorter; 0 is the "
      "whole record; a window longer than the record is an error. `z_open`: nothing said which "
      "way ddz_M's axis points (read_record's z_open): a window that fits poorly as given but "
      "well with ddz_M negated is fitted so (its key z_negated true, with a warning); "
      "`units_open`: the accelerations had no unit (read_record's units_open), and a window that "
      "fits well only with them in g is fitted so (read_in_g true, with a warning); "
      "`x_read_backward`, `z_read_up`: ddx_M and ddz_M were negated to read them (an x axis "
      "pointing backward, a z axis up), so that a poor fit's diagnosis names the reading to "
      "change.");
  m.def(
      "soil_on_scale",
      [](double G, const std::string& scale, const Soil& base) {
        return soil_on_scale(G, soil_scale_from(scale), base);
      },
      py::arg("G"), py::arg("scale") = "formulas", py::arg("base") = Soil{},
      "The soil of shear modulus G [Pa] on a scale: 'formulas' (Appendix B (42)-(45) with nu and "
      "rho of `base`) or 'table2' (the paper's Table 2 coefficients, interpolated at G).");
  m.def(
      "calibrate_records",
      [](const Case& c, const py::list& references, const std::vector<std::string>& parameters,
         double f, Int n_max, Int compare, double range, bool profile, bool shooting) {
        WindowOptions wo;
        wo.f = f;
        wo.n_max = n_max;
        std::vector<Reference> refs;
        for (const py::handle& h : references) {
          const py::dict d = py::cast<py::dict>(h);
          Reference r;
          r.name = d.contains("name") ? py::cast<std::string>(d["name"])
                                      : "reference " + std::to_string(refs.size());
          r.soil = py::cast<Soil>(d["soil"]);
          r.z_open = d.contains("z_open") && py::cast<bool>(d["z_open"]);
          r.units_open = d.contains("units_open") && py::cast<bool>(d["units_open"]);
          if (d.contains("G")) {  // the G [Pa] on "soil_scale" that "soil" was made from
            r.G = py::cast<double>(d["G"]);
            r.scale = soil_scale_from(py::cast<std::string>(d["soil_scale"]));
          }
          const Array t = py::cast<Array>(d["t"]), x = py::cast<Array>(d["ddx_M"]),
                      z = py::cast<Array>(d["ddz_M"]);
          try {
            r.data = measure_record(span_of(t, "t"), span_of(x, "ddx_M"), span_of(z, "ddz_M"), wo);
          } catch (const Error& e) {
            throw Error(r.name + ": " + e.what());
          }
          refs.push_back(std::move(r));
        }
        CalibrateOptions o;
        o.parameters = parameters;
        o.harmonics = compare;
        o.range = range;
        o.profile = profile;
        o.shooting = shooting;
        Calibration cal;
        {
          py::gil_scoped_release release;
          cal = calibrate(c, refs, o);
        }
        py::list estimates, fits;
        for (const Estimate& e : cal.estimates) {
          py::dict d;
          d["name"] = e.name;
          d["unit"] = e.unit;
          d["value"] = e.value;
          d["standard_uncertainty"] = e.standard_uncertainty;
          d["lower"] = e.lower;
          d["upper"] = e.upper;
          d["lower_open"] = e.lower_open;
          d["upper_open"] = e.upper_open;
          estimates.append(d);
        }
        for (const ReferenceFit& r : cal.references) {
          py::dict d;
          d["name"] = r.name;
          d["f"] = r.f;
          d["tau"] = r.time_shift;
          d["rms_residual"] = r.rms_residual;
          d["relative_residual"] = r.relative_residual;
          d["reduced_chi2"] = r.reduced_chi2;
          d["model_sampled"] = r.model_sampled;
          d["z_negated"] = r.z_negated;
          d["read_in_g"] = r.read_in_g;
          fits.append(d);
        }
        py::dict out;
        out["estimates"] = estimates;
        out["references"] = fits;
        out["reduced_chi2"] = cal.reduced_chi2;
        out["condition"] = cal.condition;
        out["converged"] = cal.converged;
        out["message"] = cal.message;
        out["iterations"] = cal.iterations;
        out["simulations"] = cal.simulations;
        out["warnings"] = cal.warnings;
        out["calibrated"] = cal.calibrated;
        return out;
      },
      py::arg("case"), py::arg("references"), py::arg("parameters"), py::arg("f") = 0.0,
      py::arg("n_max") = 0, py::arg("compare") = 4, py::arg("range") = 10.0,
      py::arg("profile") = true, py::arg("shooting") = true,
      "Calibrate fields of `case` (`parameters`, e.g. ['roller.M0', 'roller.P0']) on reference "
      "records of known soil, as `oscidrum calibrate`: `references` is a list of dicts with t, "
      "ddx_M, ddz_M (arrays in the model's conventions), soil (a Soil) and optionally name. "
      "Returns a dict: estimates (name, unit, value, standard_uncertainty, lower, upper, "
      "lower_open, upper_open), references (name, f, tau, residuals, reduced_chi2), "
      "reduced_chi2, condition, converged, message, iterations, simulations, warnings and "
      "calibrated (the Case to identify with).");
  m.def(
      "synthetic_record",
      [](const std::vector<Case>& cases, double duration, double sample_rate, double noise,
         double drift, double jitter, UInt seed, double speed) {
        SyntheticRecord o;
        o.duration = duration;
        o.sample_rate = sample_rate;
        o.noise = noise;
        o.drift = drift;
        o.jitter = jitter;
        o.seed = seed;
        o.speed = speed;
        RecordSamples r;
        {
          py::gil_scoped_release release;
          r = synthetic_record(cases, o);
        }
        py::dict d;
        d["t"] = to_array(r.t);
        d["ddx_M"] = to_array(r.ddx_M);
        d["ddz_M"] = to_array(r.ddz_M);
        d["position"] = to_array(r.position);
        return d;
      },
      py::arg("cases"), py::arg("duration") = 1.0, py::arg("sample_rate") = 1000.0,
      py::arg("noise") = 0.0, py::arg("drift") = 0.0, py::arg("jitter") = 0.0, py::arg("seed") = 1u,
      py::arg("speed") = 0.0,
      "A record made by oscidrum: each case of `cases` for duration / len(cases) seconds, "
      "sampled at sample_rate [1/s], with white noise and a slow drift (fractions of each "
      "signal's peak): a dict of arrays t [s], ddx_M, ddz_M [m/s^2], position [m].");
}

}  // namespace oscidrum::python
