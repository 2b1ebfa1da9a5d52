// output.hpp: formats of what the commands print. Stdout carries results; stderr carries
// progress, warnings and errors.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "oscidrum/output_table.hpp"

namespace oscidrum::cli {

/// %.6g (people) or %.17g (machines) formatting of a number.
std::string fmt(double v, int digits = 6);

/// A time for progress lines and summaries: "12 s", "3.5 min", "1.2 h".
std::string duration(double seconds);

/// A record's time [s] in a table: 5 significant digits, and to the millisecond from 100 s on
/// (a logger's clock in s since 1970 printed as 1.7646e+09 made every window look alike).
std::string time_text(double t);

/// A table of text cells with a header row, printable for people (aligned columns), as CSV or as
/// a Markdown table.
struct TextTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> right;  ///< per column: right-align (numbers); default left

  std::string text() const;
  std::string csv() const;
  std::string markdown() const;
};

/// The layout of TextTable::text() for `n_rows` rows fetched one at a time by `row(k)` (twice:
/// once for the column widths, once to write), so that a long table needs no memory per row.
void write_text_table(std::ostream& os, const std::vector<std::string>& header,
                      const std::vector<bool>& right, std::size_t n_rows,
                      const std::function<std::vector<std::string>(std::size_t)>& row);

/// A summary for people: sections of (label, value) lines, values aligned.
class Summary {
 public:
  void section(const std::string& title);
  void line(const std::string& label, const std::string& value);
  std::string text() const;

 private:
  struct Line {
    bool is_section;
    std::string label, value;
  };
  std::vector<Line> lines_;
};

/// "55.72 m/s^2", "0.3 (-)": a scalar output's value with its unit, for people (integers in full,
/// reals with `digits` significant digits).
template <class Struct, class... Types>
std::string output_text(const Struct& s, const Output<Struct, Types...>& out, int digits = 5) {
  if (is_text(out)) return text_value(s, out);
  const double v = scalar_value(s, out);
  const std::string unit = out.unit;
  return (is_integer(out) ? std::to_string(static_cast<long long>(v)) : fmt(v, digits)) +
         (unit == "-" ? std::string() : " " + unit);
}

/// Write `text` to `path` atomically (io::write_file_atomic), or to stdout if path is "-".
void write_output(const std::string& path, const std::string& text);

/// Check, before any work is done, that an output file named by `flag` can be written: not an
/// empty name, not a directory, a target (through symbolic links) that is a regular file or new,
/// in a directory that exists, or a FIFO or character device (io::output_target; refused with
/// `regular_only`, for HDF5). "-" (stdout) passes when `allow_stdout`. Throws oscidrum::Error
/// naming the flag.
void check_output_file(const std::string& flag, const std::string& path, bool allow_stdout = true,
                       bool regular_only = false);

/// A file a command reads or writes, named by `flag` on its command line.
struct NamedFile {
  std::string flag;  ///< "--csv", or what names an input ("the case file")
  std::string path;  ///< as given; "" (not given) and "-" (stdout, stdin) are passed over
  bool input = false;
};

/// Whether two paths name one file: one inode where both exist, else the same path once ".",
/// ".." and the symbolic links of its existing part are resolved.
bool same_file(const std::string& a, const std::string& b);

/// Throws oscidrum::Error when two of `files` name the same file, however spelt ("./r.csv" and
/// "r.csv", through "..", symbolic or hard links): one output would silently replace another, or
/// overwrite an input (a study file or a logger's record). Call before any work is done.
void check_distinct_files(const std::vector<NamedFile>& files);

/// Standard output carries one thing: whether one of `files` is "-" (it takes standard output,
/// and the command prints nothing else there). Throws oscidrum::Error when two of them are, or
/// one is and `format_given` names the --format the user gave (empty when not given): the two
/// would interleave into something no reader can parse.
bool file_takes_stdout(const std::vector<NamedFile>& files, const std::string& format_given);

/// check_output_file for a figure: also its format, from the extension (.png or .svg, as the
/// plotting module writes; any case). Throws oscidrum::Error naming the flag.
void check_plot_file(const std::string& flag, const std::string& path);

/// "oscidrum: warning: ..." on stderr.
void warn(const std::string& message);

/// Throws oscidrum::Error unless --harmonics (default 10) is below numerics.samples_per_period / 2
/// (the samples' Nyquist limit), naming both ways out; `which` follows the limit in the message
/// (" (case 3)").
void check_harmonics(int harmonics, int samples_per_period, const std::string& which = "");

}  // namespace oscidrum::cli
