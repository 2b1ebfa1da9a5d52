// CSV writers: steady state (docs/csv-columns.md), events, sweep results (docs/outputs.md).
#include "oscidrum_io/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <span>
#include <type_traits>
#include <variant>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/output_table.hpp"

namespace oscidrum::io {
namespace {

std::string join(const std::vector<std::string>& cells) {
  std::string s;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) s += ',';
    s += cells[i];
  }
  return s;
}

std::string label(const std::string& name, const std::string& unit) {
  return name + "[" + unit + "]";
}

}  // namespace

std::string format_double(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string format_double_short(double v) {
  if (!std::isfinite(v)) return format_double(v);
  char buf[64];
  if (v == std::trunc(v) && std::abs(v) < 1e15) {  // whole numbers as such: 5000000, not 5e+06
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return std::string(buf) == "-0" ? "0" : buf;
  }
  // The shortest %.*g that reads back as exactly v.
#ifdef __EMSCRIPTEN__
  // (Emscripten 3.1.6's libc++ has no floating-point std::to_chars.)
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
#else
  // No precision below the number of digits of the shortest text that reads back as v
  // (std::to_chars) reads back, so the search starts there: the same text as trying 1, 2, ...,
  // without formatting and parsing each (the bulk of a sweep's CSV writing). to_chars with a
  // precision writes what %.*g writes.
  const auto shortest = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  int precision = 0;
  for (const char* c = buf; c != shortest.ptr && *c != 'e'; ++c)
    precision += *c >= '0' && *c <= '9';
  for (precision = std::max(precision, 1); precision <= 17; ++precision) {
    const auto r =
        std::to_chars(buf, buf + sizeof buf - 1, v, std::chars_format::general, precision);
    *r.ptr = '\0';
    double back = 0.0;
    std::from_chars(buf, r.ptr, back);
    if (back == v) break;
  }
  return buf;
#endif
}

std::string csv_quote(std::string_view field) {
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(field);
  std::string s = "\"";
  for (char ch : field) {
    if (ch == '"') s += '"';
    s += ch;
  }
  return s + "\"";
}

std::vector<std::string> csv_split(std::string_view line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        out.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      out.emplace_back();
    } else {
      out.back() += ch;
    }
  }
  return out;
}

void write_steady_state_csv(std::ostream& out, const Result& result) {
  const std::span<const SampleOutput> columns = sample_outputs();
  std::vector<std::string> header;
  for (const SampleOutput& c : columns) header.push_back(label(c.name, c.unit));
  out << join(header) << '\n';
  const Samples& s = result.samples;
  std::string row;
  for (std::size_t j = 0; j < s.size(); ++j) {
    row.clear();
    for (const SampleOutput& c : columns) {
      if (!row.empty()) row += ',';
      std::visit(
          [&](auto member) {
            const auto& column = s.*member;
            using T = typename std::remove_cvref_t<decltype(column)>::value_type;
            if constexpr (std::is_same_v<T, Phase>)
              row += j < column.size() ? std::to_string(static_cast<int>(column[j])) : "0";
            else
              row += j < column.size() ? format_double(column[j]) : std::string("nan");
          },
          c.member);
    }
    out << row << '\n';
  }
}

void write_events_csv(std::ostream& out, const Result& result) {
  out << "t[s],kind,from,to\n";
  for (const Event& e : result.events)
    out << format_double(e.t) << ',' << to_string(e.kind) << ',' << to_string(e.from) << ','
        << to_string(e.to) << '\n';
}

std::string study_csv_header(const StudyColumns& columns) {
  std::vector<std::string> h = {"case[-]"};
  for (const std::string& key : columns.keys) {
    const std::string unit = key_unit(key);
    h.push_back(csv_quote(label(key, unit.empty() ? "-" : unit)));
  }
  h.emplace_back("status[-]");
  h.emplace_back("message[-]");
  for (const DiagnosticOutput& d : diagnostic_outputs()) h.push_back(label(d.name, d.unit));
  for (const MetricOutput& m : metric_outputs()) {
    if (is_scalar(m)) {
      h.push_back(label(m.name, m.unit));
    } else {  // a spectrum: the amplitudes A_1 ... A_N
      for (int n = 1; n <= columns.n_harmonics; ++n)
        h.push_back(label(spectrum_prefix(m.name) + "_A" + std::to_string(n), m.unit));
    }
  }
  return join(h);
}

std::string study_csv_row(const StudyColumns& columns, std::size_t index,
                          const std::vector<Value>& varied, const CaseOutcome& outcome) {
  std::vector<std::string> r = {std::to_string(index)};
  for (std::size_t i = 0; i < columns.keys.size(); ++i)
    r.push_back(i < varied.size() ? csv_quote(format_value(varied[i])) : std::string());
  const Result& res = outcome.result;
  std::size_t metric_cells = 0;
  for (const MetricOutput& m : metric_outputs())
    metric_cells += is_scalar(m) ? 1 : static_cast<std::size_t>(columns.n_harmonics);
  if (!outcome.valid) {
    r.emplace_back("invalid");
    r.push_back(csv_quote(outcome.error));
    r.resize(r.size() + diagnostic_outputs().size() + metric_cells);  // empty cells
    return join(r);
  }
  r.emplace_back(to_string(res.status));
  r.push_back(csv_quote(res.message));
  for (const DiagnosticOutput& d : diagnostic_outputs()) {
    if (is_text(d)) {
      r.push_back(csv_quote(text_value(res.diagnostics, d)));
      continue;
    }
    const double v = scalar_value(res.diagnostics, d);
    // A diagnostic that does not apply (NaN: phi_drift of a status other than a steady state or
    // gross slip, final_change before two period boundaries, switches_per_period without a sampled
    // window) is an empty cell, as docs/outputs.md says, and null in JSON.
    r.push_back(is_integer(d)   ? std::to_string(static_cast<long long>(v))
                : std::isnan(v) ? std::string()
                                : format_double_short(v));
  }
  if (!ok(res.status)) {  // only a steady state has metrics (its samples may not be kept)
    r.resize(r.size() + metric_cells);
    return join(r);
  }
  const Metrics& m = outcome.metrics;
  for (const MetricOutput& out : metric_outputs()) {
    if (is_scalar(out)) {
      r.push_back(format_double_short(scalar_value(m, out)));
      continue;
    }
    const Spectrum& h = m.*std::get<Spectrum Metrics::*>(out.member);
    for (std::size_t n = 1; n <= static_cast<std::size_t>(columns.n_harmonics); ++n)
      r.push_back(n < h.size() ? format_double_short(h[n].amplitude) : std::string());
  }
  return join(r);
}

std::string study_row_defect(const std::vector<std::string>& header, std::string_view row) {
  const std::vector<std::string> cells = csv_split(row);
  if (cells.size() != header.size())
    return "it has " + std::to_string(cells.size()) + " cells where the header has " +
           std::to_string(header.size());
  const auto status_at = std::find(header.begin(), header.end(), label("status", "-"));
  if (status_at == header.end()) return "the header has no column status[-]";
  const std::size_t s = static_cast<std::size_t>(status_at - header.begin());
  const auto index_end = std::find_if_not(cells[0].begin(), cells[0].end(),
                                          [](char ch) { return ch >= '0' && ch <= '9'; });
  if (cells[0].empty() || index_end != cells[0].end())
    return "its first cell '" + cells[0] + "' is not a case index";
  const std::string& status = cells[s];
  const auto known = statuses();
  if (status != "invalid" && std::none_of(known.begin(), known.end(),
                                          [&](const StatusInfo& k) { return status == k.name; }))
    return "its status '" + status + "' is not one of oscidrum's statuses";
  // After status and message: the diagnostics (some of them text), then the metrics (numbers).
  std::size_t c = s + 2;
  const auto number = [](const std::string& cell) {
    if (cell.empty()) return true;
    char* end = nullptr;
    (void)std::strtod(cell.c_str(), &end);
    return end == cell.c_str() + cell.size() && cell.find_first_of(" \t") == std::string::npos;
  };
  for (const DiagnosticOutput& d : diagnostic_outputs()) {
    if (c >= cells.size()) break;
    if (!is_text(d) && !number(cells[c]))
      return "its cell '" + cells[c] + "' in column " + header[c] + " is not a number";
    ++c;
  }
  for (; c < cells.size(); ++c)
    if (!number(cells[c]))
      return "its cell '" + cells[c] + "' in column " + header[c] + " is not a number";
  return {};
}

int NumericTable::find(std::string_view name) const {
  for (std::size_t c = 0; c < header.size(); ++c) {
    const std::string& h = header[c];
    if (h == name ||
        (h.size() > name.size() && h.compare(0, name.size(), name) == 0 && h[name.size()] == '['))
      return static_cast<int>(c);
  }
  return -1;
}

NumericTable read_numeric_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the file");
  NumericTable table;
  std::string line;
  std::size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells = csv_split(line);
    for (std::string& cell : cells) {
      const std::size_t a = cell.find_first_not_of(" \t"), b = cell.find_last_not_of(" \t");
      cell = a == std::string::npos ? std::string() : cell.substr(a, b - a + 1);
    }
    if (table.header.empty()) {
      table.header = cells;
      table.columns.resize(cells.size());
      continue;
    }
    if (cells.size() != table.header.size())
      throw Error(path + ":" + std::to_string(line_no) + ": " + std::to_string(cells.size()) +
                  " cells, but the header has " + std::to_string(table.header.size()));
    for (std::size_t c = 0; c < cells.size(); ++c) {
      double v = 0.0;
      const char* begin = cells[c].data();
      const char* end = begin + cells[c].size();
      const auto r = std::from_chars(begin, end, v);
      if (cells[c].empty() || r.ec != std::errc() || r.ptr != end)
        throw Error(path + ":" + std::to_string(line_no) + ": column '" + table.header[c] +
                    "' must be a number; got '" + cells[c] + "'");
      table.columns[c].push_back(v);
    }
  }
  if (table.header.empty()) throw Error(path + ": no header line (the file is empty)");
  return table;
}

}  // namespace oscidrum::io
