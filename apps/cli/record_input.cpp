// Reading measured records (record_input.hpp).
#include "record_input.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <utility>

#include "flags.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/record.hpp"

namespace oscidrum::cli {

void add_record_options(CLI::App& app, RecordInput& o, bool required, bool file_and_position) {
  if (file_and_position) {
    auto* record = app.add_option(
        "record", o.file,
        "CSV file of the record, or - for stdin (delimiter , ; tab or spaces and comment "
        "lines #, %, // are detected; a header line is optional)");
    if (required) record->required();
  }
  app.add_option("--t-col", o.t_col,
                 "time column: a name or a 1-based index (default: recognised from the header: "
                 "t, time, zeit, timestamp, ...)");
  app.add_option("--x-col", o.x_col,
                 "horizontal acceleration column x_M'': name or index (default: recognised: "
                 "ddx_M, ax, a_x, acc_x, accel_x, x_acc, horizontal, ...; a bare X if nothing else "
                 "matches; a y column beside z where no x is; y or z, whichever moves more, "
                 "where x has gravity in m/s^2 in its mean and y and z do not: a logger mounted "
                 "x vertical)");
  app.add_option(
      "--z-col", o.z_col,
      "vertical acceleration column z_M'': name or index (default: recognised: ddz_M, "
      "az, a_z, acc_z, accel_z, z_acc, vertical, ...; a bare Z if nothing else matches; a "
      "y column instead where it, not z, has gravity in its mean (a logger mounted y vertical), "
      "or where z never changes and y does; x where it alone has gravity in m/s^2)");
  if (file_and_position) {
    app.add_option(
        "--pos-col", o.pos_col,
        "position column [m] (optional; a unit in its header, km, cm, ft, is read): each "
        "window reports its position");
    app.add_option(
        "--speed-col", o.speed_col,
        "speed column [m/s] (optional; a unit in its header, km/h, m/min, mph, is read): "
        "integrated to the position");
    app.add_option("--lat-col", o.lat_col,
                   "GNSS latitude column [deg, WGS 84] (optional, with --lon-col): each window "
                   "gets the point at its centre (identify --geojson); default: a header's one "
                   "lat/Latitude/GPS Lat/Breite and one lon/Longitude/Laenge column, else its one "
                   "Easting/Rechtswert and one Northing/Hochwert column, with a note");
    app.add_option("--lon-col", o.lon_col, "GNSS longitude column [deg, WGS 84] (with --lat-col)");
    app.add_option("--east-col", o.east_col,
                   "projected easting column [m] (optional, with --north-col): each window gets "
                   "its easting and northing, and without --pos-col/--speed-col its position is "
                   "the path length along them");
    app.add_option("--north-col", o.north_col, "projected northing column [m] (with --east-col)");
  }
  app.add_option(
         "--units", o.units,
         "units of the accelerations: auto (default: each column's unit from its header, "
         "[m/s^2], [g], (mm/s2), az_g, ...; without one m/s^2, or g when the vertical's mean is "
         "about +-1, gravity in g; identify fits g where only that fits), m/s2, g "
         "(9.80665 m/s^2) or mg (a thousandth of g)")
      ->check(CLI::IsMember({"auto", "m/s2", "g", "mg"}));
  app.add_option("--t-units", o.t_units,
                 "unit of the time column: auto (default: from its header, [s], [ms], time_ms, "
                 "...; s without one), s, ms, us or ns")
      ->check(CLI::IsMember({"auto", "s", "ms", "us", "ns"}));
  app.add_option("--rate", o.rate,
                 "sampling rate [Hz], 1 ... 1e7, of a record without a time column: t = (data "
                 "row - 1) / rate (instead of --t-col; a row skipped for a missing value keeps "
                 "its place; default: the rate a line before the data states, 'Sample rate: "
                 "1000 Hz', 'fs = 2 kHz', 'Sample interval: 1 ms')")
      ->check(positive_number());
  app.add_option("--x-positive", o.x_positive,
                 "which way the record's x axis points: forward (default: the model's, the "
                 "direction of travel, where a positive driving torque MMd moves the drum) or "
                 "backward (x_M'' is negated)")
      ->check(CLI::IsMember({"forward", "backward"}));
  app.add_option("--z-positive", o.z_positive,
                 "which way the record's z axis points: auto (default: down, the model's, or up "
                 "for a two-dimensional record's y, unless the column's mean says otherwise: an "
                 "accelerometer at rest reads +1 g along an axis pointing up, -1 g along one "
                 "pointing down; with a note; without gravity in the column identify fits z_M'' "
                 "negated where only that fits, with a warning), down, or up (most accelerometer "
                 "mounts; z_M'' is negated)")
      ->check(CLI::IsMember({"auto", "down", "up"}));
}

void add_window_options(CLI::App& app, WindowOptions& o, double default_window,
                        bool auto_harmonics) {
  o.window_periods = default_window;
  if (auto_harmonics) o.n_max = 0;
  app.add_option("--f", o.f,
                 "excitation frequency [Hz]; default: estimated from the record (spectral peak, "
                 "refined by least squares) and tracked from window to window")
      ->check(positive_number());
  app.add_option("--f-min", o.search.f_min, "lowest frequency searched [Hz] (default 10)")
      ->check(positive_number());
  app.add_option("--f-max", o.search.f_max, "highest frequency searched [Hz] (default 100)")
      ->check(positive_number());
  if (auto_harmonics)
    app.add_option("--harmonics", o.n_max,
                   "harmonics n = 1 ... N fitted in each window beside a cubic trend; 0 (the "
                   "default): as many as the sampling resolves (2 N + 2 samples per period), at "
                   "most 40")
        ->check(CLI::Range(0, kMaxRecordHarmonics));
  else
    app.add_option("--harmonics", o.n_max,
                   "harmonics n = 0 ... N fitted (default 10, or as many as the record's "
                   "sampling resolves when fewer: 2 N + 1 samples per period)")
        ->check(CLI::Range(2, kMaxRecordHarmonics));
  app.add_option("--window", o.window_periods,
                 "window length in excitation periods, >= 1; 0: the whole record (default " +
                     std::to_string(static_cast<int>(default_window)) +
                     (default_window > 0 ? "; a record shorter than that is taken whole, as one "
                                           "window, with a note"
                                         : "") +
                     ")")
      ->check(non_negative_number());
  app.add_option("--hop", o.hop_periods,
                 "hop between window starts in periods (default: the window length)")
      ->check(non_negative_number());
  app.add_option("--max-residual", o.gates.max_residual,
                 "gate: largest fit residual (RMS relative to the signal) (default 0.5)")
      ->check(positive_number());
  app.add_option("--max-drift", o.gates.max_drift,
                 "gate: largest relative change of f between parts of a window (its quarters, "
                 "beyond the noise; default 0.002)")
      ->check(positive_number());
  app.add_option("--clip-level", o.gates.clip_level,
                 "gate: |a| at or above this is clipped [m/s^2, after --units]; default: "
                 "3 or more equal samples at a channel's extreme")
      ->check(non_negative_number());
  app.add_option("--max-gap", o.gates.max_gap,
                 "gate: a time step longer than this part of an excitation period is a gap "
                 "(default 0.5; a few lost samples are not)")
      ->check(positive_number());
  app.add_option("--max-change", o.gates.max_change,
                 "gate: largest change of the response within a window, |RMS(later part) - "
                 "RMS(earlier part)| / RMS of the fitted x_M'' or z_M'' over the window's 4 (3, 2) "
                 "equal parts, beyond the noise (default 0.05; a window across a change of soil "
                 "fits neither side)")
      ->check(positive_number());
}

void report_reading(const std::vector<std::string>& notes) {
  for (const std::string& n : notes) std::cerr << "oscidrum: record: " << n << "\n";
}

void report_reading(const RecordColumns& rec) { report_reading(rec.notes); }

void warn_unchecked_change(std::span<const RecordWindow* const> windows, const char* command) {
  std::size_t unchecked = 0, valid = 0;
  for (const RecordWindow* w : windows) {
    if (!w->valid || w->whole) continue;
    ++valid;
    if (std::isnan(w->change)) ++unchecked;
  }
  if (unchecked == 0) return;
  const int n =
      windows.empty() ? 0 : static_cast<int>(windows.front()->metrics.ddx_harmonics.size()) - 1;
  std::cerr << "oscidrum: " << command << ": warning: " << unchecked << " of " << valid
            << " valid windows are too short to check whether the response changes within them "
               "(each half needs one period and "
            << 2 * (2 * std::max(n, 0) + 1)
            << " samples, twice its fit's coefficients): a window across a change of the soil "
               "passes with mixed metrics; give a longer --window, or fewer --harmonics\n";
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
    std::error_code ec;
    if (std::filesystem::is_directory(o.file, ec))
      throw Error(name + ": is a directory, not a record file");
    file.open(o.file, std::ios::binary);
    if (!file)
      throw Error(name + ": cannot open the file (" +
                  (std::filesystem::exists(o.file, ec) ? "not readable" : "no such file") + ")");
  }
  RecordColumns rec = oscidrum::read_record(o.file == "-" ? std::cin : file, name, o);
  // Said with the file's name here (the analysis would say "record: needs at least 2 samples").
  if (rec.t.size() < 2)
    throw Error(name +
                ": one data row; a record needs at least 2 samples (and for its "
                "frequency and harmonics, at least one excitation period of them)");
  return rec;
}

}  // namespace oscidrum::cli

namespace oscidrum::cli {

namespace {

// Two columns a, b of the record at time `at` (linear between samples; the first or last value
// outside the record; NaN without the columns).
std::pair<double, double> pair_at(const std::vector<double>& t, const std::vector<double>& a,
                                  const std::vector<double>& b, double at) {
  if (a.empty() || a.size() != t.size() || b.size() != t.size()) return {NAN, NAN};
  const auto it = std::lower_bound(t.begin(), t.end(), at);
  const std::size_t j = static_cast<std::size_t>(it - t.begin());
  if (j == 0) return {a.front(), b.front()};
  if (j >= t.size()) return {a.back(), b.back()};
  const double u = (at - t[j - 1]) / (t[j] - t[j - 1]);
  return {a[j - 1] + u * (a[j] - a[j - 1]), b[j - 1] + u * (b[j] - b[j - 1])};
}

}  // namespace

std::pair<double, double> lat_lon_at(const RecordColumns& rec, double t) {
  return pair_at(rec.t, rec.lat, rec.lon, t);
}

std::pair<double, double> east_north_at(const RecordColumns& rec, double t) {
  return pair_at(rec.t, rec.east, rec.north, t);
}

nlohmann::ordered_json reading_json(const RecordInput& o, const RecordColumns& rec) {
  const auto channel = [](const std::string& column, double factor, const char* unit) {
    return nlohmann::ordered_json{{"column", column}, {"factor", factor}, {"unit", unit}};
  };
  return {{"delimiter", rec.delimiter},
          {"x_positive", o.x_positive},
          {"z_positive", rec.z_positive},
          {"z_open", rec.z_open},
          {"units_open", rec.units_open},
          {"t", channel(rec.t_column, rec.t_factor, "s")},
          {"ddx_M", channel(rec.x_column, rec.x_factor, "m/s^2")},
          {"ddz_M", channel(rec.z_column, rec.z_factor, "m/s^2")}};
}

}  // namespace oscidrum::cli
