// record_input.hpp: reading a measured acceleration record for `analyze` and `identify`: a file
// or stdin ("-"), delimiter (, ; tab or spaces) and comment lines (# % //) detected, a header
// line or none, columns by name or by 1-based index, accelerations in m/s^2 or g.
#pragma once

#include <string>
#include <vector>

#include "oscidrum/record.hpp"

namespace CLI {
class App;
}

namespace oscidrum::cli {

struct RecordInput {
  std::string file;  ///< path, or "-" for stdin
  std::string t_col = "t", x_col = "ddx_M", z_col = "ddz_M";
  std::string pos_col, speed_col;  ///< optional position [m] or speed [m/s] column
  std::string units = "m/s2";      ///< m/s2 or g (the accelerations)
};

/// The columns of a record, accelerations in m/s^2.
struct RecordColumns {
  std::vector<double> t, ddx_M, ddz_M, position;  ///< position empty without a column
  std::string delimiter;  ///< as detected: "comma", "semicolon", "tab", "whitespace"
};

/// Adds the record argument and --t-col, --x-col, --z-col, --pos-col, --speed-col, --units.
void add_record_options(CLI::App& app, RecordInput& o, bool required = true);

/// Read the record. Throws oscidrum::Error (exit 2) naming the file, line and column.
RecordColumns read_record(const RecordInput& o);

/// Adds --f, --f-min, --f-max, --harmonics, --window, --hop and the gates --max-residual,
/// --max-drift, --clip-level, --max-gap to `app`, stored in `o`. `auto_harmonics`: --harmonics
/// defaults to 0, the number chosen from the sampling (identify).
void add_window_options(CLI::App& app, WindowOptions& o, double default_window,
                        bool auto_harmonics = false);

/// One line per window that failed, for the message of a record with nothing valid.
std::string failure_reasons(const std::vector<RecordWindow>& windows);

/// Standard gravity for --units g [m/s^2].
inline constexpr double kStandardGravity = 9.80665;

}  // namespace oscidrum::cli
