// record_input.hpp: reading a measured acceleration record for `analyze` and `identify`: a file
// or stdin ("-"), delimiter (, ; tab or spaces) and comment lines (# % //) detected, a header
// line or none, columns by name or by 1-based index, accelerations in m/s^2 or g.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "oscidrum/record.hpp"
#include "oscidrum/record_reader.hpp"

namespace CLI {
class App;
}

namespace oscidrum::cli {

/// The record file and how its text is read (oscidrum::RecordReading).
struct RecordInput : RecordReading {
  std::string file;  ///< path, or "-" for stdin
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
void report_reading(const std::vector<std::string>& notes);

/// How the record was read, for the JSON outputs of analyze and identify: the columns taken, the
/// factors applied, the axis conventions (x_positive, z_positive) and the delimiter.
nlohmann::ordered_json reading_json(const RecordInput& o, const RecordColumns& rec);

/// A warning on stderr when valid windows (not a whole record taken as one) could not be checked
/// for a change of the response within them (RecordWindow::change NaN: halves too short).
void warn_unchecked_change(std::span<const RecordWindow* const> windows, const char* command);

/// The record's latitude and longitude [deg] at time t (linear between samples; NaN without
/// the columns).
std::pair<double, double> lat_lon_at(const RecordColumns& rec, double t);
/// The same for easting and northing [m].
std::pair<double, double> east_north_at(const RecordColumns& rec, double t);

/// One line per window that failed, for the message of a record with nothing valid.
std::string failure_reasons(const std::vector<RecordWindow>& windows);

}  // namespace oscidrum::cli
