// Bindings of oscidrum/record.hpp: metrics of a measured acceleration record (paper Fig. 23).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <deque>
#include <fstream>
#include <span>
#include <string>
#include <variant>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum/record_reader.hpp"

namespace oscidrum::python {
namespace {

py::array_t<double> column(const std::vector<Harmonic>& h, double Harmonic::*member) {
  py::array_t<double> a(static_cast<py::ssize_t>(h.size()));
  auto out = a.mutable_unchecked<1>();
  for (std::size_t n = 0; n < h.size(); ++n) out(static_cast<py::ssize_t>(n)) = h[n].*member;
  return a;
}

const char* doc(const RecordOutput& o) {
  static std::deque<std::string> docs;  // stable addresses
  docs.push_back(std::string(o.description) + " [" + o.unit + "]" +
                 (is_scalar(o) ? "" : " (list of Harmonic)"));
  return docs.back().c_str();
}

}  // namespace

void bind_record(py::module_& m) {
  py::class_<RecordMetrics> cls(
      m, "RecordMetrics",
      "Metrics of a measured record, from a least-squares harmonic fit (docs/outputs.md).");
  for (const RecordOutput& o : record_outputs())
    std::visit([&](auto member) { cls.def_readonly(o.name, member, doc(o)); }, o.member);
  cls.def_property_readonly_static(
         "scalar_names",
         [](py::handle) {
           py::list names;
           for (const RecordOutput& o : record_outputs())
             if (is_scalar(o)) names.append(o.name);
           return names;
         },
         "names of the scalar outputs, in to_dict order")
      .def(
          "to_dict",
          [](const RecordMetrics& r) {
            py::dict d;
            for (const RecordOutput& o : record_outputs())
              if (is_scalar(o)) d[o.name] = scalar_value(r, o);
            return d;
          },
          "The scalar outputs as {name: value}.")
      .def_property_readonly(
          "ddx_amplitude",
          [](const RecordMetrics& r) { return column(r.ddx_harmonics, &Harmonic::amplitude); },
          "A_n of x_M'' [m/s^2]")
      .def_property_readonly(
          "ddz_amplitude",
          [](const RecordMetrics& r) { return column(r.ddz_harmonics, &Harmonic::amplitude); },
          "A_n of z_M'' [m/s^2]")
      .def_property_readonly(
          "ddx_phase",
          [](const RecordMetrics& r) { return column(r.ddx_harmonics, &Harmonic::phase); },
          "theta_n of x_M'' [rad]")
      .def_property_readonly(
          "ddz_phase",
          [](const RecordMetrics& r) { return column(r.ddz_harmonics, &Harmonic::phase); },
          "theta_n of z_M'' [rad]")
      .def("__repr__", [](const RecordMetrics& r) {
        char buf[240];
        std::snprintf(buf, sizeof buf,
                      "RecordMetrics(cycles=%.4g, ddx_max=%.6g m/s^2, ddz_max=%.6g m/s^2, "
                      "psi_xz=%.6g rad, area=%.6g m^2/s^4, residual_x=%.3g, residual_z=%.3g)",
                      r.cycles, r.ddx_max, r.ddz_max, r.psi_xz, r.area, r.residual_x, r.residual_z);
        return std::string(buf);
      });
  m.def(
      "analyze_record",
      [](const Array& t, const Array& ddx, const Array& ddz, double f, Int n_max) {
        return analyze_record(span_of(t, "t"), span_of(ddx, "ddx_M"), span_of(ddz, "ddz_M"), f,
                              n_max);
      },
      py::arg("t"), py::arg("ddx_M"), py::arg("ddz_M"), py::arg("f"), py::arg("n_max") = 10,
      "Metrics of a measured record: fit y(t) = sum_n (a_n cos(n nu t) + b_n sin(n nu t)) to "
      "x_M'' and z_M'' [m/s^2] sampled at t [s] (strictly increasing, any spacing, at least one "
      "period of f [Hz]) by least squares, then evaluate the metrics on the fitted periodic "
      "signals. Raises oscidrum.Error on inconsistent input.");
  m.def(
      "read_record",
      [](const py::object& where, const std::string& t_col, const std::string& x_col,
         const std::string& z_col, const std::string& pos_col, const std::string& speed_col,
         const std::string& lat_col, const std::string& lon_col, const std::string& east_col,
         const std::string& north_col, const std::string& unbalance_col, const std::string& units,
         const std::string& t_units, double rate, const std::string& x_positive,
         const std::string& z_positive) {
        if (!py::isinstance<py::str>(where) && !py::hasattr(where, "__fspath__"))
          throw Error("read_record: path must be a str or os.PathLike; got " +
                      python_description(where));
        const std::string path = py::str(py::module_::import("os").attr("fspath")(where));
        RecordReading o;
        o.t_col = t_col, o.x_col = x_col, o.z_col = z_col;
        o.pos_col = pos_col, o.speed_col = speed_col;
        o.lat_col = lat_col, o.lon_col = lon_col, o.east_col = east_col, o.north_col = north_col;
        o.unbalance_col = unbalance_col;
        o.units = units, o.t_units = t_units, o.rate = rate;
        o.x_positive = x_positive, o.z_positive = z_positive;
        // The CLI's checks of the choices (its flags allow only these).
        const auto choice = [](const std::string& name, const std::string& v,
                               std::initializer_list<const char*> allowed) {
          std::string list;
          for (const char* a : allowed) {
            if (v == a) return;
            list += (list.empty() ? "" : ", ") + std::string(a);
          }
          throw Error("read_record: " + name + " must be one of " + list + "; got '" + v + "'");
        };
        choice("units", units, {"auto", "m/s2", "g", "mg"});
        choice("t_units", t_units, {"auto", "s", "ms", "us", "ns"});
        choice("x_positive", x_positive, {"forward", "backward"});
        choice("z_positive", z_positive, {"auto", "down", "up"});
        if (!(rate == 0.0 || (rate >= 1.0 && rate <= 1e7)))
          throw Error("read_record: rate must be 0 (the time column) or in [1, 1e7] [Hz]; got " +
                      std::to_string(rate));
        RecordColumns r;
        {
          py::gil_scoped_release release;
          std::ifstream in(path);
          if (!in) throw Error(path + ": cannot open the file");
          r = read_record(in, path, o);
        }
        py::dict d;
        d["t"] = to_array(r.t);
        d["ddx_M"] = to_array(r.ddx_M);
        d["ddz_M"] = to_array(r.ddz_M);
        const std::pair<const char*, const std::vector<double>*> optional[] = {
            {"position", &r.position}, {"lat", &r.lat},     {"lon", &r.lon},
            {"east", &r.east},         {"north", &r.north}, {"alpha", &r.unbalance_angle}};
        for (const auto& [key, v] : optional)
          if (!v->empty()) d[key] = to_array(*v);
        d["notes"] = r.notes;
        d["columns"] = py::dict(py::arg("t") = r.t_column, py::arg("ddx_M") = r.x_column,
                                py::arg("ddz_M") = r.z_column);
        d["factors"] = py::dict(py::arg("t") = r.t_factor, py::arg("ddx_M") = r.x_factor,
                                py::arg("ddz_M") = r.z_factor);
        d["delimiter"] = r.delimiter;
        d["z_positive"] = r.z_positive;
        d["z_open"] = r.z_open;
        d["units_open"] = r.units_open;
        return d;
      },
      py::arg("path"), py::arg("t_col") = "", py::arg("x_col") = "", py::arg("z_col") = "",
      py::arg("pos_col") = "", py::arg("speed_col") = "", py::arg("lat_col") = "",
      py::arg("lon_col") = "", py::arg("east_col") = "", py::arg("north_col") = "",
      py::arg("unbalance_col") = "", py::arg("units") = "auto", py::arg("t_units") = "auto",
      py::arg("rate") = 0.0, py::arg("x_positive") = "forward", py::arg("z_positive") = "auto",
      "A measured record's file read as `oscidrum analyze` and `identify` read it (docs/cli.md): "
      "columns recognised from the header (or given by name or 1-based index: t_col, x_col, "
      "z_col, pos_col, speed_col, lat_col, lon_col, east_col, north_col, unbalance_col), units "
      "from it (units: 'auto', 'm/s2', 'g' or 'mg'; t_units: 'auto', 's', 'ms', 'us' or 'ns'), "
      "rate [Hz] for "
      "a record without a time column, and the axes' directions (x_positive: 'forward' or "
      "'backward'; z_positive: 'auto' (down unless the column's mean is about +1 g: up), 'down' or "
      "'up'). Returns a dict: t [s], ddx_M, ddz_M [m/s^2] in "
      "the model's conventions (x forward, z down), position [m], lat, lon [deg], east, north "
      "[m] and alpha [rad] when read, notes (how each column was read, what was skipped or "
      "merged), columns (the header each came from), factors, delimiter, z_positive (the "
      "direction the z column was read in), z_open (true: 'auto' found no gravity to decide "
      "it; identify_record(z_open=True) then fits z_M'' negated where that fits and as read "
      "does not) and units_open (true: the accelerations had no unit and no gravity in g told "
      "it; identify_record(units_open=True) fits them in g where only that fits). Raises "
      "oscidrum.Error naming the file, line and column.");
  m.def(
      "gravity_points_up",
      [](const std::vector<double>& ddz_M) {
        double mean = 0.0;
        const bool up = gravity_points_up(ddz_M, &mean);
        return py::make_tuple(up, mean);
      },
      py::arg("ddz_M"),
      "Whether a vertical acceleration read as positive down [m/s^2] keeps gravity along an axis "
      "pointing up (its mean within 0.15 g of +1 g, what an accelerometer at rest reads along an "
      "upward axis), as read_record's z_positive='auto' decides: (points_up, mean [m/s^2]).");
}

}  // namespace oscidrum::python
