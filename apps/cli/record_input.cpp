// Reading measured records (record_input.hpp).
#include "record_input.hpp"

#include <CLI/CLI.hpp>
#include <charconv>
#include <fstream>
#include <iostream>
#include <sstream>

#include "oscidrum/error.hpp"
#include "oscidrum/record.hpp"

namespace oscidrum::cli {
namespace {

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

bool is_comment(const std::string& line) {
  const std::string s = trim(line);
  return s.empty() || s[0] == '#' || s[0] == '%' || s.rfind("//", 0) == 0;
}

std::vector<std::string> split(const std::string& line, char delim) {
  std::vector<std::string> cells;
  if (delim == ' ') {
    std::istringstream in(line);
    std::string cell;
    while (in >> cell) cells.push_back(cell);
    return cells;
  }
  std::string cell;
  bool quoted = false;
  for (char ch : line) {
    if (ch == '"') {
      quoted = !quoted;
    } else if (ch == delim && !quoted) {
      cells.push_back(trim(cell));
      cell.clear();
    } else {
      cell += ch;
    }
  }
  cells.push_back(trim(cell));
  return cells;
}

bool parse_number(std::string cell, bool decimal_comma, double& v) {
  if (decimal_comma)
    for (char& ch : cell)
      if (ch == ',') ch = '.';
  if (!cell.empty() && cell[0] == '+') cell.erase(0, 1);
  const char* begin = cell.data();
  const char* end = begin + cell.size();
  const auto r = std::from_chars(begin, end, v);
  return !cell.empty() && r.ec == std::errc() && r.ptr == end;
}

}  // namespace

void add_record_options(CLI::App& app, RecordInput& o, bool required) {
  auto* record = app.add_option(
      "record", o.file,
      "CSV file of the record, or - for stdin (delimiter , ; tab or spaces and comment "
      "lines #, %, // are detected; a header line is optional)");
  if (required) record->required();
  app.add_option("--t-col", o.t_col, "time column [s]: a name or a 1-based index (default t)");
  app.add_option("--x-col", o.x_col,
                 "horizontal acceleration column x_M'': name or index (default ddx_M)");
  app.add_option("--z-col", o.z_col,
                 "vertical acceleration column z_M'', down positive: name or index (default "
                 "ddz_M)");
  app.add_option("--pos-col", o.pos_col,
                 "position column [m] (optional): each window reports its position");
  app.add_option("--speed-col", o.speed_col,
                 "speed column [m/s] (optional): integrated to the position");
  app.add_option("--units", o.units, "units of the accelerations: m/s2 (default) or g (9.80665)")
      ->check(CLI::IsMember({"m/s2", "g"}));
}

void add_window_options(CLI::App& app, WindowOptions& o, double default_window,
                        bool auto_harmonics) {
  o.window_periods = default_window;
  if (auto_harmonics) o.n_max = 0;
  app.add_option("--f", o.f,
                 "excitation frequency [Hz]; default: estimated from the record (spectral peak, "
                 "refined by least squares) and tracked from window to window")
      ->check(CLI::PositiveNumber);
  app.add_option("--f-min", o.search.f_min, "lowest frequency searched [Hz] (default 10)")
      ->check(CLI::PositiveNumber);
  app.add_option("--f-max", o.search.f_max, "highest frequency searched [Hz] (default 100)")
      ->check(CLI::PositiveNumber);
  if (auto_harmonics)
    app.add_option("--harmonics", o.n_max,
                   "harmonics n = 1 ... N fitted in each window beside a cubic trend; 0 (the "
                   "default): as many as the sampling resolves (2 N + 2 samples per period), at "
                   "most 40")
        ->check(CLI::Range(0, 200));
  else
    app.add_option("--harmonics", o.n_max, "harmonics n = 0 ... N fitted (default 10)")
        ->check(CLI::Range(2, 200));
  app.add_option("--window", o.window_periods,
                 "window length in excitation periods; 0: the whole record (default " +
                     std::to_string(static_cast<int>(default_window)) + ")")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--hop", o.hop_periods,
                 "hop between window starts in periods (default: the window length)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-residual", o.gates.max_residual,
                 "gate: largest fit residual (RMS relative to the signal) (default 0.5)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-drift", o.gates.max_drift,
                 "gate: largest relative change of f between the halves of a window (default "
                 "0.002)")
      ->check(CLI::PositiveNumber);
  app.add_option("--clip-level", o.gates.clip_level,
                 "gate: |a| at or above this is clipped [m/s^2, after --units]; default: "
                 "3 or more equal samples at a channel's extreme")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-gap", o.gates.max_gap,
                 "gate: a time step longer than this part of an excitation period is a gap "
                 "(default 0.5; a few lost samples are not)")
      ->check(CLI::PositiveNumber);
}

std::string failure_reasons(const std::vector<RecordWindow>& windows) {
  std::string out;
  std::size_t shown = 0;
  for (const RecordWindow& w : windows) {
    if (w.valid) continue;
    if (++shown > 5) {
      out += "; ...";
      break;
    }
    out += (out.empty() ? "" : "; ") + std::string("window ") + std::to_string(w.index) +
           " (t = " + std::to_string(w.t_start) + " s): " + w.reason;
  }
  return out;
}

RecordColumns read_record(const RecordInput& o) {
  const std::string name = o.file == "-" ? std::string("<stdin>") : o.file;
  std::ifstream file;
  if (o.file != "-") {
    file.open(o.file, std::ios::binary);
    if (!file) throw Error(name + ": cannot open the file");
  }
  std::istream& in = o.file == "-" ? std::cin : file;
  // Streamed: the first non-comment line sets the delimiter and the header; every other line is
  // parsed as it is read, so memory holds the columns, not the text (24 bytes per row).
  std::string line, first;
  std::size_t no = 0, first_no = 0;
  auto next_line = [&](std::string& into) {
    while (std::getline(in, into)) {
      ++no;
      if (!into.empty() && into.back() == '\r') into.pop_back();
      if (!is_comment(into)) return true;
    }
    return false;
  };
  if (!next_line(first)) throw Error(name + ": no data (the record is empty or all comments)");
  first_no = no;
  // Delimiter: the first of ; tab , that the first line holds, else whitespace.
  char delim = ' ';
  RecordColumns out;
  out.delimiter = "whitespace";
  if (first.find(';') != std::string::npos) {
    delim = ';';
    out.delimiter = "semicolon";
  } else if (first.find('\t') != std::string::npos) {
    delim = '\t';
    out.delimiter = "tab";
  } else if (first.find(',') != std::string::npos) {
    delim = ',';
    out.delimiter = "comma";
  }
  const bool decimal_comma = delim == ';';  // 1,5;2,25 (a European spreadsheet)
  // Header: the first line unless all its cells are numbers.
  std::vector<std::string> header = split(first, delim);
  bool has_header = false;
  for (const std::string& cell : header) {
    double v = 0;
    if (!parse_number(cell, decimal_comma, v)) has_header = true;
  }
  if (!has_header)
    for (std::size_t c = 0; c < header.size(); ++c) header[c] = "column " + std::to_string(c + 1);
  auto find = [&](const std::string& col, const char* flag) -> int {
    for (std::size_t c = 0; c < header.size(); ++c) {
      const std::string& h = header[c];
      if (h == col || (h.size() > col.size() && h.compare(0, col.size(), col) == 0 &&
                       (h[col.size()] == '[' || h[col.size()] == ' ')))
        return static_cast<int>(c);
    }
    int index = 0;
    const auto r = std::from_chars(col.data(), col.data() + col.size(), index);
    if (r.ec == std::errc() && r.ptr == col.data() + col.size()) {
      if (index >= 1 && index <= static_cast<int>(header.size())) return index - 1;
      throw Error(name + ": " + flag + " " + col + " is not a column index in [1, " +
                  std::to_string(header.size()) + "]");
    }
    std::string names;
    for (const std::string& h : header) names += (names.empty() ? "" : ", ") + h;
    throw Error(name + ": no column '" + col + "' (choose one with " + flag +
                ", by name or 1-based index); the header has: " + names);
  };
  const int ct = find(o.t_col, "--t-col"), cx = find(o.x_col, "--x-col"),
            cz = find(o.z_col, "--z-col");
  const int cp = o.pos_col.empty() ? -1 : find(o.pos_col, "--pos-col");
  const int cs = o.speed_col.empty() ? -1 : find(o.speed_col, "--speed-col");
  std::vector<double> speed;
  const double g = o.units == "g" ? kStandardGravity : 1.0;
  auto parse = [&](const std::string& text, std::size_t line_no) {
    const std::vector<std::string> cells = split(text, delim);
    if (cells.size() != header.size())
      throw Error(name + ":" + std::to_string(line_no) + ": " + std::to_string(cells.size()) +
                  " cells, but the header has " + std::to_string(header.size()));
    auto get = [&](int c) {
      double v = 0;
      if (!parse_number(cells[static_cast<std::size_t>(c)], decimal_comma, v))
        throw Error(name + ":" + std::to_string(line_no) + ": column '" +
                    header[static_cast<std::size_t>(c)] + "' must be a number; got '" +
                    cells[static_cast<std::size_t>(c)] + "'");
      return v;
    };
    out.t.push_back(get(ct));
    out.ddx_M.push_back(g * get(cx));
    out.ddz_M.push_back(g * get(cz));
    if (cp >= 0) out.position.push_back(get(cp));
    if (cs >= 0) speed.push_back(get(cs));
  };
  if (!has_header) parse(first, first_no);
  while (next_line(line)) parse(line, no);
  if (out.t.empty()) throw Error(name + ": no data rows after the header");
  if (cs >= 0 && cp < 0) {
    for (std::size_t i = 1; i < out.t.size(); ++i)
      if (!(out.t[i] > out.t[i - 1])) return out;  // analyze_windows reports it
    out.position = integrate_speed(out.t, speed);
  }
  return out;
}

}  // namespace oscidrum::cli
