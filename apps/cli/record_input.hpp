// record_input.hpp: reading a measured acceleration record for `analyze` and `identify`: a file
// or stdin ("-"), delimiter (, ; tab or spaces) and comment lines (# % //) detected, a header
// line or none, columns by name or by 1-based index, accelerations in m/s^2 or g.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "oscidrum/record.hpp"

namespace CLI {
class App;
}

namespace oscidrum::cli {

struct RecordInput {
  std::string file;  ///< path, or "-" for stdin
  /// Column names or 1-based indices; empty: recognised from the header (t, time, ...; ddx_M,
  /// ax, acc_x, ...; ddz_M, az, acc_z, ...: see read_record).
  std::string t_col, x_col, z_col;
  std::string pos_col, speed_col;      ///< optional position [m] or speed [m/s] column
  std::string lat_col, lon_col;        ///< optional GNSS latitude, longitude [deg, WGS 84]
  std::string east_col, north_col;     ///< optional projected easting, northing [m]
  std::string units = "auto";          ///< the accelerations: auto (the header's), m/s2 or g
  std::string t_units = "auto";        ///< the time column: auto (the header's, else s), s, ms, us
  std::string x_positive = "forward";  ///< forward (the model's x) or backward
  std::string z_positive = "down";     ///< down (the model's z) or up
};

/// The columns of a record in the model's conventions: t in s, accelerations in m/s^2, x_M''
/// positive forward (the direction of travel), z_M'' positive down.
struct RecordColumns {
  std::vector<double> t, ddx_M, ddz_M, position;  ///< position empty without a column
  std::vector<double> lat, lon;     ///< GNSS latitude, longitude [deg] (empty without the columns)
  std::vector<double> east, north;  ///< projected easting, northing [m] (empty without them)
  std::string delimiter;            ///< as detected: "comma", "semicolon", "tab", "whitespace"
  /// How each column was read, for the summary: "t: 'Time [ms]' (ms)" and so on.
  std::vector<std::string> notes;
  /// The column each of t, x_M'', z_M'' was read from (its header, or its 1-based index without
  /// one) and the factor applied to reach the model's units and signs [s or m/s^2 per unit read].
  std::string t_column, x_column, z_column;
  double t_factor = 1.0, x_factor = 1.0, z_factor = 1.0;
};

/// Adds the record argument and --t-col, --x-col, --z-col, --pos-col, --speed-col, --units,
/// --t-units, --x-positive, --z-positive. `file_and_position` false: only how the columns are read
/// (no record argument, no position or GNSS columns), for a command that takes several records.
void add_record_options(CLI::App& app, RecordInput& o, bool required = true,
                        bool file_and_position = true);

/// Read the record. Throws oscidrum::Error (exit 2) naming the file, line and column.
RecordColumns read_record(const RecordInput& o);

/// Adds --f, --f-min, --f-max, --harmonics, --window, --hop and the gates --max-residual,
/// --max-drift, --clip-level, --max-gap to `app`, stored in `o`. `auto_harmonics`: --harmonics
/// defaults to 0, the number chosen from the sampling (identify).
void add_window_options(CLI::App& app, WindowOptions& o, double default_window,
                        bool auto_harmonics = false);

/// The notes of read_record on stderr ("oscidrum: record: x_M'': column 'acc_x [g]' x 9.80665 ->
/// m/s^2 (positive forward)"), one per channel not read as the model writes it.
void report_reading(const RecordColumns& rec);

/// How the record was read, for the JSON outputs of analyze and identify: the columns taken, the
/// factors applied, the axis conventions (x_positive, z_positive) and the delimiter.
nlohmann::ordered_json reading_json(const RecordInput& o, const RecordColumns& rec);

/// The record's latitude and longitude [deg] at time t (linear between samples; NaN without
/// the columns).
std::pair<double, double> lat_lon_at(const RecordColumns& rec, double t);
/// The same for easting and northing [m].
std::pair<double, double> east_north_at(const RecordColumns& rec, double t);

/// One line per window that failed, for the message of a record with nothing valid.
std::string failure_reasons(const std::vector<RecordWindow>& windows);

/// Standard gravity for --units g [m/s^2].
inline constexpr double kStandardGravity = 9.80665;

}  // namespace oscidrum::cli
