// oscidrum/output_table.hpp: the output lists of oscidrum/outputs.hpp as tables to iterate at run
// time: name, unit, label, description and the struct member of every output. The CSV and JSON
// writers, the Python bindings, the run summary and `oscidrum outputs` read these tables.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "oscidrum/metrics.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

/// One output: a member of `Struct` of one of the `Types`.
template <class Struct, class... Types>
struct Output {
  const char* name;         ///< key in CSV headers, JSON and Python, e.g. "ddx_max"
  const char* unit;         ///< SI unit, "-" if dimensionless
  const char* label;        ///< short text for people, e.g. "x_M'' max"
  const char* description;  ///< one line, for the docs and Python docstrings
  std::variant<Types Struct::*...> member;
};

using SampleOutput = Output<Samples, SampleValues, SamplePhases>;
/// Diagnostics are numbers, except the method (an enumeration, written as its name) and the
/// fallback reason (text).
using DiagnosticOutput = Output<Diagnostics, int, long, double, SteadyMethod, std::string>;
using MetricOutput = Output<Metrics, double, Spectrum>;
using RecordOutput = Output<RecordMetrics, double, Spectrum>;

/// One Status with its name (as in to_string) and description.
struct StatusInfo {
  Status status;
  const char* name;
  const char* description;
};

/// Every output of each kind, in output order (OSCIDRUM_SAMPLE_COLUMNS, ...).
std::span<const SampleOutput> sample_outputs();
std::span<const DiagnosticOutput> diagnostic_outputs();
std::span<const MetricOutput> metric_outputs();
std::span<const RecordOutput> record_outputs();
std::span<const StatusInfo> statuses();

/// Which list an acceleration metric also belongs to: true for the outputs of
/// OSCIDRUM_ACCELERATION_METRICS (computed for simulations and measured records alike).
bool is_acceleration_metric(std::string_view name);

/// The CSV column prefix of a spectrum output: "ddx" for "ddx_harmonics" (columns ddx_A1 ...).
std::string spectrum_prefix(std::string_view name);

/// The amplitude A_n of the spectrum output `out` (ddx_harmonics, ddz_harmonics) of `m` [the
/// output's unit], NaN where `m` holds no such harmonic (n beyond its spectrum, no metrics).
double harmonic_amplitude(const Metrics& m, const MetricOutput& out, std::size_t n);

/// The largest n for which some of `metrics` holds A_n of a spectrum output (0: none).
template <class Range, class Get>
std::size_t harmonics_held(const Range& items, Get metrics_of) {
  std::size_t n = 0;
  for (const auto& item : items) {
    const Metrics& m = metrics_of(item);
    n = std::max({n, m.ddx_harmonics.empty() ? 0 : m.ddx_harmonics.size() - 1,
                  m.ddz_harmonics.empty() ? 0 : m.ddz_harmonics.size() - 1});
  }
  return n;
}

/// A scalar member's value as a double (integers converted exactly up to 2^53).
template <class Struct, class... Types>
double scalar_value(const Struct& s, const Output<Struct, Types...>& out) {
  return std::visit(
      [&s](auto member) -> double {
        if constexpr (std::is_arithmetic_v<std::remove_reference_t<decltype(s.*member)>>)
          return static_cast<double>(s.*member);
        else
          return 0.0;  // not a scalar (a spectrum or a column)
      },
      out.member);
}

/// True if the output is a scalar of integer type (int, long).
template <class Struct, class... Types>
bool is_integer(const Output<Struct, Types...>& out) {
  return std::visit(
      [](auto member) {
        using T = std::remove_cvref_t<decltype(std::declval<const Struct&>().*member)>;
        return std::is_integral_v<T>;
      },
      out.member);
}

/// True if the output is a scalar (a number, not a spectrum or a column).
template <class Struct, class... Types>
bool is_scalar(const Output<Struct, Types...>& out) {
  return std::visit(
      [](auto member) {
        using T = std::remove_cvref_t<decltype(std::declval<const Struct&>().*member)>;
        return std::is_arithmetic_v<T>;
      },
      out.member);
}

/// True if the output is text (an enumeration written by its name, or a string).
template <class Struct, class... Types>
bool is_text(const Output<Struct, Types...>& out) {
  return std::visit(
      [](auto member) {
        using T = std::remove_cvref_t<decltype(std::declval<const Struct&>().*member)>;
        return std::is_enum_v<T> || std::is_same_v<T, std::string>;
      },
      out.member);
}

/// A text output's value: the enumeration's name (to_string) or the string ("" for others).
template <class Struct, class... Types>
std::string text_value(const Struct& s, const Output<Struct, Types...>& out) {
  return std::visit(
      [&s](auto member) -> std::string {
        using T = std::remove_cvref_t<decltype(s.*member)>;
        if constexpr (std::is_enum_v<T>)
          return to_string(s.*member);
        else if constexpr (std::is_same_v<T, std::string>)
          return s.*member;
        else
          return std::string();
      },
      out.member);
}

/// True if `name` is a text column of the study CSV (status, message, the text diagnostics).
bool is_text_column(std::string_view name);

}  // namespace oscidrum
