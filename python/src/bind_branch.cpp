// Bindings of oscidrum/branch.hpp: continue_branch(case, key, from_, to, ...) -> dict. The
// continuation runs with the GIL released; Ctrl-C cancels it and raises KeyboardInterrupt.
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <complex>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/branch.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/motion.hpp"
#include "oscidrum/output_table.hpp"

namespace oscidrum::python {
namespace {

// The points as columns (the CSV of `oscidrum continue --csv`, names without units), the
// bifurcations as a list of dicts.
py::dict branch_dict(const Branch& b) {
  py::dict d;
  d["key"] = b.key;
  d["unit"] = b.unit;
  d["multiplicity"] = b.multiplicity;
  d["end"] = std::string(to_string(b.end));
  d["message"] = b.message;
  d["period_maps"] = b.period_maps;
  d["seconds"] = b.seconds;
  py::dict points;
  const auto add = [&](const char* name, auto get) {
    std::vector<double> v;
    for (const BranchPoint& p : b.points) v.push_back(static_cast<double>(get(p)));
    points[name] = to_array(v);
  };
  add("parameter", [](const BranchPoint& p) { return p.parameter; });
  add("arclength", [](const BranchPoint& p) { return p.arclength; });
  add("multiplicity", [](const BranchPoint& p) { return p.multiplicity; });
  add("stable", [](const BranchPoint& p) { return p.stable() ? 1 : 0; });
  add("unstable", [](const BranchPoint& p) { return p.unstable; });
  add("max_modulus", [](const BranchPoint& p) { return p.floquet.max_modulus; });
  add("dq_ds", [](const BranchPoint& p) { return p.dq_ds; });
  add("min_N", [](const BranchPoint& p) { return p.min_N; });
  for (const MetricOutput& o : metric_outputs()) {
    if (!std::holds_alternative<double Metrics::*>(o.member)) continue;
    std::vector<double> v;
    for (const BranchPoint& p : b.points) v.push_back(scalar_value(p.metrics, o));
    points[o.name] = to_array(v);
  }
  // The spectra's amplitudes as the CSV's columns ddx_A1 ... ddx_AH, ddz_A1 ...
  const std::size_t n_h =
      harmonics_held(b.points, [](const BranchPoint& p) -> const Metrics& { return p.metrics; });
  for (const MetricOutput& o : metric_outputs()) {
    if (std::holds_alternative<double Metrics::*>(o.member)) continue;
    for (std::size_t n = 1; n <= n_h; ++n) {
      std::vector<double> v;
      for (const BranchPoint& p : b.points) v.push_back(harmonic_amplitude(p.metrics, o, n));
      points[(spectrum_prefix(o.name) + "_A" + std::to_string(n)).c_str()] = to_array(v);
    }
  }
  py::list sequence, multipliers;
  for (const BranchPoint& p : b.points) {
    sequence.append(p.sequence);
    multipliers.append(p.floquet.multipliers);
  }
  points["sequence"] = sequence;
  d["points"] = points;
  d["multipliers"] = multipliers;
  py::list bifs;
  for (const Bifurcation& f : b.bifurcations) {
    py::dict x;
    x["kind"] = std::string(to_string(f.kind));
    x["parameter"] = f.parameter;
    x["tolerance"] = f.tolerance;
    x["after_point"] = f.after_point;
    x["multiplier"] = f.multiplier;
    x["description"] = f.description;
    x["child"] = f.child;
    bifs.append(x);
  }
  d["bifurcations"] = bifs;
  py::list children;
  for (const Branch& c : b.children) children.append(branch_dict(c));
  d["children"] = children;
  return d;
}

py::dict continue_branch_py(const Case& c, const std::string& key, double from, double to,
                            double initial_step, double max_step, double tolerance, Int max_points,
                            bool metrics, Int harmonics, Int switch_depth,
                            std::optional<double> MMd_fraction) {
  BranchOptions o;
  if (MMd_fraction) o.MMd_fraction = *MMd_fraction;
  o.key = dotted_field_key(key);  // Python's flat names too ("mu": "unknown key 'mu'" before)
  o.from = from;
  o.to = to;
  o.initial_step = initial_step;
  o.max_step = max_step;
  o.tolerance = tolerance;
  o.max_points = max_points;
  o.metrics = metrics;
  o.harmonics = harmonics;
  o.switch_depth = switch_depth;
  GuardedCalls calls;  // Ctrl-C, looked for at most every 50 ms
  o.cancelled = [&]() { return calls.cancelled(); };
  Branch b;
  {
    py::gil_scoped_release release;
    b = continue_branch(c, o);
  }
  calls.rethrow();
  return branch_dict(b);
}

}  // namespace

void bind_branch(py::module_& m) {
  py::class_<MotionAnalysis>(m, "MotionAnalysis",
                             "What a motion without a periodic steady state is "
                             "(docs/bifurcations.md, 'Beyond the last periodic orbit').")
      .def_readonly("kind", &MotionAnalysis::kind,
                    "quasi_periodic, chaotic, periodic, converging or undecided")
      .def_readonly("lyapunov", &MotionAnalysis::lyapunov, "largest Lyapunov exponent [1/s]")
      .def_readonly("lyapunov_first", &MotionAnalysis::lyapunov_first,
                    "the same from the window's first half [1/s]")
      .def_readonly("lyapunov_second", &MotionAnalysis::lyapunov_second,
                    "... and from its second half [1/s]")
      .def_readonly("periods", &MotionAnalysis::periods, "excitation periods examined [-]")
      .def_readonly("recurrence", &MotionAnalysis::recurrence,
                    "p > 0: the stroboscopic points repeat every p periods [-]")
      .def_readonly("converging_period", &MotionAnalysis::converging_period,
                    "p > 0: points p periods apart approach each other geometrically: the motion "
                    "converges [-]")
      .def_readonly("contraction", &MotionAnalysis::contraction,
                    "shrink factor of the distance between points p periods apart over the "
                    "window's second half [-]")
      .def_property_readonly(
          "section",
          [](const MotionAnalysis& a) {
            const std::size_t rows = a.section.size(),
                              cols = rows > 0 ? a.section.front().size() : 0;
            py::array_t<double> out({rows, cols});
            auto w = out.mutable_unchecked<2>();
            for (std::size_t i = 0; i < rows; ++i)
              for (std::size_t j = 0; j < cols; ++j)
                w(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) = a.section[i][j];
            return out;
          },
          "the stroboscopic points: the roller's state at t0 + k T, one row per period (the "
          "state's components in order: delta, phi, x_A, s_A and their rates; then the gap and "
          "its rate with contact.unilateral)")
      .def_readonly("evidence", &MotionAnalysis::evidence, "the verdict with its numbers")
      .def("__repr__", [](const MotionAnalysis& a) {
        return "MotionAnalysis(kind='" + a.kind + "', lyapunov=" + std::to_string(a.lyapunov) +
               " 1/s, periods=" + std::to_string(a.periods) + ")";
      });
  m.def(
      "analyze_motion",
      [](const Case& c, const Result& result, Int periods) {
        const Model model(c);
        py::gil_scoped_release release;
        return analyze_motion(model, result, periods);
      },
      py::arg("case"), py::arg("result"), py::arg("periods") = 400,
      "Examine the motion of `result` (simulated from `case`) from its first sample over "
      "`periods` further excitation periods: stroboscopic points, largest Lyapunov exponent, "
      "recurrence, and a verdict (docs/bifurcations.md). simulate() does this itself for a run "
      "without a steady state (Diagnostics.motion).");
  m.def(
      "continue_branch", &continue_branch_py, py::arg("case"), py::arg("key"), py::arg("from_"),
      py::arg("to"), py::arg("initial_step") = 0.02, py::arg("max_step") = 0.05,
      py::arg("tolerance") = 1e-6, py::arg("max_points") = 2000, py::arg("metrics") = true,
      py::arg("harmonics") = 10, py::arg("switch_depth") = 1, py::arg("MMd_fraction") = py::none(),
      "Follow the periodic orbits of `case` through the parameter `key` from `from_` to `to` "
      "(SI units) by pseudo-arclength continuation, stable and unstable alike, and locate the "
      "bifurcations on the branch (docs/bifurcations.md). `MMd_fraction`: MMd = MMd_fraction * "
      "M0 at every value, with the M0 in effect there (it follows roller.M0, or roller.f with "
      "roller.unbalance; a Case keeps only the MMd its MMd_fraction gave); None: the case's MMd "
      "throughout.\n\n"
      "Returns\n-------\ndict\n    key, unit, multiplicity, end ('reached_end', 'left_range', "
      "'gross_slip', 'lift_off', 'period_halved', 'step_too_small', 'max_points', 'start_failed'), "
      "message, "
      "period_maps, "
      "seconds; points: columns (NumPy arrays) parameter, arclength, multiplicity, stable, "
      "unstable, max_modulus, dq_ds, min_N, every metric, the amplitudes ddx_A1 ... ddz_AH (H = "
      "harmonics), and sequence (list of str); "
      "multipliers: one list of complex per point; bifurcations: list of dicts (kind, "
      "parameter, tolerance, after_point, multiplier, description, child); children: the "
      "branches switched onto at period doublings (switch_depth levels: the period-2p branches "
      "born there, or the period-p branch a period-2p orbit shrank onto), as dicts alike. "
      "pandas.DataFrame(result['points']) is the table of `oscidrum continue --csv`.\n\n"
      "Raises\n------\noscidrum.Error\n    A key that cannot be continued, a range outside its "
      "rule, bad options.");
}

}  // namespace oscidrum::python
