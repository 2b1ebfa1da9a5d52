// Text tables, summaries and output files.
#include "output.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "oscidrum/error.hpp"
#include "oscidrum/text.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/files.hpp"

namespace oscidrum::cli {

std::string fmt(double v, int digits) {
  if (std::isnan(v)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string time_text(double t) {
  if (!(std::abs(t) >= 100.0) || !std::isfinite(t)) return fmt(t, 5);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", t);
  return buf;
}

std::string duration(double seconds) {
  if (seconds < 60) return fmt(seconds, 2) + " s";
  if (seconds < 3600) return fmt(seconds / 60, 2) + " min";
  return fmt(seconds / 3600, 2) + " h";
}

void write_text_table(std::ostream& os, const std::vector<std::string>& header,
                      const std::vector<bool>& right, std::size_t n_rows,
                      const std::function<std::vector<std::string>(std::size_t)>& row) {
  std::vector<std::size_t> width(header.size(), 0);
  for (std::size_t i = 0; i < header.size(); ++i) width[i] = header[i].size();
  for (std::size_t k = 0; k < n_rows; ++k) {
    const std::vector<std::string> cells = row(k);
    for (std::size_t i = 0; i < cells.size() && i < width.size(); ++i)
      width[i] = std::max(width[i], cells[i].size());
  }
  auto emit = [&](const std::vector<std::string>& cells) {
    std::string line;
    for (std::size_t i = 0; i < width.size(); ++i) {
      const std::string cell = i < cells.size() ? cells[i] : std::string();
      const std::string pad(width[i] - cell.size(), ' ');
      const bool r = i < right.size() && right[i];
      line += (i ? "  " : "") + (r ? pad + cell : cell + (i + 1 < width.size() ? pad : ""));
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    os << line << '\n';
  };
  emit(header);
  std::vector<std::string> rule;
  for (std::size_t w : width) rule.emplace_back(w, '-');
  emit(rule);
  for (std::size_t k = 0; k < n_rows; ++k) emit(row(k));
}

std::string TextTable::text() const {
  std::ostringstream out;
  write_text_table(out, header, right, rows.size(), [&](std::size_t k) { return rows[k]; });
  return out.str();
}

std::string TextTable::csv() const {
  auto emit = [](const std::vector<std::string>& cells) {
    std::string line;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i) line += ',';
      line += io::csv_quote(cells[i]);
    }
    return line + "\n";
  };
  std::string out = emit(header);
  for (const auto& row : rows) out += emit(row);
  return out;
}

std::string TextTable::markdown() const {
  auto cell = [](std::string s) {
    std::string out;
    for (char ch : s) {
      if (ch == '|') out += '\\';
      out += ch;
    }
    return out;
  };
  auto emit = [&](const std::vector<std::string>& cells) {
    std::string line = "|";
    for (const std::string& c : cells) {
      line += ' ';  // (appends: GCC 12 warns falsely on "literal" + std::string&&)
      line += cell(c);
      line += " |";
    }
    return line + "\n";
  };
  std::string out = emit(header);
  out += "|";
  for (std::size_t i = 0; i < header.size(); ++i)
    out += (i < right.size() && right[i]) ? "---:|" : "---|";
  out += "\n";
  for (const auto& row : rows) out += emit(row);
  return out;
}

void Summary::section(const std::string& title) { lines_.push_back({true, title, ""}); }

void Summary::line(const std::string& label, const std::string& value) {
  lines_.push_back({false, label, value});
}

std::string Summary::text() const {
  std::size_t width = 0;
  for (const Line& l : lines_)
    if (!l.is_section) width = std::max(width, l.label.size());
  std::string out;
  for (const Line& l : lines_) {
    if (l.is_section) {
      out += (out.empty() ? "" : "\n") + l.label + "\n";
    } else {
      out += "  " + l.label + std::string(width - l.label.size() + 2, ' ') + l.value + "\n";
    }
  }
  return out;
}

void write_output(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::cout << text << std::flush;
  } else {
    io::write_file_atomic(path, text);
  }
}

void check_plot_file(const std::string& flag, const std::string& path) {
  std::error_code ec;
  if (!path.empty() && std::filesystem::is_directory(path, ec))
    throw Error(flag + " " + path + " is a directory; give the figure's file name (e.g. " +
                (std::filesystem::path(path) / "figure.png").string() + ")");
  check_output_file(flag, path, false);
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext != ".png" && ext != ".svg")
    throw Error(flag + " " + path + ": the figure's format comes from its extension: .png or .svg" +
                (ext.empty() ? std::string(" (none given)") : "; got " + ext));
}

void check_output_file(const std::string& flag, const std::string& path, bool allow_stdout,
                       bool regular_only) {
  if (path.empty())
    throw Error(flag + " needs a file name; got an empty one" +
                (allow_stdout ? std::string(" ('-' is stdout)") : std::string()));
  if (path == "-") {
    if (allow_stdout) return;
    // Elsewhere '-' is standard output: a file of that name in the working directory is not what
    // was meant (--hdf5 - wrote one, exit 0).
    throw Error(flag + " writes a file, not standard output: give a file name; got '-'");
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error(flag + " " + path + " is a directory; give a file name (e.g. " +
                (std::filesystem::path(path) / "results.csv").string() + ")");
  io::OutputTarget target;
  try {
    target = io::output_target(path, regular_only);
  } catch (const Error& e) {
    throw Error(flag + ": " + e.what());
  }
  if (target.direct) return;  // a FIFO or device: written in place
  // The file is written beside its target (through symbolic links) and renamed over it.
  const std::filesystem::path parent = std::filesystem::path(target.path).parent_path();
  const std::string shown = target.path == path ? path : path + " (-> " + target.path + ")";
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    throw Error(flag + " " + shown + ": the directory " + parent.string() + " does not exist");
  if (::access(parent.empty() ? "." : parent.c_str(), W_OK) != 0)
    throw Error(flag + " " + shown + ": cannot write into " +
                (parent.empty() ? std::string("the current directory") : parent.string()) + ": " +
                std::strerror(errno));
  // Permissions are not everything (root may write anywhere, yet /proc takes no new file): the
  // temporary file the output is written through is created, and removed again.
  try {
    io::OutputFile probe(path, regular_only);
  } catch (const Error& e) {
    throw Error(flag + ": " + e.what());
  }
}

bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    return !ec && same;
  }
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec);
  if (ec) return false;
  const fs::path cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !ec && ca == cb;
}

void check_distinct_files(const std::vector<NamedFile>& files) {
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = i + 1; j < files.size(); ++j) {
      const NamedFile &a = files[i], &b = files[j];
      if (a.path.empty() || b.path.empty() || a.path == "-" || b.path == "-") continue;
      if (a.input && b.input) continue;
      if (!same_file(a.path, b.path)) continue;
      if (a.input || b.input) {
        const NamedFile &in = a.input ? a : b, &out = a.input ? b : a;
        throw Error(out.flag + " " + out.path + " names the input, " + in.flag + " " + in.path +
                    ", which writing it would overwrite; name the output otherwise");
      }
      throw Error(a.flag + " " + a.path + " and " + b.flag + " " + b.path +
                  " name the same file: one output would replace the other; name them otherwise");
    }
}

bool file_takes_stdout(const std::vector<NamedFile>& files, const std::string& format_given) {
  std::vector<std::string> to_stdout;
  for (const NamedFile& f : files)
    if (!f.input && f.path == "-") to_stdout.push_back(f.flag + " -");
  if (!format_given.empty() && !to_stdout.empty()) to_stdout.push_back("--format " + format_given);
  if (to_stdout.size() > 1)
    throw Error(to_stdout[0] + " and " + to_stdout[1] +
                " would both write to standard output; send one of them to a file");
  return !to_stdout.empty();
}

void check_harmonics(int harmonics, int samples_per_period, const std::string& which) {
  if (harmonics < samples_per_period / 2) return;
  throw Error("--harmonics (default 10) must be below numerics.samples_per_period / 2 = " +
              std::to_string(samples_per_period / 2) + ", the samples' Nyquist limit" + which +
              "; got " + std::to_string(harmonics) + ": give --harmonics " +
              std::to_string(std::max(0, samples_per_period / 2 - 1)) +
              " or less, or numerics.samples_per_period of at least " +
              std::to_string(2 * harmonics + 2));
}

void warn(const std::string& message) {
  std::cerr << "oscidrum: warning: " << printable(message) << "\n";
}

}  // namespace oscidrum::cli
