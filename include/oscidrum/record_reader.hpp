// oscidrum/record_reader.hpp: the columns of a measured acceleration record from its text (CSV,
// semicolon, tab, pipe or whitespace separated), in the model's conventions. Pure text: the caller
// opens the file (the CLI's `analyze` and `identify`) or hands over the text (the browser
// explorer); the reader neither opens nor writes files.
#pragma once

#include <istream>
#include <string>
#include <vector>

namespace oscidrum {

/// Standard gravity, the factor of accelerations given in g [m/s^2].
inline constexpr double kStandardGravity = 9.80665;

/// How a record's text is read: the columns (empty: recognised from the header), the units and
/// the axis conventions (the options of `oscidrum analyze` and `identify`, docs/cli.md).
struct RecordReading {
  /// Column names or 1-based indices; empty: recognised from the header (t, time, ...; ddx_M,
  /// ax, acc_x, ...; ddz_M, az, acc_z, ...: see read_record).
  std::string t_col, x_col, z_col;
  std::string pos_col, speed_col;   ///< optional position [m] or speed [m/s] column
  std::string lat_col, lon_col;     ///< optional GNSS latitude, longitude [deg, WGS 84]
  std::string east_col, north_col;  ///< optional projected easting, northing [m]
  /// Optional angle of the vibratory drum's unbalance [rad]: alpha with the unbalance force's
  /// downward component F0 sin(alpha) (z down), so alpha = nu t for oscidrum's own exciters
  /// (docs/model.md section 14); kb of a record needs it (docs/outputs.md).
  std::string unbalance_col;
  std::string units = "auto";    ///< the accelerations: auto (the header's), m/s2, g or mg
  std::string t_units = "auto";  ///< the time column: auto (the header's, else s), s, ms, us, ns
  /// Sampling rate [Hz] of a record without a time column, 1 ... 1e7: > 0 gives t = (data row - 1)
  /// / rate and no time column is read (0: the time column). Rows skipped for missing values keep
  /// their place in time.
  double rate = 0.0;
  std::string x_positive = "forward";  ///< forward (the model's x) or backward
  /// down (the model's z), up (negated), or auto: down (up for a two-dimensional record's y,
  /// read as the vertical when there is no z column) unless the column's mean says otherwise
  /// (an accelerometer at rest reads +1 g along an axis pointing up: then turned, with a note).
  std::string z_positive = "auto";
};

/// The columns of a record in the model's conventions: t in s, accelerations in m/s^2, x_M''
/// positive forward (the direction of travel), z_M'' positive down.
struct RecordColumns {
  std::vector<double> t, ddx_M, ddz_M, position;  ///< position empty without a column
  std::vector<double> lat, lon;     ///< GNSS latitude, longitude [deg] (empty without the columns)
  std::vector<double> east, north;  ///< projected easting, northing [m] (empty without them)
  std::vector<double> unbalance_angle;  ///< the unbalance's angle [rad] (empty without a column)
  std::string delimiter;  ///< as detected: "comma", "semicolon", "tab", "pipe", "whitespace"
  /// How each column was read, for the summary: "t: 'Time [ms]' (ms)" and so on.
  std::vector<std::string> notes;
  /// The column each of t, x_M'', z_M'' was read from (its header, or its 1-based index without
  /// one) and the factor applied to reach the model's units and signs [s or m/s^2 per unit read].
  std::string t_column, x_column, z_column;
  double t_factor = 1.0, x_factor = 1.0, z_factor = 1.0;
  std::string z_positive = "down";  ///< which way the z column was read to point: down or up
  /// z_positive "auto" found no gravity in the column: its direction is auto's first guess
  /// (down; a two-dimensional record's y: up), which identify may turn when the fit says so
  /// (IdentifyOptions::z_open). False when the direction was given or gravity decided it.
  bool z_open = false;
  /// The accelerations have no unit (no --units, none in the header: read in m/s^2) and no
  /// gravity in g told it (a vertical mean of about +-1, which reads them in g, with a note):
  /// identify may read them in g when the fit says so (IdentifyOptions::units_open).
  bool units_open = false;
};

/// Read a record from `in` (`name` names it in messages: the file, "<stdin>"): a UTF-8
/// byte-order mark is dropped; comment lines (# % //) are skipped; the delimiter is the first of
/// ; tab , on the first line, else whitespace (with ';' a decimal comma); the first line is a
/// header unless all its cells are numbers. Streamed: memory holds the columns, not the text
/// (but for UTF-16 text, recognised by its byte-order mark and converted whole). A file that is
/// not text (gzip, zip or xlsx, xls, HDF5, NUL bytes) is refused with what it is.
/// Throws oscidrum::Error naming the record, line and column, or the option to give.
RecordColumns read_record(std::istream& in, const std::string& name, const RecordReading& o);

/// How far from +1 g the mean of a vertical acceleration may lie and still be gravity read along
/// an upward axis (gravity_points_up) [-, a fraction of kStandardGravity].
inline constexpr double kGravityBand = 0.15;

/// Whether a vertical acceleration read as positive down [m/s^2] keeps gravity along an axis that
/// points up: an accelerometer reads the specific force, at rest +1 g along an upward axis and
/// -1 g along a downward one, so a mean within kGravityBand g of +1 g says the axis points up
/// (z_positive "auto" then turns the column). `mean` receives the column's mean [m/s^2] (NaN for
/// an empty column, which never points up).
bool gravity_points_up(const std::vector<double>& ddz_M, double* mean = nullptr);

}  // namespace oscidrum
