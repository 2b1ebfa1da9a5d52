// Bindings of oscidrum/diagram.hpp: bifurcation_diagram(case, key, from_, to, ...) -> dict. The
// diagram runs with the GIL released; Ctrl-C cancels it and raises KeyboardInterrupt.
#include <pybind11/stl.h>

#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/diagram.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/output_table.hpp"

namespace oscidrum::python {
namespace {

// The values as columns, and the stroboscopic points as columns (the CSV of `oscidrum diagram
// --csv`, names without units).
py::dict diagram_dict(const Diagram& d) {
  py::dict out;
  out["key"] = d.key;
  out["unit"] = d.unit;
  out["periods_integrated"] = d.periods_integrated;
  out["seconds"] = d.seconds;
  py::dict values;
  // Each column in its own type: counts and signs as integers, flags as booleans (NumPy's
  // int64 and bool), measures as floats.
  const auto add = [&]<class T>(const char* name, T (*get)(const DiagramValue&)) {
    py::array_t<T> a(static_cast<py::ssize_t>(d.values.size()));
    for (std::size_t i = 0; i < d.values.size(); ++i) a.mutable_data()[i] = get(d.values[i]);
    values[name] = a;
  };
  add.operator()<double>("parameter", [](const DiagramValue& x) { return x.parameter; });
  add.operator()<std::int64_t>("direction",
                               [](const DiagramValue& x) -> std::int64_t { return x.direction; });
  add.operator()<bool>("from_rest", [](const DiagramValue& x) { return x.from_rest; });
  add.operator()<bool>("shooting", [](const DiagramValue& x) { return x.shooting; });
  add.operator()<std::int64_t>("period",
                               [](const DiagramValue& x) -> std::int64_t { return x.period; });
  add.operator()<double>("lyapunov", [](const DiagramValue& x) { return x.motion.lyapunov; });
  add.operator()<double>("excitation_period",
                         [](const DiagramValue& x) { return x.excitation_period; });
  py::list verdict, evidence;
  for (const DiagramValue& x : d.values)
    verdict.append(x.motion.kind), evidence.append(x.motion.evidence);
  values["verdict"] = verdict;
  values["evidence"] = evidence;
  out["values"] = values;
  py::dict points;
  std::vector<std::int64_t> index, direction;
  std::vector<double> parameter;
  for (std::size_t i = 0; i < d.values.size(); ++i)
    for (std::size_t k = 0; k < d.values[i].section.size(); ++k) {
      index.push_back(static_cast<std::int64_t>(i));
      parameter.push_back(d.values[i].parameter);
      direction.push_back(d.values[i].direction);
    }
  points["value"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(index.size()), index.data());
  points["parameter"] = to_array(parameter);
  points["direction"] =
      py::array_t<std::int64_t>(static_cast<py::ssize_t>(direction.size()), direction.data());
  for (const SampleOutput& o : sample_outputs()) {
    std::vector<double> column;
    for (const DiagramValue& x : d.values)
      std::visit(
          [&](auto member) {
            for (const auto& v : x.section.*member) column.push_back(static_cast<double>(v));
          },
          o.member);
    points[o.name] = to_array(column);
  }
  out["points"] = points;
  return out;
}

py::dict bifurcation_diagram_py(const Case& c, const std::string& key, double from, double to,
                                Int steps, const std::string& sweep, Int discard, Int periods,
                                std::optional<double> MMd_fraction) {
  DiagramOptions o;
  if (MMd_fraction) o.MMd_fraction = *MMd_fraction;
  o.key = dotted_field_key(key);  // Python's flat names too ("mu" -> "contact.mu")
  o.from = from;
  o.to = to;
  o.steps = steps;
  if (sweep == "up")
    o.sweep = DiagramSweep::up;
  else if (sweep == "down")
    o.sweep = DiagramSweep::down;
  else if (sweep == "both")
    o.sweep = DiagramSweep::both;
  else
    throw Error("bifurcation_diagram: sweep must be 'up', 'down' or 'both'; got '" + sweep + "'");
  o.discard = discard;
  o.periods = periods;
  GuardedCalls calls;  // Ctrl-C, looked for at most every 50 ms
  o.cancelled = [&]() { return calls.cancelled(); };
  Diagram d;
  {
    py::gil_scoped_release release;
    d = bifurcation_diagram(c, o);
  }
  calls.rethrow();
  return diagram_dict(d);
}

}  // namespace

void bind_diagram(py::module_& m) {
  m.def("bifurcation_diagram", &bifurcation_diagram_py, py::arg("case"), py::arg("key"),
        py::arg("from_"), py::arg("to"), py::arg("steps") = 50, py::arg("sweep") = "up",
        py::arg("discard") = 200, py::arg("periods") = 400, py::arg("MMd_fraction") = py::none(),
        "The brute-force bifurcation diagram of `case` in the parameter `key` (SI units, from_ < "
        "to): the motion at steps + 1 values, each started from the state the previous value "
        "ended in (sweep 'up', 'down' or 'both'), `discard` periods dropped, then `periods` "
        "stroboscopic points kept and the motion examined (docs/bifurcations.md). `MMd_fraction`: "
        "MMd = MMd_fraction * M0 at every value, with the M0 in effect there (None: the case's "
        "MMd throughout).\n\n"
        "Returns\n-------\ndict\n    key, unit, periods_integrated, seconds; values: columns "
        "(NumPy arrays) parameter, direction (+1 up, -1 down), from_rest, shooting, period, "
        "lyapunov "
        "[1/s] (NaN where the flow stopped before it was computed), excitation_period [s], and "
        "verdict, evidence (lists of str), one entry per "
        "value in the order visited; points: columns value (its index in values), parameter, "
        "direction and every output column (t, delta, x_A, s_A, ddx_M, ddz_M, ...), one entry "
        "per stroboscopic point. pandas.DataFrame(result['points']) is the table of `oscidrum "
        "diagram --csv`.\n\n"
        "Raises\n------\noscidrum.Error\n    A key that cannot be varied, a range outside its "
        "rule, bad options.");
}

}  // namespace oscidrum::python
