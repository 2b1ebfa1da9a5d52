// Reading the text of measured records (oscidrum/record_reader.hpp): delimiter, comments, header,
// units and axis conventions, as `oscidrum analyze` and `identify` (and the browser explorer)
// read them.
#include "oscidrum/record_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <tuple>
#include <utility>

#include "metrics/median_step.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/record.hpp"
#include "util/one_value.hpp"

namespace oscidrum {
namespace {

// A magnitude of x_M'' or z_M'' [m/s^2] (1e8 g) that no accelerometer reads: a corrupted cell.
constexpr double kImplausibleAcceleration = 9.80665e8;

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

bool is_comment(const std::string& line) {
  const std::string s = trim(line);
  if (!s.empty() && s[0] == '#') {
    // A spreadsheet's error value in the first cell (#N/A, #DIV/0!, ...) is a row with a missing
    // value, not a comment: dropped as one, it lost its place in time under --rate and moved
    // every later sample a step earlier (a record failed with "frequency drift").
    std::string first = s.substr(0, s.find_first_of(",;\t| "));
    for (char& ch : first) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (const char* error : {"#n/a", "#div/0!", "#value!", "#num!", "#ref!", "#name?", "#null!"})
      if (first == error) return false;
  }
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

// 1, 0.001, -9.80665: the factor a column was multiplied by, for the notes.
std::string format_factor(double k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", k);
  return buf;
}

bool parse_number(std::string cell, bool decimal_comma, double& v) {
  if (decimal_comma)
    for (char& ch : cell)
      if (ch == ',') ch = '.';
  if (!cell.empty() && cell[0] == '+') cell.erase(0, 1);
  // A Fortran program's double-precision exponent: 1.2345D+01 is 1.2345e+01.
  if (const std::size_t k = cell.find_first_of("dD");
      k != std::string::npos && k > 0 && k + 1 < cell.size() &&
      (std::isdigit(static_cast<unsigned char>(cell[k - 1])) || cell[k - 1] == '.')) {
    std::size_t j = k + 1;
    if (cell[j] == '+' || cell[j] == '-') ++j;
    if (j < cell.size() &&
        std::all_of(cell.begin() + static_cast<std::ptrdiff_t>(j), cell.end(),
                    [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); }))
      cell[k] = 'e';
  }
  const char* begin = cell.data();
  const char* end = begin + cell.size();
#ifdef __EMSCRIPTEN__
  // Emscripten 3.1.6's libc++ has no floating-point std::from_chars: strtod reads the same text
  // once what from_chars refuses is refused first (leading spaces, a sign after a '+', hexadecimal)
  // and a value out of range fails as it does there.
  if (cell.empty() || std::isspace(static_cast<unsigned char>(cell[0])) || cell[0] == '+' ||
      cell.find_first_of("xX") != std::string::npos)
    return false;
  char* stop = nullptr;
  errno = 0;
  v = std::strtod(begin, &stop);
  return stop == end && errno != ERANGE;
#else
  const auto r = std::from_chars(begin, end, v);
  return !cell.empty() && r.ec == std::errc() && r.ptr == end;
#endif
}

// Days from 1970-01-01 to y-m-d in the Gregorian calendar (y >= 1).
long days_since_1970(long y, int m, int d) {
  static constexpr int kBefore[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  const auto leap_years = [](long n) { return n / 4 - n / 100 + n / 400; };  // in 1 ... n
  const bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  return 365 * (y - 1970) + (leap_years(y - 1) - leap_years(1969)) + kBefore[m - 1] +
         (leap && m > 2 ? 1 : 0) + d - 1;
}

// A clock time as loggers write it: an optional date, 'T' or spaces, HH:MM:SS with an optional
// fraction ('.' or ','), an optional AM/PM and an optional zone (Z, +hh:mm, -hhmm); or, without a
// date, an elapsed MM:SS with a fraction (01:01.500). The date: YYYY-MM-DD, YYYY/MM/DD,
// DD.MM.YYYY, or with slashes or dashes and the year last, M/D/YYYY as US spreadsheets write it
// (D/M/YYYY where the first field is above 12); fields of one digit too. `day`: days since
// 1970-01-01 (0 without a date); `seconds`: of that day (of the hour for MM:SS), UTC when a zone
// is given; `period`: after what an undated clock starts again.
struct ClockTime {
  long day = 0;
  long seconds = 0;       // whole seconds of the day
  double fraction = 0.0;  // and its fraction, [0, 1)
  bool dated = false;
  long period = 86400;  // [s]: 3600 for MM:SS
};

std::optional<ClockTime> parse_clock(const std::string& text) {
  const std::string c = trim(text);
  std::size_t i = 0;
  const auto digits = [&](std::size_t n, long& v) {
    if (i + n > c.size()) return false;
    v = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const char ch = c[i + k];
      if (!std::isdigit(static_cast<unsigned char>(ch))) return false;
      v = 10 * v + (ch - '0');
    }
    i += n;
    return true;
  };
  // 1 ... max digits; their count into n.
  const auto number = [&](std::size_t max, long& v, std::size_t& n) {
    n = 0;
    v = 0;
    while (n < max && i < c.size() && std::isdigit(static_cast<unsigned char>(c[i]))) {
      v = 10 * v + (c[i] - '0');
      ++i;
      ++n;
    }
    return n > 0;
  };
  const auto expect = [&](char ch) {
    if (i < c.size() && c[i] == ch) return ++i, true;
    return false;
  };
  ClockTime out;
  // A date first when the text has one: a '-', '/' or '.' before its first ':'.
  const std::size_t colon = c.find(':');
  if (colon == std::string::npos) return std::nullopt;
  if (c.find_first_of("-/.", 0) < colon) {
    long a = 0, b = 0, e = 0;
    std::size_t na = 0, nb = 0, ne = 0;
    if (!number(4, a, na) || i >= c.size()) return std::nullopt;
    const char sep = c[i];
    if (sep != '-' && sep != '/' && sep != '.') return std::nullopt;
    ++i;
    if (!number(2, b, nb) || !expect(sep) || !number(4, e, ne)) return std::nullopt;
    long y = 0, mo = 0, d = 0;
    if (na == 4 && sep != '.') {
      y = a, mo = b, d = e;  // YYYY-MM-DD, YYYY/MM/DD
      if (ne > 2) return std::nullopt;
    } else if (ne == 4 && na <= 2) {
      if (sep == '.' || a > 12)
        d = a, mo = b, y = e;  // DD.MM.YYYY, D/M/YYYY
      else
        mo = a, d = b, y = e;  // M/D/YYYY
    } else {
      return std::nullopt;
    }
    if (y < 1 || mo < 1 || mo > 12 || d < 1 || d > 31) return std::nullopt;
    if (!expect('T') && !expect(' ')) return std::nullopt;
    while (i < c.size() && c[i] == ' ') ++i;
    out.day = days_since_1970(y, static_cast<int>(mo), static_cast<int>(d));
    out.dated = true;
  }
  long h = 0, mi = 0, sec = 0;
  std::size_t nh = 0;
  // One-digit hours too (9:05:00.5); without a date, up to four digits of minutes (MM:SS).
  if (!number(out.dated ? 2 : 4, h, nh) || !expect(':') || !digits(2, mi)) return std::nullopt;
  const bool has_seconds = expect(':');
  if (out.dated && !has_seconds) return std::nullopt;
  const bool minutes_seconds = !has_seconds;
  if (minutes_seconds) {
    // An elapsed MM:SS(.fff): the first field counts minutes, the second seconds.
    sec = mi;
    mi = h;
    h = 0;
    if (sec > 59 || i >= c.size() || (c[i] != '.' && c[i] != ',')) return std::nullopt;
    out.period = 3600;
  } else if (nh > 2 || !digits(2, sec) || h > 23 || mi > 59 || sec > 60) {
    return std::nullopt;
  }
  double fraction = 0.0;
  if (i < c.size() && (c[i] == '.' || c[i] == ',')) {
    ++i;
    const std::size_t start = i;
    while (i < c.size() && std::isdigit(static_cast<unsigned char>(c[i]))) ++i;
    if (i == start) return std::nullopt;
    // Rounded once, as the decimal fraction it is.
    if (!parse_number("0." + c.substr(start, i - start), false, fraction)) return std::nullopt;
  }
  // AM / PM (12 AM is midnight, 12 PM noon).
  {
    std::size_t k = i;
    while (k < c.size() && c[k] == ' ') ++k;
    if (!minutes_seconds && k + 2 <= c.size() && (c[k + 1] == 'M' || c[k + 1] == 'm') &&
        (k + 2 == c.size() || c[k + 2] == ' ')) {
      const char ap = static_cast<char>(std::toupper(static_cast<unsigned char>(c[k])));
      if (ap == 'A' || ap == 'P') {
        if (h < 1 || h > 12) return std::nullopt;
        h = (h % 12) + (ap == 'P' ? 12 : 0);
        i = k + 2;
        while (i < c.size() && c[i] == ' ') ++i;
      }
    }
  }
  long offset = 0;  // the zone's [s], subtracted to give UTC
  if (i < c.size()) {
    if (c[i] == 'Z' && i + 1 == c.size()) {
      ++i;
    } else if (c[i] == '+' || c[i] == '-') {
      const long sign = c[i] == '+' ? 1 : -1;
      ++i;
      long oh = 0, om = 0;
      if (!digits(2, oh)) return std::nullopt;
      expect(':');
      if (i < c.size() && !digits(2, om)) return std::nullopt;
      if (oh > 23 || om > 59) return std::nullopt;
      offset = sign * (3600 * oh + 60 * om);
    }
  }
  if (i != c.size()) return std::nullopt;
  if (minutes_seconds && offset != 0) return std::nullopt;
  out.seconds = 3600 * h + 60 * mi + sec - offset;
  out.fraction = fraction;
  return out;
}

// A header cell split into its name and unit: "Time [ms]", "acc_z (g)", "az/g", "ax_mps2".
struct Heading {
  std::string name, unit;
  std::string key;  // the name lower-case, letters and digits only: "acc_x" -> "accx"
};

std::string lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

// A missing value as loggers write one: an empty cell, NaN, NA, null, a dash.
bool is_missing(const std::string& cell) {
  const std::string c = lower(trim(cell));
  // (and a spreadsheet's error values: #N/A, #DIV/0!, #VALUE!, #NUM!, #REF!, #NAME?, #NULL!)
  return c.empty() || c == "nan" || c == "-nan" || c == "na" || c == "n/a" || c == "null" ||
         c == "none" || c == "-" || c == "--" || c == "#n/a" || c == "#div/0!" || c == "#value!" ||
         c == "#num!" || c == "#ref!" || c == "#name?" || c == "#null!";
}

// The lines of a text ended by LF, CR LF or a lone CR (classic Mac OS text, as Excel for Mac
// wrote its CSV), each without its end; next() is false at the end of the text, as std::getline.
// Lines are read by std::getline (LF); one that holds a CR before its end is split there (a
// text of lone CRs is one such line, held whole).
class LineReader {
 public:
  explicit LineReader(std::istream& in) : in_(in) {}
  bool next(std::string& l) {
    if (at_ >= held_.size()) {
      if (!std::getline(in_, held_)) return false;
      at_ = 0;
      if (const std::size_t cr = held_.find('\r');
          cr == std::string::npos || cr + 1 == held_.size()) {
        l.swap(held_);  // the usual line: no lone CR within it
        held_.clear();
        return true;
      }
    }
    const std::size_t end = std::min(held_.find('\r', at_), held_.size());
    l.assign(held_, at_, end - at_);
    at_ = end + 1;
    if (at_ >= held_.size()) held_.clear(), at_ = 0;
    return true;
  }

 private:
  std::istream& in_;
  std::string held_;
  std::size_t at_ = 0;
};

std::string key_of(const std::string& name) {
  std::string k;
  for (char ch : lower(name))
    if (std::isalnum(static_cast<unsigned char>(ch))) k += ch;
  return k;
}

double time_scale(const std::string& unit);
double acceleration_scale(const std::string& unit);

bool is_unit(const std::string& u) {
  return !std::isnan(time_scale(u)) || !std::isnan(acceleration_scale(u));
}

// A cell ending in a bracketed part ("acc_x [m/s^2]", "t (ms)", "{g}"): the part before it and
// the bracketed part, each trimmed; nullopt for a cell that ends in no bracket.
std::optional<std::pair<std::string, std::string>> split_bracket(const std::string& cell) {
  const std::string c = trim(cell);
  for (const auto& [open, close] :
       {std::pair{'[', ']'}, std::pair{'(', ')'}, std::pair{'{', '}'}}) {
    const std::size_t a = c.rfind(open);
    if (a != std::string::npos && !c.empty() && c.back() == close)
      return std::pair{trim(c.substr(0, a)), trim(c.substr(a + 1, c.size() - a - 2))};
  }
  return std::nullopt;
}

Heading heading(const std::string& cell) {
  Heading h{trim(cell), "", ""};
  if (const auto parts = split_bracket(cell)) std::tie(h.name, h.unit) = *parts;
  // "(t)" after a name is the argument of a function of time ("x''(t)"), not a unit.
  if (key_of(h.unit) == "t" && !h.name.empty()) h.unit.clear();
  if (h.unit.empty()) {
    // A unit after the last space or '_' ("az m/s^2", "ax_g", "time_ms"), or a quantity over its
    // unit ("az/g", "t/s").
    const std::size_t sep = h.name.find_last_of("_ ");
    const std::size_t slash = h.name.find('/');
    if (sep != std::string::npos && sep > 0 && is_unit(h.name.substr(sep + 1))) {
      h.unit = h.name.substr(sep + 1);
      h.name = trim(h.name.substr(0, sep));
    } else if (slash != std::string::npos && slash > 0 && is_unit(h.name.substr(slash + 1))) {
      h.unit = trim(h.name.substr(slash + 1));
      h.name = trim(h.name.substr(0, slash));
    }
  }
  h.key = key_of(h.name);
  // Two primes, the paper's notation for a second derivative ("x_M''", "z''", "x″"): the key of
  // the model's name for it ("ddxm", "ddz"), not of the coordinate itself.
  for (const char* primes : {"''", "\"", "\xE2\x80\xB3"}) {  // '', ", U+2033 double prime
    const std::string p = primes;
    if (h.name.size() > p.size() && h.name.ends_with(p)) {
      h.key = "dd" + key_of(h.name.substr(0, h.name.size() - p.size()));
      break;
    }
  }
  return h;
}

// The factor from a column's unit to SI (s or m/s^2); NaN for a unit not of that kind.
double time_scale(const std::string& unit) {
  // The micro sign or the Greek mu first: the key keeps ASCII letters only, so "\xC2\xB5s" is
  // "s" there.
  const std::string bare = trim(unit);
  if (bare == "\xC2\xB5s" || bare == "\xCE\xBCs") return 1e-6;
  const std::string u = key_of(unit);
  if (u == "s" || u == "sec" || u == "second" || u == "seconds") return 1.0;
  if (u == "ms" || u == "msec" || u == "millisecond" || u == "milliseconds") return 1e-3;
  if (u == "us" || u == "usec" || u == "microsecond" || u == "microseconds") return 1e-6;
  if (u == "millis") return 1e-3;  // as Arduino-style loggers name their clock
  if (u == "micros") return 1e-6;
  if (u == "ns" || u == "nsec" || u == "nanos" || u == "nanosecond" || u == "nanoseconds")
    return 1e-9;
  return std::numeric_limits<double>::quiet_NaN();
}

double acceleration_scale(const std::string& unit) {
  std::string u = lower(unit);
  std::erase(u, ' ');
  // m/s^2 written in its usual ways: m/s^2, m/s2, m/s\xC2\xB2, m s^-2, m*s^-2, mps2, ms-2, m.s-2,
  // m\xC2\xB7s\xE2\x81\xBB\xC2\xB2 (a middle dot and a superscript minus two).
  auto per_s2 = [](const std::string& rest) {
    return rest == "/s^2" || rest == "/s2" || rest == "/s\xC2\xB2" || rest == "s^-2" ||
           rest == "*s^-2" || rest == "s-2" || rest == "ps2" || rest == "/s/s" || rest == "s2" ||
           rest == "/sec^2" || rest == "/sec2" || rest == ".s-2" || rest == ".s^-2" ||
           rest == "\xC2\xB7s-2" || rest == "\xC2\xB7s^-2" ||
           rest == "\xC2\xB7s\xE2\x81\xBB\xC2\xB2" || rest == "s\xE2\x81\xBB\xC2\xB2";
  };
  if (u == "g" || u == "g0" || u == "gn") return 9.80665;
  if (u == "mg") return 9.80665e-3;  // milli-g, as MEMS accelerometers report
  if (u.rfind("ft", 0) == 0 && per_s2(u.substr(2))) return 0.3048;
  if (u.rfind("mm", 0) == 0 && per_s2(u.substr(2))) return 1e-3;
  if (u.rfind("cm", 0) == 0 && per_s2(u.substr(2))) return 1e-2;
  if (u.rfind("m", 0) == 0 && per_s2(u.substr(1))) return 1.0;
  return std::numeric_limits<double>::quiet_NaN();
}

// The factor of a --units choice to m/s^2: g, mg (a logger whose unit is stated nowhere in the
// file, only in its manual) or m/s2.
double units_factor(const std::string& units) {
  return units == "g" ? kStandardGravity : units == "mg" ? 1e-3 * kStandardGravity : 1.0;
}

// The factor from a speed's unit to m/s, and from a length's to m; NaN for another unit.
double speed_scale(const std::string& unit) {
  std::string u = lower(unit);
  std::erase(u, ' ');
  if (u == "m/s" || u == "mps" || u == "m/sec" || u == "ms^-1" || u == "ms-1") return 1.0;
  if (u == "km/h" || u == "kmh" || u == "kph" || u == "kmph" || u == "km/hr") return 1.0 / 3.6;
  if (u == "m/min") return 1.0 / 60.0;
  if (u == "mph") return 0.44704;
  if (u == "ft/s" || u == "fps") return 0.3048;
  if (u == "cm/s") return 1e-2;
  if (u == "mm/s") return 1e-3;
  return std::numeric_limits<double>::quiet_NaN();
}

double length_scale(const std::string& unit) {
  const std::string u = key_of(unit);
  if (u == "m" || u == "meter" || u == "metre" || u == "meters" || u == "metres") return 1.0;
  if (u == "km") return 1e3;
  if (u == "cm") return 1e-2;
  if (u == "mm") return 1e-3;
  if (u == "ft" || u == "feet") return 0.3048;
  return std::numeric_limits<double>::quiet_NaN();
}

// GNSS columns a logger writes (keys): latitude and longitude in degrees, or projected easting
// and northing; recognised only where the flags name none of them.
bool is_latitude_key(const std::string& k) {
  for (const char* n : {"lat", "latitude", "gpslat", "gpslatitude", "gnsslat", "gnsslatitude",
                        "breite", "breitengrad", "latdeg"})
    if (k == n) return true;
  return false;
}
bool is_longitude_key(const std::string& k) {
  for (const char* n :
       {"lon", "lng", "long", "longitude", "gpslon", "gpslng", "gpslong", "gpslongitude", "gnsslon",
        "gnsslongitude", "laenge", "lnge", "laengengrad", "lngengrad", "londeg"})
    if (k == n) return true;
  return false;
}
bool is_easting_key(const std::string& k) {
  for (const char* n : {"easting", "east", "rechtswert", "utmeast", "utmeasting", "utme"})
    if (k == n) return true;
  return false;
}
bool is_northing_key(const std::string& k) {
  for (const char* n : {"northing", "north", "hochwert", "utmnorth", "utmnorthing", "utmn"})
    if (k == n) return true;
  return false;
}

// Names loggers give the three channels (keys: lower-case letters and digits).
bool is_time_key(const std::string& k) {
  static const char* const names[] = {"t",       "time",   "times",  "zeit",    "timestamp",
                                      "ts",      "tsec",   "sec",    "elapsed", "elapsedtime",
                                      "timesec", "timems", "seconds"};
  for (const char* n : names)
    if (k == n) return true;
  return false;
}

// A time column named otherwise, taken only where no column has a name of `is_time_key`; its
// rank, 0 for none: 1 for a name ending in "time", "zeit" or "tiempo" or starting with "time",
// "zeit" or "tijd" (Relative Time, Record Time, Sample time, DateTime, Uhrzeit, Messzeit, Time of
// day, Zeitstempel, Tijdstempel, Marca de tiempo), a time unit alone (ms, millis, us, s: the
// column's unit too) and the words for it in a few languages (Sekunden, Dauer, Duration, tiempo,
// temps, tempo, tijd, horodatage, heure); 2 for a date (Date, Datum: a spreadsheet's serial date,
// or a clock time with a date), taken where nothing of rank 1 is (beside an Uhrzeit, a Datum
// holds the day).
int time_key_rank(const std::string& k) {
  static const char* const names[] = {"sekunden", "dauer", "duration", "tiempo",    "temps",
                                      "tempo",    "tijd",  "heure",    "horodatage"};
  for (const char* n : names)
    if (k == n) return 1;
  if (k.size() > 4 && (k.starts_with("time") || k.starts_with("zeit") || k.starts_with("tijd") ||
                       k.ends_with("time") || k.ends_with("zeit") || k.ends_with("tiempo")))
    return 1;
  if (!std::isnan(time_scale(k))) return 1;
  return k == "date" || k == "datum" ? 2 : 0;
}

// The sampling rate a logger's preamble line states ("Sample rate: 1000 Hz", "Sampling frequency
// [Hz] = 2000", "rate = 1000", "fs 500", "Abtastrate: 1 kHz", "Sample interval: 1 ms"), in Hz;
// NaN if the line states none. A frequency alone ("Frequency: 39 Hz") may be the excitation's and
// is not read.
double preamble_rate(const std::string& line) {
  std::string l = lower(line);
  while (!l.empty() && (l.front() == '#' || l.front() == '%' || l.front() == '/' ||
                        std::isspace(static_cast<unsigned char>(l.front()))))
    l.erase(0, 1);
  struct Key {
    const char* word;
    bool interval;  // a time between samples, not a rate
  };
  static const Key keys[] = {{"sampling rate", false},
                             {"sample rate", false},
                             {"samplerate", false},
                             {"sample_rate", false},
                             {"sampling_rate", false},
                             {"samplingrate", false},
                             {"sampling frequency", false},
                             {"sample frequency", false},
                             {"sampling_frequency", false},
                             {"sample_frequency", false},
                             {"samplingfrequency", false},
                             {"abtastrate", false},
                             {"abtastfrequenz", false},
                             {"scan rate", false},
                             {"rate", false},
                             {"fs", false},
                             {"sampling interval", true},
                             {"sample interval", true},
                             {"sampling_interval", true},
                             {"sample_interval", true},
                             {"sample period", true},
                             {"abtastintervall", true},
                             {"dt", true}};
  for (const Key& key : keys) {
    const std::string w = key.word;
    if (l.rfind(w, 0) != 0) continue;  // the line starts with the key
    std::string rest = l.substr(w.size());
    if (!rest.empty() && std::isalnum(static_cast<unsigned char>(rest.front()))) continue;
    // A unit in brackets after the key ("[Hz]", "(ms)"), then separators.
    std::string unit;
    std::size_t i = 0;
    while (i < rest.size() && rest[i] == ' ') ++i;
    if (i < rest.size() && (rest[i] == '[' || rest[i] == '(')) {
      const std::size_t close = rest.find(rest[i] == '[' ? ']' : ')', i);
      if (close == std::string::npos) return std::nan("");
      unit = trim(rest.substr(i + 1, close - i - 1));
      i = close + 1;
    }
    while (i < rest.size() && (rest[i] == ' ' || rest[i] == ':' || rest[i] == '=' ||
                               rest[i] == '\t' || rest[i] == ';' || rest[i] == ','))
      ++i;
    const char* begin = rest.c_str() + i;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin || !(v > 0.0) || !std::isfinite(v)) return std::nan("");
    std::string after = trim(std::string(end));
    while (!after.empty() && (after.back() == ';' || after.back() == ',')) after.pop_back();
    if (unit.empty())
      unit = after;
    else if (!after.empty())
      return std::nan("");  // more than a number after the key
    if (key.interval) {
      const double k = unit.empty() || unit == "s" || unit == "sec" ? 1.0
                       : unit == "ms"                               ? 1e-3
                       : unit == "us" || unit == "\u00b5s"          ? 1e-6
                                                                    : std::nan("");
      return 1.0 / (k * v);
    }
    const double k = unit.empty() || unit == "hz" || unit == "1/s" || unit == "/s" ||
                             unit == "sps" || unit == "s/s" || unit == "samples/s"
                         ? 1.0
                     : unit == "khz" || unit == "ksps" ? 1e3
                                                       : std::nan("");
    return k * v;
  }
  return std::nan("");
}

// The words that name the drum in a column's key (ax_drum, drum acc. x, Beschl. Bandage X,
// Trommel, the drum's centre M: ax_centre, acc_x_center): what they qualify is read without them.
constexpr const char* kDrumWords[] = {"drum", "bandage", "trommel", "centre", "center"};

bool names_the_drum(const std::string& k) {
  for (const char* w : kDrumWords)
    if (k.find(w) != std::string::npos) return true;
  return false;
}

// 'x', 'y' or 'z' if the key names an acceleration along that axis (the model's names, ax, a_x,
// acc_x, accel_x, acceleration_x, x_acc, xacc, ddx, horizontal, vertical, longitudinal, ...); 0
// otherwise. (y: the lateral axis of a three-axis logger, or the vertical of a two-dimensional
// record without z.)
char acceleration_axis(const std::string& k) {
  for (const char* w : kDrumWords)
    if (const std::size_t at = k.find(w); at != std::string::npos && k.size() > std::strlen(w)) {
      const std::string rest = k.substr(0, at) + k.substr(at + std::strlen(w));
      // The drum's word with an axis alone (Drum X, Bandage Z): that axis's channel of the drum.
      if (rest == "x" || rest == "y" || rest == "z") return rest.front();
      return acceleration_axis(rest);
    }
  // A linear acceleration (linear_acceleration_x, as phones' and robots' inertial units name
  // the acceleration without the rotation's): the name without the word, and without the path of
  // the message it is a field of (ROS's field.linear_acceleration.x as `rostopic echo -p`
  // writes it, /imu/data/linear_acceleration/x as PlotJuggler exports it).
  if (const std::size_t at = k.find("linearacceleration"); at != std::string::npos && at > 0)
    return acceleration_axis(k.substr(at));
  if (k.size() > 6 && k.starts_with("linear")) return acceleration_axis(k.substr(6));
  // A numbered sensor or channel before the name (Sensor1_AccX, S1.ax, Ch1_AccX, Kanal 2 az), or
  // a numbered accelerometer before its axis (A1_X, acc2 z, a1x): the name after the number.
  for (const char* word : {"sensor", "sens", "channel", "kanal", "ch", "s", "accelerometer",
                           "accel", "acc", "a", "imu"}) {
    const std::string w = word;
    if (!k.starts_with(w) || k.size() < w.size() + 2 ||
        !std::isdigit(static_cast<unsigned char>(k[w.size()])))
      continue;
    std::size_t at = w.size();
    while (at < k.size() && std::isdigit(static_cast<unsigned char>(k[at]))) ++at;
    if (at == k.size()) continue;
    const std::string rest = k.substr(at);
    const bool accelerometer = w[0] == 'a' || w == "imu";
    if (rest.size() == 1 && (rest[0] == 'x' || rest[0] == 'y' || rest[0] == 'z'))
      return accelerometer ? rest[0] : char{0};
    return acceleration_axis(rest);
  }
  // The model's names and the notations of a second derivative: x double dot (xddot, xdd,
  // ddot{x}, x_dotdot, x_2dot), x prime prime (xpp), d2x (d^2x, d2x/dt2), of x or of x_M (xm...
  // or ...m: x_dd_M).
  for (const char axis : {'x', 'y', 'z'}) {
    const std::string a(1, axis);
    for (const std::string& name :
         {"dd" + a + "m",   "dd" + a,         a + "ddot",       a + "dd",      a + "pp",
          a + "mddot",      a + "mdd",        a + "mpp",        a + "ddotm",   a + "ddm",
          a + "ppm",        a + "dotdot",     a + "dotdotm",    a + "mdotdot", a + "2dot",
          a + "2dotm",      "ddot" + a,       "ddot" + a + "m", "d2" + a,      "d2" + a + "m",
          "d2" + a + "dt2", "d2" + a + "mdt2"})
      if (k == name) return axis;
  }
  // acc_hor / acc_vert, a_h / a_v, horizontal / vertical, hor / vert; the horizontal one named
  // for the direction of travel: longitudinal, acc_long, a_long (not "long" alone: a GNSS
  // longitude).
  // acc_h / acc_v and ax_M / az_M (the drum centre M's) as well.
  if (k == "axm" || k == "acch" || k == "accelh" || k == "accelerationh") return 'x';
  if (k == "azm" || k == "accv" || k == "accelv" || k == "accelerationv") return 'z';
  if (k == "ax" || k == "ah" || k == "hor" || k == "ahor" || k == "acchor" || k == "accelhor" ||
      k == "accelerationhor" || k.find("horiz") != std::string::npos || k == "along" ||
      k == "acclong" || k == "accellong" || k == "accelerationlong" ||
      k.find("longitudinal") != std::string::npos)
    return 'x';
  if (k == "az" || k == "av" || k.find("vert") != std::string::npos) return 'z';
  // (German loggers: Beschleunigung, Beschl.; a vibration channel, Vib X, whose unit tells an
  // acceleration from a velocity: a unit that is not an acceleration's is an error.)
  for (const char* stem :
       {"acceleration", "accel", "acc", "a", "beschleunigung", "beschl", "vibration", "vib"}) {
    const std::string st = stem;
    for (char axis : {'x', 'y', 'z'}) {
      // acc_x, accx, a_x, x_acc, xacc, acc_x1 (a channel number), acc_x_M and acc_M_x (the
      // drum centre M's)
      if (k == st + axis || k == axis + st || k == st + axis + 'm' || k == st + 'm' + axis)
        return axis;
      if (k.size() == st.size() + 2 && k.rfind(st + axis, 0) == 0 &&
          std::isdigit(static_cast<unsigned char>(k.back())))
        return axis;
    }
  }
  // Longer names: acc... or accelerometer... ending in the axis (accelerometer_z, acc_drum_x,
  // Beschl. Bandage X), or the axis first (z_acceleration, xaccel).
  for (char axis : {'x', 'y', 'z'}) {
    for (const char* stem : {"acc", "beschl"}) {
      const bool acc = k.find(stem) != std::string::npos;
      if (acc && k.rfind(stem, 0) == 0 && k.back() == axis) return axis;
      if (acc && k.front() == axis && k.find(stem) == 1) return axis;
      if (acc && k.front() == axis && k.size() > 1 && k[1] == 'm' && k.find(stem) == 2)
        return axis;  // xM_acc: the drum centre M's
    }
  }
  return 0;
}

// UTF-16 text (a spreadsheet's "Unicode text" export) with its byte-order mark, as UTF-8.
std::string utf8_of_utf16(const std::string& raw, bool little_endian) {
  std::string out;
  out.reserve(raw.size() / 2);
  const auto unit = [&](std::size_t i) {
    const auto a = static_cast<unsigned char>(raw[i]), b = static_cast<unsigned char>(raw[i + 1]);
    return little_endian ? static_cast<unsigned>(a | (b << 8))
                         : static_cast<unsigned>(b | (a << 8));
  };
  for (std::size_t i = 2; i + 1 < raw.size(); i += 2) {
    unsigned c = unit(i);
    if (c >= 0xD800 && c < 0xDC00 && i + 3 < raw.size()) {  // a surrogate pair
      const unsigned low = unit(i + 2);
      if (low >= 0xDC00 && low < 0xE000) {
        c = 0x10000 + ((c - 0xD800) << 10) + (low - 0xDC00);
        i += 2;
      }
    }
    if (c >= 0xD800 && c < 0xE000) c = 0xFFFD;  // a lone surrogate: the replacement character
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

// A file that is not text, by its first bytes: what it is and what to do, or empty.
// Whether a line is valid UTF-8 (ASCII is).
bool is_utf8(const std::string& line) {
  std::size_t i = 0;
  while (i < line.size()) {
    const auto b = static_cast<unsigned char>(line[i]);
    const std::size_t n = b < 0x80           ? 1
                          : (b >> 5) == 0x6  ? 2
                          : (b >> 4) == 0xE  ? 3
                          : (b >> 3) == 0x1E ? 4
                                             : 0;
    if (n == 0 || i + n > line.size()) return false;
    for (std::size_t k = 1; k < n; ++k)
      if ((static_cast<unsigned char>(line[i + k]) & 0xC0) != 0x80) return false;
    i += n;
  }
  return true;
}

// A line of Windows-1252 / Latin-1 text (a European spreadsheet's CSV export: "m/s\xB2",
// "\xB5s", "\xB0C") as UTF-8: each byte above 0x7F the code point of the same number (0x80 ...
// 0x9F, Windows-1252's punctuation, as the replacement character; no header needs them).
std::string utf8_of_latin1(const std::string& line) {
  std::string out;
  out.reserve(line.size() + 8);
  for (const char ch : line) {
    const auto b = static_cast<unsigned char>(ch);
    if (b < 0x80) {
      out += ch;
    } else if (b < 0xA0) {
      out += "\xEF\xBF\xBD";
    } else {
      out += static_cast<char>(0xC0 | (b >> 6));
      out += static_cast<char>(0x80 | (b & 0x3F));
    }
  }
  return out;
}

std::string not_text(const std::string& first_line) {
  if (first_line.rfind("\x1F\x8B", 0) == 0)
    return "a gzip-compressed file: decompress it first (gunzip)";
  if (first_line.rfind("PK\x03\x04", 0) == 0)
    return "a zip archive (an Excel .xlsx workbook is one): export the sheet as CSV text";
  if (first_line.rfind("\xD0\xCF\x11\xE0", 0) == 0)
    return "an Excel .xls workbook: export the sheet as CSV text";
  if (first_line.rfind("\x89HDF", 0) == 0)
    return "an HDF5 file: export the record's columns as CSV text";
  if (first_line.find('\0') != std::string::npos)
    return "not text (a NUL byte in its first line; UTF-16 without a byte-order mark?): save it "
           "as CSV text, UTF-8 or UTF-16 with its byte-order mark";
  return "";
}

// Columns logged at a slower rate than the accelerations (a GNSS receiver's few Hz beside a
// kHz): the rows where every one of `columns` holds a number are the fixes; each column is filled
// linearly in time between fixes, held before the first and after the last. Returns the fixes
// (none: the columns are left as they are).
std::size_t fill_between_fixes(const std::vector<double>& t,
                               std::initializer_list<std::vector<double>*> columns) {
  const auto is_fix = [&columns](std::size_t i) {
    return std::all_of(columns.begin(), columns.end(),
                       [i](const std::vector<double>* c) { return std::isfinite((*c)[i]); });
  };
  std::size_t fixes = 0;
  for (std::size_t i = 0; i < t.size(); ++i) fixes += is_fix(i) ? 1 : 0;
  if (fixes == 0 || fixes == t.size()) return fixes;
  std::size_t last = t.size();  // the previous fix
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!is_fix(i)) continue;
    for (std::vector<double>* c : columns) {
      std::vector<double>& v = *c;
      if (last == t.size()) {
        for (std::size_t j = 0; j < i; ++j) v[j] = v[i];
      } else {
        const double span = t[i] - t[last];  // (times checked later)
        for (std::size_t j = last + 1; j < i; ++j)
          v[j] = v[last] + (span > 0.0 ? (t[j] - t[last]) / span : 0.0) * (v[i] - v[last]);
      }
    }
    last = i;
  }
  for (std::vector<double>* c : columns)
    for (std::size_t j = last + 1; j < t.size(); ++j) (*c)[j] = (*c)[last];
  return fixes;
}

// The track advances only where it moves more than this many times the fixes' scatter from
// where it last advanced (two fixes of one place lie farther apart than 5 sqrt(2) sigma with a
// chance of exp(-12.5)).
constexpr double kTrackDeadband = 5.0 * 1.4142135623730951;
// The scatter is measured over lags of rows up to this time [s] (beyond the interval between a
// receiver's fixes, within which a logger's rows may be filled or interpolated; short enough that
// a roller's speed changes little over it).
constexpr double kScatterLag = 0.5;

// The path length [m] along a track of projected coordinates at each row (`east` and `north`
// filled between fixes, as the reader fills them, or as a logger wrote them). A fix's own
// scatter is no travel: summed row to row, the scatter of a roller standing still adds up to
// metres within a minute. The scatter sigma: for lags of 1, 2, 4, ... rows up to kScatterLag,
// the median distance of a row from the line through the rows a lag before and after it (divided
// by what white noise makes of it), per axis; the largest over the lags (rows between a
// receiver's fixes, filled or interpolated by a logger, lie on lines between them: only lags as
// long as the fixes' interval see their scatter). The track advances where it has moved more than
// kTrackDeadband sigma from the row it last advanced at, by that distance; a row between two such
// rows by how far along their chord it has come (its projection, within the chord, never back).
std::vector<double> track_length(const std::vector<double>& t, const std::vector<double>& east,
                                 const std::vector<double>& north) {
  const std::size_t n = t.size();
  std::vector<double> path(n, 0.0);
  if (n < 2) return path;
  double sigma = 0.0;
  std::vector<double> off;
  for (std::size_t lag = 1; 2 * lag < n; lag *= 2) {
    const std::size_t stride = std::max<std::size_t>(1, (n - 2 * lag) / 2048);
    off.clear();
    for (std::size_t i = lag; i + lag < n; i += stride) {
      const std::size_t a = i - lag, c = i + lag;
      if (!(t[i] > t[a] && t[c] > t[i])) continue;
      const double r = (t[c] - t[i]) / (t[i] - t[a]);
      const double per_sigma = std::sqrt(1.0 + (1.0 + r) * (1.0 + r) + r * r);
      for (const std::vector<double>* v : {&east, &north})
        off.push_back(std::abs((*v)[c] - (*v)[i] - r * ((*v)[i] - (*v)[a])) / per_sigma);
    }
    if (off.size() >= 8) {
      std::nth_element(off.begin(), off.begin() + static_cast<std::ptrdiff_t>(off.size() / 2),
                       off.end());
      sigma = std::max(sigma, off[off.size() / 2] / 0.6745);  // the median of |N(0, 1)|
    }
    if (t[std::min(n - 1, 2 * lag)] - t[0] > 2.0 * kScatterLag) break;
  }
  const double deadband = kTrackDeadband * sigma;
  std::size_t a = 0;     // the row the track last advanced at
  double p0 = 0.0;       // the path there
  std::size_t from = 0;  // the rows after `a` not yet given their path
  for (std::size_t i = 1; i < n; ++i) {
    const double d = std::hypot(east[i] - east[a], north[i] - north[a]);
    if (!(d > deadband) && i + 1 < n) continue;
    const bool advanced = d > deadband;
    // The rows since `a`: along the chord to i (or, at the end without advancing, held).
    double along = 0.0;
    for (std::size_t j = from + 1; j <= i; ++j) {
      if (advanced) {
        const double proj = ((east[j] - east[a]) * (east[i] - east[a]) +
                             (north[j] - north[a]) * (north[i] - north[a])) /
                            d;
        along = std::max(along, std::clamp(proj, 0.0, d));
      }
      path[j] = p0 + along;
    }
    from = i;
    if (advanced) {
      a = i;
      p0 += d;
      path[i] = p0;
    }
  }
  return path;
}

}  // namespace

RecordColumns read_record(std::istream& in, const std::string& name, const RecordReading& o) {
  // UTF-16 with a byte-order mark (FF FE little-endian, FE FF big-endian): read as UTF-8 text.
  if (const int b = in.peek(); b == 0xFF || b == 0xFE) {
    const std::string raw{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const bool le = raw.rfind("\xFF\xFE", 0) == 0, be = raw.rfind("\xFE\xFF", 0) == 0;
    if (!le && !be)  // bytes no UTF-8 text begins with
      throw Error(name + ": not text (its first byte is 0x" + (b == 0xFF ? "FF" : "FE") +
                  " without a UTF-16 byte-order mark): save it as CSV text, UTF-8 or UTF-16 with "
                  "its byte-order mark");
    std::istringstream text(utf8_of_utf16(raw, le));
    RecordColumns r = read_record(text, name, o);
    r.notes.insert(r.notes.begin(), std::string("read as UTF-16 text (") + (le ? "little" : "big") +
                                        "-endian, by its byte-order mark)");
    return r;
  }
  // Streamed: the first non-comment line sets the delimiter and the header; every other line is
  // parsed as it is read, so memory holds the columns, not the text (24 bytes per row).
  std::string line, first;
  std::size_t no = 0, first_no = 0;
  LineReader lines(in);
  // A line that is not UTF-8 is Windows-1252 / Latin-1 text, read as its UTF-8 (noted once).
  std::size_t latin1_at = 0;
  auto as_utf8 = [&](std::string& l) {
    if (std::all_of(l.begin(), l.end(), [](char ch) { return (ch & 0x80) == 0; }) || is_utf8(l))
      return;
    l = utf8_of_latin1(l);
    if (latin1_at == 0) latin1_at = no;
  };
  auto next_line = [&](std::string& into) {
    while (lines.next(into)) {
      ++no;
      if (!into.empty() && into.back() == '\r') into.pop_back();
      as_utf8(into);
      if (!is_comment(into)) return true;
    }
    return false;
  };
  // A UTF-8 byte-order mark (spreadsheets write one) is not part of the first cell.
  auto strip_bom = [](std::string& l) {
    if (l.rfind("\xEF\xBB\xBF", 0) == 0) l.erase(0, 3);
  };
  // The delimiter of a line: the first of ; tab | , that it holds, else whitespace (a comma
  // beside the others is a decimal comma).
  const auto delimiter_of = [](const std::string& l) {
    if (l.find(';') != std::string::npos) return ';';
    if (l.find('\t') != std::string::npos) return '\t';
    if (l.find('|') != std::string::npos) return '|';
    if (l.find(',') != std::string::npos) return ',';
    return ' ';
  };
  // A cell of a units line: its unit, with or without brackets ("[s]", "s").
  const auto strip_brackets = [](const std::string& c) {
    const auto parts = split_bracket(c);
    return parts && parts->first.empty() ? parts->second : trim(c);
  };
  // A line of units under the header ("s;m/s^2;g", "[s],[g],[g]"): n cells, each empty or a unit,
  // at least one a unit.
  const auto is_units_row = [&](const std::string& l, char d, std::size_t n) {
    const std::vector<std::string> cells = split(l, d);
    if (cells.size() < n) return false;
    bool unit = false;
    for (const std::string& cell : cells) {
      const std::string c = strip_brackets(cell);
      if (c.empty() || c == "-") continue;
      if (!is_unit(c)) return false;
      unit = true;
    }
    return unit;
  };
  // A line with a number (or clock time) in some cell, under delimiter d.
  const auto has_number = [&](const std::string& l, char d) {
    for (const std::string& cell : split(l, d)) {
      double v = 0;
      if (parse_number(cell, d == ';' || d == '\t' || d == '|', v) || parse_clock(cell))
        return true;
    }
    return false;
  };
  // A logger's metadata line ("Device: HAMM", "rate = 1000"): never the header.
  const auto is_metadata = [&](const std::string& l) {
    const std::vector<std::string> cells = split(l, delimiter_of(l));
    return cells.empty() || trim(cells.front()).ends_with(':') || l.find('=') != std::string::npos;
  };
  // The lines before the data: a logger's preamble (metadata without comment marks), the header
  // and a line of units under it. The header is the first line (not metadata, at least two cells)
  // whose next kDataRows lines (after a line of units) have as many cells under the same
  // delimiter and a number in one: a preamble of "key value" pairs with numbers ("Rate 1000",
  // "Gain 2.5") is not taken for a header and its data. A record that ends sooner is decided on
  // the lines it has (at least one); without such a line, the first line as before. At most
  // kLeadLines are held.
  constexpr std::size_t kDataRows = 3;
  constexpr std::size_t kLeadLines = 200;
  std::vector<std::pair<std::string, std::size_t>> lead;
  std::size_t header_at = 0, data_at = 1;  // indices in lead
  bool has_units = false, decided = false;
  // Cells of a line without empty ones at its end (a trailing delimiter).
  const auto cells_of = [](const std::string& l, char d) {
    std::vector<std::string> c = split(l, d);
    while (c.size() > 1 && trim(c.back()).empty()) c.pop_back();
    return c.size();
  };
  // at_end: the record has no more lines (decide on those there are).
  const auto decide = [&](bool at_end) {
    for (std::size_t i = 0; i + 1 < lead.size(); ++i) {
      const std::string& h = lead[i].first;
      if (is_metadata(h)) continue;
      const char d = delimiter_of(h);
      const std::size_t n = cells_of(h, d);
      if (n < 2) continue;
      std::size_t j = i + 1;
      const bool units = is_units_row(lead[j].first, d, n);
      if (units) {
        if (j + 1 >= lead.size()) return false;  // one more line to see
        ++j;
      }
      // A data row: n cells, counted with or without empty ones at its end (a row whose last
      // values are missing, "0.001,,2," under four columns).
      const auto data_row = [&](const std::string& l) {
        return delimiter_of(l) == d && (cells_of(l, d) == n || split(l, d).size() == n) &&
               has_number(l, d);
      };
      std::size_t rows = 0;
      while (rows < kDataRows && j + rows < lead.size() && data_row(lead[j + rows].first)) ++rows;
      if (rows == kDataRows || (rows > 0 && j + rows == lead.size() && at_end)) {
        header_at = i;
        data_at = j;
        has_units = units;
        return true;
      }
      if (j + rows == lead.size() && !at_end) return false;  // more lines to see
    }
    return false;
  };
  // The last comment line before the first other line: the header of a record whose header is
  // commented out ("# t,ax,az" as numpy.savetxt writes it, "% time ax az" as Octave does).
  std::string comment_before;
  std::size_t comment_before_no = 0;
  std::vector<std::pair<std::string, std::size_t>> comments_before;  // (for a stated rate)
  {
    bool any = false;
    for (std::string l; lead.size() < kLeadLines && lines.next(l);) {
      ++no;
      if (no == 1) {
        if (const std::string what = not_text(l); !what.empty()) throw Error(name + ": " + what);
        strip_bom(l);
      }
      if (!l.empty() && l.back() == '\r') l.pop_back();
      as_utf8(l);
      if (is_comment(l)) {
        if (!any && !trim(l).empty()) comment_before = l, comment_before_no = no;
        if (comments_before.size() < kLeadLines) comments_before.emplace_back(l, no);
        continue;
      }
      any = true;
      lead.emplace_back(std::move(l), no);
      if ((decided = decide(false))) break;
    }
    if (!any) throw Error(name + ": no data (the record is empty or all comments)");
    if (!decided) decided = decide(true);
    if (!decided) {  // the first line, as before; its next lines follow as data
      header_at = 0;
      data_at = 1;
      has_units = false;
    }
  }
  first = lead[header_at].first;
  first_no = lead[header_at].second;
  // Delimiter: the first of ; tab | , that the header line holds, else whitespace.
  const char delim = delimiter_of(first);
  RecordColumns out;
  out.delimiter = delim == ';'    ? "semicolon"
                  : delim == '\t' ? "tab"
                  : delim == ','  ? "comma"
                  : delim == '|'  ? "pipe"
                                  : "whitespace";
  // 1,5;2,25 or 1,5<tab>2,25 (a European spreadsheet's CSV or "Unicode text"): a comma within a
  // cell is a decimal comma where it is not the delimiter.
  const bool decimal_comma = delim == ';' || delim == '\t' || delim == '|';
  // Header: that line unless its cells are numbers wherever the lines below have numbers (a
  // text column of the data, a ROS message's frame_id "imu_link", is text in every row: a first
  // data row is not a header for it). Up to three lines below are looked at (a first data row
  // may be all missing values).
  std::vector<std::string> header = split(first, delim);
  // A delimiter at the end of the header line names no column (a spreadsheet's export).
  while (header.size() > 1 && trim(header.back()).empty()) header.pop_back();
  bool has_header = false;
  {
    const auto value = [&](const std::string& cell) {
      double v = 0;
      return parse_number(cell, decimal_comma, v) || parse_clock(cell);
    };
    std::vector<bool> number_below(header.size(), data_at >= lead.size());
    for (std::size_t k = data_at; k < lead.size() && k < data_at + 3; ++k) {
      const std::vector<std::string> below = split(lead[k].first, delim);
      for (std::size_t c = 0; c < header.size(); ++c)
        if (c >= below.size() || value(below[c])) number_below[c] = true;
    }
    for (std::size_t c = 0; c < header.size(); ++c)
      if (!value(header[c]) && number_below[c]) has_header = true;
    // Quoted numbers with a decimal comma in a comma-separated file ("0,5","1,25": a spreadsheet
    // in a German locale): no cell below reads as a number, and the message said the record had
    // no header line. A decimal comma needs another separator between the cells.
    if (!has_header && delim == ',' && data_at < lead.size()) {
      const std::vector<std::string> below = split(lead[data_at].first, delim);
      std::size_t commas = 0, numbers = 0;
      for (const std::string& cell : below) {
        double v = 0;
        const bool comma = cell.find(',') != std::string::npos;
        commas += comma ? 1 : 0;
        numbers += comma && parse_number(cell, true, v) ? 1 : 0;
      }
      if (numbers > 0 && numbers == commas && 2 * numbers >= below.size())
        throw Error(name + ": line " + std::to_string(lead[data_at].second) +
                    " holds quoted numbers with a decimal comma (" + trim(below.front()) +
                    ") in a comma-separated file: a decimal comma needs ';', a tab or '|' between "
                    "the cells (save the file with ';' as the separator, or with decimal points)");
    }
  }
  // No header, but a comment just before the data that names as many columns, none a number:
  // those are the names (the data start at the first line, as without a header).
  bool commented_header = false;
  if (!has_header && header_at == 0 && !comment_before.empty()) {
    std::string c = trim(comment_before);
    c.erase(0, c.rfind("//", 0) == 0 ? 2 : 1);
    while (!c.empty() && (c.front() == '#' || c.front() == '%')) c.erase(0, 1);
    const std::vector<std::string> cells = split(trim(c), delim);
    bool names = cells.size() == header.size();
    for (const std::string& cell : cells) {
      double v = 0;
      names = names && !trim(cell).empty() && !parse_number(cell, decimal_comma, v) &&
              !parse_clock(cell);
    }
    if (names) {
      header = cells;
      has_header = commented_header = true;
      out.notes.push_back("header from the comment at line " + std::to_string(comment_before_no));
    }
  }
  if (header_at > 0)
    out.notes.push_back("skipped " + std::to_string(header_at) + " line" +
                        (header_at > 1 ? "s" : "") + " before the " +
                        (has_header ? "header" : "data") +
                        " (a logger's preamble), which starts at line " + std::to_string(first_no));
  std::vector<std::string> units_row;
  if (has_units) {
    units_row = split(lead[header_at + 1].first, delim);
    out.notes.push_back("units from line " + std::to_string(lead[header_at + 1].second) +
                        ", under the header");
  }
  if (!has_header)
    for (std::size_t c = 0; c < header.size(); ++c) header[c] = "column " + std::to_string(c + 1);
  std::vector<Heading> headings;
  for (const std::string& h : header) headings.push_back(heading(h));
  for (std::size_t c = 0; c < headings.size() && c < units_row.size(); ++c) {
    const std::string u = strip_brackets(units_row[c]);
    if (headings[c].unit.empty() && !u.empty() && u != "-") headings[c].unit = u;
  }
  auto names = [&] {
    std::string all;
    for (const std::string& h : header) all += (all.empty() ? "" : ", ") + h;
    return all;
  };
  // A column given by its name (exactly, or without its unit) or by 1-based index.
  // Columns that bear one name (two ddx_M, a logger's copy of a channel): a name cannot choose.
  auto twice = [&](const std::vector<int>& same, const std::string& col, const char* flag) {
    std::string at;
    for (int c : same) at += (at.empty() ? "" : ", ") + std::to_string(c + 1);
    throw Error(name + ": the header names several columns '" + col + "' (columns " + at +
                "); choose one with " + flag + " and its 1-based index");
  };
  auto find = [&](const std::string& col, const char* flag) -> int {
    std::vector<int> same;
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == col || headings[c].name == col) same.push_back(static_cast<int>(c));
    if (same.size() > 1) twice(same, col, flag);
    if (same.size() == 1) return same.front();
    for (std::size_t c = 0; c < header.size(); ++c)
      if (lower(headings[c].name) == lower(col)) return static_cast<int>(c);
    int index = 0;
    const auto r = std::from_chars(col.data(), col.data() + col.size(), index);
    if (r.ec == std::errc() && r.ptr == col.data() + col.size()) {
      if (index >= 1 && index <= static_cast<int>(header.size())) return index - 1;
      throw Error(name + ": " + flag + " " + col + " is not a column index in [1, " +
                  std::to_string(header.size()) + "]");
    }
    throw Error(name + ": no column '" + col + "' (choose one with " + flag +
                ", by name or 1-based index); the header has: " + names());
  };
  // A column recognised by the names loggers give it; exactly one must match.
  // `bare`: a name that counts only where no other column matches (a three-axis logger's bare
  // X, Y, Z channels; beside acc_x, an x is a position or anything else).
  auto recognise = [&](const char* what, const char* flag, const char* model_name, auto matches,
                       const char* bare = nullptr,
                       int (*rank)(const std::string&) = nullptr) -> int {
    // The model's own name (as `run --csv` writes it) first, exactly: t[s] beside T[N].
    std::vector<int> own;
    for (std::size_t c = 0; c < headings.size(); ++c)
      if (headings[c].name == model_name) own.push_back(static_cast<int>(c));
    if (own.size() > 1) twice(own, model_name, flag);
    if (own.size() == 1) return own.front();
    std::vector<int> hits;
    for (std::size_t c = 0; c < headings.size(); ++c)
      if (matches(headings[c].key)) hits.push_back(static_cast<int>(c));
    if (hits.empty() && bare)
      for (std::size_t c = 0; c < headings.size(); ++c)
        if (headings[c].key == bare) hits.push_back(static_cast<int>(c));
    // Else the names of the lowest rank that some column has.
    for (int r = 1; hits.empty() && rank && r <= 2; ++r)
      for (std::size_t c = 0; c < headings.size(); ++c)
        if (rank(headings[c].key) == r) hits.push_back(static_cast<int>(c));
    // Several: the one that names the drum (ax_drum beside ax_frame, Bandage beside Rahmen).
    if (hits.size() > 1 && std::count_if(hits.begin(), hits.end(), [&](int c) {
                             return names_the_drum(headings[static_cast<std::size_t>(c)].key);
                           }) == 1)
      return *std::find_if(hits.begin(), hits.end(), [&](int c) {
        return names_the_drum(headings[static_cast<std::size_t>(c)].key);
      });
    if (hits.size() == 1) return hits.front();
    if (!has_header)
      throw Error(name + ": the record has no header line: give the " + std::string(what) +
                  " column with " + flag + " (a 1-based index)");
    std::string which;
    for (int c : hits) which += (which.empty() ? "" : ", ") + header[static_cast<std::size_t>(c)];
    throw Error(name + ": " +
                (hits.empty()
                     ? "no column looks like the " + std::string(what)
                     : "several columns look like the " + std::string(what) + " (" + which + ")") +
                "; choose one with " + flag + " (a name or 1-based index)" +
                (std::string_view(flag) == "--t-col"
                     ? ", or give the sampling rate with --rate HZ for a record without one"
                     : "") +
                "; the header has: " + names());
  };
  // From what resolves the slowest excitation searched (a few Hz) to far beyond any logger's.
  if (!(o.rate == 0.0 || (o.rate >= 1.0 && o.rate <= 1e7)))
    throw Error(name +
                ": the sampling rate (--rate) must be in [1, 1e7] Hz (0: read the time "
                "column); got " +
                format_factor(o.rate));
  if (o.rate > 0.0 && !o.t_col.empty())
    throw Error(name + ": give the time column (--t-col) or the sampling rate (--rate), not both");
  // A record without a time column whose preamble (or a comment before the data) states the
  // sampling rate: t from the row number at that rate, with a note (--rate overrides it).
  double rate = o.rate;
  std::string rate_line;
  if (rate == 0.0 && o.t_col.empty() && has_header) {
    bool time_column = false;
    for (const Heading& h : headings)
      time_column = time_column || h.name == "t" || is_time_key(h.key) || time_key_rank(h.key) > 0;
    std::vector<std::pair<std::string, std::size_t>> stated = comments_before;
    for (std::size_t k = 0; k < header_at; ++k) stated.push_back(lead[k]);
    for (const auto& [text, line_no] : stated) {
      const double r = time_column ? std::nan("") : preamble_rate(text);
      if (std::isfinite(r) && r >= 1.0 && r <= 1e7) {
        rate = r;
        rate_line = "line " + std::to_string(line_no) + " ('" + trim(text) + "')";
        break;
      }
    }
  }
  const bool by_rate = rate > 0.0;
  // A stamp in two columns, whole seconds and nanoseconds (ROS 2's header.stamp.sec and
  // header.stamp.nanosec, ROS 1's secs and nsecs), where no column names a time: the seconds'
  // column is the time, the nanoseconds' added to it (cns).
  int cns = -1;
  int c_stamp = -1;
  if (!by_rate && o.t_col.empty() && has_header &&
      std::none_of(headings.begin(), headings.end(), [](const Heading& h) {
        return h.name == "t" || is_time_key(h.key) || time_key_rank(h.key) > 0;
      })) {
    for (std::size_t c = 0; c < headings.size() && cns < 0; ++c)
      for (const auto& [nanos, whole] :
           {std::pair{"nanosec", "sec"}, std::pair{"nsecs", "secs"}, std::pair{"nsec", "sec"}}) {
        const std::string& k = headings[c].key;
        if (!k.ends_with(nanos)) continue;
        const std::string seconds = k.substr(0, k.size() - std::strlen(nanos)) + whole;
        for (std::size_t d = 0; d < headings.size(); ++d)
          if (headings[d].key == seconds && c_stamp < 0) c_stamp = static_cast<int>(d);
        if (c_stamp >= 0) {
          cns = static_cast<int>(c);
          break;
        }
      }
  }
  const int ct = by_rate        ? -1
                 : c_stamp >= 0 ? c_stamp
                 : o.t_col.empty()
                     ? recognise("time", "--t-col", "t", is_time_key, nullptr, time_key_rank)
                     : find(o.t_col, "--t-col");
  // A time zone in the time column's brackets ("Timestamp (UTC)") is not its unit.
  if (ct >= 0) {
    Heading& h = headings[static_cast<std::size_t>(ct)];
    const std::string zone = key_of(h.unit);
    for (const char* z : {"utc", "gmt", "cet", "cest", "mez", "mesz", "local", "localtime", "z"})
      if (zone == z) h.unit.clear();
    // A time column named by its unit alone ("ms", "millis", "us") is in that unit.
    if (h.unit.empty() && !std::isnan(time_scale(h.name))) h.unit = h.name;
  }
  // The columns that name an acceleration along each axis (x and z also by their bare letter or
  // the model's own name).
  std::vector<int> x_like, y_like, z_like;
  for (std::size_t c = 0; c < headings.size(); ++c) {
    const std::string& k = headings[c].key;
    const char axis = acceleration_axis(k);
    const int column = static_cast<int>(c);
    if (axis == 'x' || k == "x" || headings[c].name == "ddx_M") x_like.push_back(column);
    if (axis == 'y') y_like.push_back(column);
    if (axis == 'z' || k == "z" || headings[c].name == "ddz_M") z_like.push_back(column);
  }
  // A three-axis logger's bare X, Y, Z (Time,X,Y,Z): Y is its y channel, so that the mounting
  // rules below see it (a y vertical, an x vertical); it was left out, and z, lateral, was read
  // as the vertical without a word. (A bare y beside named accelerations may be a position.)
  const auto bare = [&](const char* letter) {
    return std::any_of(headings.begin(), headings.end(),
                       [&](const Heading& h) { return h.key == letter; });
  };
  if (y_like.empty() && bare("x") && bare("y") && bare("z") && x_like.size() == 1 &&
      z_like.size() == 1)
    for (std::size_t c = 0; c < headings.size(); ++c)
      if (headings[c].key == "y") y_like.push_back(static_cast<int>(c));
  // A record with y and z accelerations and no x (a two-axis sensor whose channels are y and z,
  // or a logger whose travel axis is y): its one y is the horizontal, with a note (under the
  // flags' conventions for x: forward unless --x-positive backward).
  std::string x_from_y;
  int cx = -1;
  if (o.x_col.empty()) {
    if (x_like.empty() && y_like.size() == 1 && !z_like.empty() && has_header &&
        (o.z_col.empty() || find(o.z_col, "--z-col") != y_like.front())) {
      cx = y_like.front();
      x_from_y = header[static_cast<std::size_t>(cx)];
    } else {
      cx = recognise(
          "horizontal acceleration x_M''", "--x-col", "ddx_M",
          [](const std::string& k) { return acceleration_axis(k) == 'x'; }, "x");
    }
  } else {
    cx = find(o.x_col, "--x-col");
  }
  // A two-dimensional record (another implementation's x and y, y vertical) has no z column:
  // its one y acceleration is the vertical, with a note (beside a z column, y is lateral).
  int cz = -1, cy = -1;
  std::string z_from_y;
  if (o.z_col.empty()) {
    // (A y read as the horizontal above is not a candidate for the vertical.)
    std::erase(y_like, cx);
    if (z_like.empty() && y_like.size() == 1 && has_header) {
      cz = y_like.front();
      z_from_y = header[static_cast<std::size_t>(cz)];
    } else {
      cz = recognise(
          "vertical acceleration z_M''", "--z-col", "ddz_M",
          [](const std::string& k) { return acceleration_axis(k) == 'z'; }, "z");
      // Beside it, a three-axis logger's one y channel: the vertical instead when gravity says so
      // (below, once the rows are read).
      if (y_like.size() == 1 && y_like.front() != cz && y_like.front() != cx) cy = y_like.front();
    }
  } else {
    cz = find(o.z_col, "--z-col");
  }
  // One column read as two quantities (--x-col and --z-col alike, or the time as x): the
  // figure of a signal against itself has no area, and its numbers would mean nothing.
  for (const auto& [a, fa, b, fb] :
       {std::tuple{ct, "--t-col", cx, "--x-col"}, std::tuple{ct, "--t-col", cz, "--z-col"},
        std::tuple{cx, "--x-col", cz, "--z-col"}})
    if (a >= 0 && a == b)
      throw Error(name + ": " + fa + " and " + fb + " are the same column '" +
                  header[static_cast<std::size_t>(a)] + "' (column " + std::to_string(a + 1) +
                  "); give each its own column");
  const int cp = o.pos_col.empty() ? -1 : find(o.pos_col, "--pos-col");
  const int cs = o.speed_col.empty() ? -1 : find(o.speed_col, "--speed-col");
  const int cu = o.unbalance_col.empty() ? -1 : find(o.unbalance_col, "--unbalance-col");
  if (o.lat_col.empty() != o.lon_col.empty())
    throw Error(std::string("give both --lat-col and --lon-col (the point of each window); got "
                            "only ") +
                (o.lat_col.empty() ? "--lon-col" : "--lat-col"));
  if (o.east_col.empty() != o.north_col.empty())
    throw Error(std::string("give both --east-col and --north-col; got only ") +
                (o.east_col.empty() ? "--north-col" : "--east-col"));
  int ceast = o.east_col.empty() ? -1 : find(o.east_col, "--east-col");
  int cnorth = o.north_col.empty() ? -1 : find(o.north_col, "--north-col");
  int clat = o.lat_col.empty() ? -1 : find(o.lat_col, "--lat-col");
  int clon = o.lon_col.empty() ? -1 : find(o.lon_col, "--lon-col");
  // Without those flags, a header with exactly one latitude and one longitude column (Latitude,
  // GPS Lon, Breite, Laenge), else one easting and one northing (Easting, Rechtswert,
  // Hochwert), gives each window its point, with a note.
  std::string gnss_note, gnss_text;  // gnss_text: the first cell of theirs that is no number
  if (clat < 0 && ceast < 0 && has_header) {
    const auto only = [&](bool (*is)(const std::string&)) {
      int hit = -1, hits = 0;
      for (std::size_t c = 0; c < headings.size(); ++c)
        if (is(headings[c].key) && static_cast<int>(c) != ct && static_cast<int>(c) != cx &&
            static_cast<int>(c) != cz)
          hit = static_cast<int>(c), ++hits;
      return hits == 1 ? hit : -1;
    };
    struct Pair {
      bool (*first)(const std::string&);
      bool (*second)(const std::string&);
      int *c1, *c2;
      const char *names, *unit, *flags;
    };
    for (const Pair& pair :
         {Pair{is_latitude_key, is_longitude_key, &clat, &clon, "latitude and longitude",
               "[deg, WGS 84]", "--lat-col and --lon-col"},
          Pair{is_easting_key, is_northing_key, &ceast, &cnorth, "easting and northing", "[m]",
               "--east-col and --north-col"}}) {
      const int a = only(pair.first), b = only(pair.second);
      if (a < 0 || b < 0) continue;
      *pair.c1 = a;
      *pair.c2 = b;
      gnss_note = std::string("position: ") + pair.names + " from the columns '" +
                  header[static_cast<std::size_t>(a)] + "' and '" +
                  header[static_cast<std::size_t>(b)] + "' " + pair.unit +
                  ", each window's point (give " + pair.flags + " to choose)";
      break;
    }
  }
  // Units: a flag's, else the column's header, else SI.
  auto column_scale = [&](int c, bool time) {
    const Heading& h = headings[static_cast<std::size_t>(c)];
    if (time && o.t_units != "auto")
      return o.t_units == "ms" ? 1e-3 : o.t_units == "us" ? 1e-6 : o.t_units == "ns" ? 1e-9 : 1.0;
    // A velocity or a displacement is no acceleration whatever --units says: the advice to give
    // --units read a velocity channel [mm/s] as g (exit 0, a note of the factor only).
    if (!time && !h.unit.empty() &&
        (!std::isnan(speed_scale(h.unit)) || !std::isnan(length_scale(h.unit))))
      throw Error(name + ": column '" + header[static_cast<std::size_t>(c)] + "': unit '" + h.unit +
                  "' is a " + (std::isnan(speed_scale(h.unit)) ? "displacement" : "velocity") +
                  ", not an acceleration: the drum-centre accelerations x_M'', z_M'' are read "
                  "(an accelerometer's channels; choose them with --x-col / --z-col)");
    if (!time && o.units != "auto") {
      const double k = units_factor(o.units);
      const double stated = h.unit.empty() ? k : acceleration_scale(h.unit);
      if (!std::isnan(stated) && stated != k)
        out.notes.push_back("column '" + header[static_cast<std::size_t>(c)] + "': --units " +
                            o.units + " overrides its header's unit " + h.unit);
      return k;
    }
    if (h.unit.empty()) return 1.0;
    const double k = time ? time_scale(h.unit) : acceleration_scale(h.unit);
    if (std::isnan(k))
      throw Error(name + ": column '" + header[static_cast<std::size_t>(c)] + "': unit '" + h.unit +
                  "' is not " +
                  (time ? "a time unit (s, ms, us, ns); give --t-units"
                        : "an acceleration unit (m/s^2, mm/s^2, cm/s^2, ft/s^2, g, mg); give "
                          "--units for the one it is"));
    return k;
  };
  // A speed's, a position's or a coordinate's unit from its header ("Speed [km/h]",
  // "Distance (km)"); none: SI.
  const auto other_scale = [&](int c, double (*scale)(const std::string&), const char* what) {
    if (c < 0) return 1.0;
    const Heading& h = headings[static_cast<std::size_t>(c)];
    if (h.unit.empty()) return 1.0;
    const double k = scale(h.unit);
    if (std::isnan(k))
      throw Error(name + ": column '" + header[static_cast<std::size_t>(c)] + "': unit '" + h.unit +
                  "' is not " + what);
    return k;
  };
  const double kspeed = other_scale(cs, speed_scale, "a speed unit (m/s, km/h, m/min, mph)");
  const double kpos = other_scale(cp, length_scale, "a length unit (m, km, cm, mm, ft)");
  const double keast = other_scale(ceast, length_scale, "a length unit (m, km)");
  const double knorth = other_scale(cnorth, length_scale, "a length unit (m, km)");
  const double kt = by_rate ? 1.0 / rate : column_scale(ct, true);
  double kx = column_scale(cx, false) * (o.x_positive == "backward" ? -1.0 : 1.0);
  // z_positive "auto": down, or up for a two-dimensional record's y (the usual Cartesian axes),
  // until the column's mean says otherwise (below).
  bool z_up = o.z_positive == "up" || (o.z_positive == "auto" && !z_from_y.empty());
  double kz = column_scale(cz, false) * (z_up ? -1.0 : 1.0);
  // A note for each channel not read as the model writes it (its name, unit 1, same sign); empty
  // for one read as written.
  auto note = [&](const char* channel, int c, double k, const char* si) {
    const std::string& named = headings[static_cast<std::size_t>(c)].name;
    if (k == 1.0 && (named == "t" || named == "ddx_M" || named == "ddz_M")) return std::string();
    return std::string(channel) + ": column '" + header[static_cast<std::size_t>(c)] + "' x " +
           format_factor(k) + " -> " + si;
  };
  out.t_column = by_rate    ? std::string("(row number / rate)")
                 : cns >= 0 ? header[static_cast<std::size_t>(ct)] + " + " +
                                  header[static_cast<std::size_t>(cns)] + " x 1e-9"
                            : header[static_cast<std::size_t>(ct)];
  if (cns >= 0)
    out.notes.push_back("t: columns '" + header[static_cast<std::size_t>(ct)] + "' (s) and '" +
                        header[static_cast<std::size_t>(cns)] +
                        "' (ns), a stamp in whole seconds and nanoseconds");
  out.x_column = header[static_cast<std::size_t>(cx)];
  out.z_column = header[static_cast<std::size_t>(cz)];
  out.t_factor = kt;
  out.x_factor = kx;
  out.z_factor = kz;
  // The channels' notes keep their places here and get their text when gravity has decided the
  // unit of a column without one and the sign of the vertical (below).
  std::size_t x_note_at = out.notes.size(), z_note_at = x_note_at + 1;
  out.notes.emplace_back();
  out.notes.emplace_back();
  if (!x_from_y.empty())
    out.notes.push_back("x_M'': no x column: the y column '" + x_from_y +
                        "' is read as the horizontal beside the vertical z (a sensor's y and z "
                        "channels, y along the direction of travel), pointing " +
                        (o.x_positive == "backward" ? "backward (--x-positive)"
                                                    : "forward (give --x-positive backward if it "
                                                      "points the other way)"));
  if (!z_from_y.empty())
    out.notes.push_back("z_M'': no z column: the y column '" + z_from_y +
                        "' is read as the vertical (a two-dimensional record's x and y), " +
                        (o.z_positive == "auto"
                             ? "pointing up as y usually does (give --z-positive down if it "
                               "points down)"
                             : "pointing " + o.z_positive + " (--z-positive)"));
  std::vector<double> speed, y_raw;
  // A row with a missing or non-finite value in a column read is skipped (and counted: a note
  // says how many, and the gap gate judges the windows they fall in).
  std::size_t skipped = 0, first_skipped = 0, data_rows = 0;
  // The time column as clock times (2026-05-12 10:31:22.125): decided on the first data row;
  // t in s from that row's time.
  std::optional<bool> clock;
  ClockTime clock0;
  bool have_clock0 = false;
  long last_clock = 0;
  long extra_days = 0;  // midnights (hours, for MM:SS) passed by a clock without a date
  auto parse = [&](const std::string& text, std::size_t line_no) {
    std::vector<std::string> cells = split(text, delim);
    // Delimiters at the end of a data row beyond the header's columns hold no values.
    while (cells.size() > header.size() && trim(cells.back()).empty()) cells.pop_back();
    if (cells.size() != header.size())
      throw Error(name + ":" + std::to_string(line_no) + ": " + std::to_string(cells.size()) +
                  " cells, but the header has " + std::to_string(header.size()));
    bool missing = false;
    ++data_rows;
    auto get = [&](int c) {
      const std::string& cell = cells[static_cast<std::size_t>(c)];
      double v = 0;
      if (is_missing(cell) || (parse_number(cell, decimal_comma, v) && !std::isfinite(v))) {
        missing = true;
        return 0.0;
      }
      if (!parse_number(cell, decimal_comma, v))
        throw Error(name + ":" + std::to_string(line_no) + ": column '" +
                    header[static_cast<std::size_t>(c)] + "' must be a number" +
                    (c == ct ? std::string(" or a clock time (2026-05-12 10:31:22.125)") : "") +
                    "; got '" + cell + "'");
      return v;
    };
    auto get_time = [&] {
      if (by_rate) return static_cast<double>(data_rows - 1) / rate;  // exact row times
      const std::string& cell = cells[static_cast<std::size_t>(ct)];
      double v = 0;
      if (!clock && !is_missing(cell))
        clock = !parse_number(cell, decimal_comma, v) && parse_clock(cell).has_value();
      if (!clock.value_or(false)) return kt * get(ct) + (cns >= 0 ? 1e-9 * get(cns) : 0.0);
      if (is_missing(cell)) {
        missing = true;
        return 0.0;
      }
      const std::optional<ClockTime> c = parse_clock(cell);
      if (!c || (have_clock0 && (c->dated != clock0.dated || c->period != clock0.period)))
        throw Error(name + ":" + std::to_string(line_no) + ": column '" +
                    header[static_cast<std::size_t>(ct)] + "' must be a clock time like the " +
                    (clock0.dated ? "first row's, with a date" : "first row's, without a date") +
                    "; got '" + cell + "'");
      if (!have_clock0) {
        clock0 = *c;
        have_clock0 = true;
        last_clock = c->seconds;
      }
      // A clock without a date that goes back by more than half its period passed midnight (an
      // MM:SS clock, the hour).
      if (!c->dated && c->seconds < last_clock - c->period / 2) ++extra_days;
      last_clock = c->seconds;
      // Whole seconds apart, then the fractions: no rounding of a large number of seconds.
      return static_cast<double>((c->day - clock0.day) * 86400 + extra_days * c->period +
                                 (c->seconds - clock0.seconds)) +
             (c->fraction - clock0.fraction);
    };
    const double t = get_time();
    const double x = kx * get(cx), z = kz * get(cz);
    // The y channel that may be the vertical: read as it is (NaN where it has no number), and
    // without skipping the row for it.
    double y = std::nan("");
    if (cy >= 0 && !missing) {
      const std::string& cell = cells[static_cast<std::size_t>(cy)];
      if (!is_missing(cell) && !parse_number(cell, decimal_comma, y)) y = std::nan("");
    }
    // A speed or position logged at the GNSS receiver's few Hz beside accelerations at a kHz: an
    // empty cell does not skip the row (99 % of a record's rows were dropped, and the refusal
    // spoke of its sampling); NaN, filled in time from the values around it below.
    const auto sparse = [&](int c) {
      return is_missing(cells[static_cast<std::size_t>(c)]) ? std::nan("") : get(c);
    };
    const double p = cp >= 0 ? kpos * sparse(cp) : 0.0, sp = cs >= 0 ? kspeed * sparse(cs) : 0.0,
                 u = cu >= 0 ? get(cu) : 0.0;
    // A GNSS cell without a number (a receiver's fix comes at a few Hz, the accelerations at a
    // kHz) does not skip the row: NaN, filled from the fixes around it below.
    // In columns recognised rather than chosen, a cell that is no number (48°12'N) is NaN too,
    // and the columns are dropped below.
    const auto fix = [&](int c) {
      const std::string& cell = cells[static_cast<std::size_t>(c)];
      double v = 0;
      if (is_missing(cell)) return std::nan("");
      if (!gnss_note.empty() && !parse_number(cell, decimal_comma, v)) {
        if (gnss_text.empty())
          gnss_text = "line " + std::to_string(line_no) + " has '" + trim(cell) + "'";
        return std::nan("");
      }
      return get(c);
    };
    const double lat = clat >= 0 ? fix(clat) : 0.0, lon = clat >= 0 ? fix(clon) : 0.0;
    const double east = ceast >= 0 ? keast * fix(ceast) : 0.0,
                 north = ceast >= 0 ? knorth * fix(cnorth) : 0.0;
    if (missing) {
      if (skipped++ == 0) first_skipped = line_no;
      return;
    }
    // An acceleration beyond any accelerometer's range (a corrupted cell, 1e30 or 1e308) is said
    // here: in a window it made the gates speak of clipping or of a change of soil, and beyond
    // 1e154 its squares overflowed into NaN in the messages.
    for (const auto& [what, v] : {std::pair{"x_M''", x}, std::pair{"z_M''", z}})
      if (std::abs(v) > kImplausibleAcceleration)
        throw Error(name + ":" + std::to_string(line_no) + ": " + what + " = " + format_factor(v) +
                    " m/s^2, beyond any accelerometer (1e8 g): a corrupted cell? (remove the "
                    "line, or the record's part around it)");
    // A time that goes back is said here, at its line (the analysis would name only the sample).
    if (!out.t.empty() && t < out.t.back())
      throw Error(name + ":" + std::to_string(line_no) + ": the time goes back: " +
                  format_factor(t) + " s after " + format_factor(out.t.back()) +
                  " s (the time column read in seconds; rows out of order, a logger that "
                  "restarted its clock, or files joined: give each part on its own)");
    out.t.push_back(t);
    out.ddx_M.push_back(x);
    out.ddz_M.push_back(z);
    if (cy >= 0) y_raw.push_back(y);
    if (cp >= 0) out.position.push_back(p);
    if (cs >= 0) speed.push_back(sp);
    if (cu >= 0) out.unbalance_angle.push_back(u);
    if (clat >= 0) {
      if (std::abs(lat) > 90.0 || std::abs(lon) > 180.0) {
        if (!gnss_note.empty()) {  // recognised, not chosen: not coordinates in degrees
          gnss_note = "position: the columns '" + header[static_cast<std::size_t>(clat)] +
                      "' and '" + header[static_cast<std::size_t>(clon)] +
                      "' are not read as latitude and longitude: line " + std::to_string(line_no) +
                      " has " + format_factor(lat) + ", " + format_factor(lon) +
                      ", outside [-90, 90], [-180, 180] degrees (give --lat-col and --lon-col "
                      "for columns in degrees)";
          clat = clon = -1;
          out.lat.clear();
          out.lon.clear();
          return;
        }
        throw Error(name + ":" + std::to_string(line_no) +
                    ": latitude, longitude must be in "
                    "[-90, 90], [-180, 180] degrees (WGS 84); got " +
                    format_factor(lat) + ", " + format_factor(lon));
      }
      out.lat.push_back(lat);
      out.lon.push_back(lon);
    }
    if (ceast >= 0) {
      out.east.push_back(east);
      out.north.push_back(north);
    }
  };
  // A line that repeats the header (files joined with their headers) is skipped and counted.
  // A line refused as a row that has another number of cells than the header, or no number, is
  // an error unless no row follows it: up to kFooterLines such lines at the end are a footer
  // ("End of data", a summary) or a last row cut short by a logger's power loss, skipped with a
  // note. (A line with the header's cells and a number is a row, and its error stands.)
  constexpr std::size_t kFooterLines = 20;
  std::size_t repeated_headers = 0, first_repeated_header = 0;
  std::optional<Error> refused;  // the first line refused, while no row has followed it
  std::size_t refused_at = 0, footer = 0;
  std::string refused_text;
  const std::string header_key = key_of(first);
  auto take = [&](const std::string& text, std::size_t line_no) {
    if (has_header && !commented_header && key_of(text) == header_key) {
      if (repeated_headers++ == 0) first_repeated_header = line_no;
      return;
    }
    try {
      parse(text, line_no);
    } catch (const Error& e) {
      // A line with the columns' number of cells and a number in one is a row: its error stands.
      if (cells_of(text, delim) == header.size() && has_number(text, delim)) throw;
      if (!refused) {
        refused = e;
        refused_at = line_no;
        refused_text = trim(text);
      }
      if (++footer > kFooterLines) throw *refused;
      return;
    }
    if (refused) throw *refused;  // a row after the refused line: it was no footer
  };
  // The held lines after the header (and its units), then the rest as it is read; without a
  // header the first line is data too.
  for (std::size_t k = has_header && !commented_header ? data_at : header_at; k < lead.size(); ++k)
    take(lead[k].first, lead[k].second);
  while (next_line(line)) take(line, no);
  if (refused && out.t.empty()) throw *refused;
  if (refused) {
    if (refused_text.size() > 40) refused_text = refused_text.substr(0, 37) + "...";
    out.notes.push_back("skipped " + std::to_string(footer) + " line" + (footer > 1 ? "s" : "") +
                        " after the data, from line " + std::to_string(refused_at) + " ('" +
                        refused_text +
                        "'), that are not rows of its columns: a footer, or a last row cut "
                        "short");
  }
  // The GNSS columns: recognised ones with a cell that is no number are dropped; NaN between
  // fixes filled linearly in time from the fixes around it (held before the first fix and after
  // the last); without any fix, none.
  {
    const bool latlon = clat >= 0;
    std::vector<double>& a = latlon ? out.lat : out.east;
    std::vector<double>& b = latlon ? out.lon : out.north;
    if (!gnss_text.empty()) {
      gnss_note = "position: the columns '" +
                  header[static_cast<std::size_t>(latlon ? clat : ceast)] + "' and '" +
                  header[static_cast<std::size_t>(latlon ? clon : cnorth)] +
                  "' are not read as coordinates: " + gnss_text + " (give " +
                  (latlon ? "--lat-col and --lon-col" : "--east-col and --north-col") +
                  " for columns of numbers)";
      a.clear();
      b.clear();
      clat = clon = ceast = cnorth = -1;
    } else if (!a.empty()) {
      const std::size_t fixes = fill_between_fixes(out.t, {&a, &b});
      if (fixes == 0) {
        gnss_note = "position: the columns '" +
                    header[static_cast<std::size_t>(latlon ? clat : ceast)] + "' and '" +
                    header[static_cast<std::size_t>(latlon ? clon : cnorth)] +
                    "' hold no fix: no window has a point";
        a.clear();
        b.clear();
        clat = clon = ceast = cnorth = -1;
      } else if (fixes < a.size()) {
        out.notes.push_back("position: " + std::to_string(fixes) + " of the " +
                            std::to_string(a.size()) +
                            " rows hold a GNSS fix; the rows between are interpolated in time");
      }
      // Projected coordinates read as well as latitude and longitude: filled between their own
      // fixes too (they stayed NaN between fixes, and with them every window's position,
      // easting and northing, without a word).
      if (latlon && !out.east.empty() && fill_between_fixes(out.t, {&out.east, &out.north}) == 0) {
        out.notes.push_back("position: the columns '" + header[static_cast<std::size_t>(ceast)] +
                            "' and '" + header[static_cast<std::size_t>(cnorth)] +
                            "' hold no fix: no easting, northing or position from them");
        out.east.clear();
        out.north.clear();
        ceast = cnorth = -1;
      }
    }
    if (!gnss_note.empty()) out.notes.push_back(gnss_note);
  }
  // The speed and position columns: empty cells between values filled linearly in time (held
  // before the first value and after the last), as the GNSS columns are.
  for (const auto& [column, values] : {std::pair{cs, &speed}, std::pair{cp, &out.position}}) {
    if (column < 0 || values->empty()) continue;
    std::vector<double>& v = *values;
    const std::string& col = header[static_cast<std::size_t>(column)];
    const std::size_t given = fill_between_fixes(out.t, {&v});
    if (given == 0)
      throw Error(name + ": the column '" + col + "' (" +
                  (column == cs ? "--speed-col" : "--pos-col") + ") holds no number");
    if (given == v.size()) continue;
    out.notes.push_back(std::string(column == cs ? "speed" : "position") + ": " +
                        std::to_string(given) + " of the " + std::to_string(v.size()) +
                        " rows hold a value in '" + col +
                        "'; the rows between are interpolated in time");
  }
  if (latin1_at > 0)
    out.notes.push_back("read as Windows-1252 / Latin-1 text: line " + std::to_string(latin1_at) +
                        " is not UTF-8 (a spreadsheet's export: its m/s\xC2\xB2, \xC2\xB5s as "
                        "they were meant)");
  if (repeated_headers > 0)
    out.notes.push_back("skipped " + std::to_string(repeated_headers) + " line" +
                        (repeated_headers > 1 ? "s" : "") + " repeating the header (the first at " +
                        "line " + std::to_string(first_repeated_header) + "; files joined)");
  if (out.t.empty())
    throw Error(name + (skipped > 0 ? ": every data row (" + std::to_string(skipped) +
                                          ") has a missing or non-finite value"
                                    : std::string(": no data rows after the header")));
  // A three-axis record whose vertical is its y axis (z lateral, or along the drum's axle), told
  // by one of two things, each with a note (--z-col reads z):
  // - gravity, which an accelerometer at rest reads as +-1 g along the vertical and about 0 along
  //   a horizontal axis, is in the mean of y and not in z's (in m/s^2, or in g for columns
  //   without a unit: a mean of about +-1, read in g below);
  // - z has the same value in every row and y does not: another implementation's three
  //   coordinates with y vertical and z along the axle (the drum never moves that way), read
  //   pointing up as y usually does, as a two-dimensional record's y.
  if (cy >= 0) {
    const auto mean_of = [](const std::vector<double>& v, double k) {
      double sum = 0.0;
      for (double e : v) sum += e;
      return v.empty() ? std::nan("") : k * sum / static_cast<double>(v.size());
    };
    const Heading& hy = headings[static_cast<std::size_t>(cy)];
    const Heading& hz = headings[static_cast<std::size_t>(cz)];
    const double ky = o.units != "auto" ? (units_factor(o.units))
                      : hy.unit.empty() ? 1.0
                                        : acceleration_scale(hy.unit);
    const double mean_y = mean_of(y_raw, ky), mean_z = mean_of(out.ddz_M, 1.0);
    const auto gravity = [](double mean, bool unitless) {
      const double a = std::abs(mean);
      return std::abs(a - kStandardGravity) < kGravityBand * kStandardGravity ||
             (unitless && std::abs(a - 1.0) < kGravityBand);
    };
    const bool unitless_y = hy.unit.empty(), unitless_z = hz.unit.empty() && hz.name != "ddz_M";
    const bool by_gravity = o.units == "auto" && gravity(mean_y, unitless_y) &&
                            !gravity(mean_z, unitless_z) && unitless_y == unitless_z;
    const auto [z_lo, z_hi] = std::minmax_element(out.ddz_M.begin(), out.ddz_M.end());
    const auto [y_lo, y_hi] = std::minmax_element(y_raw.begin(), y_raw.end());
    const bool z_still = out.ddz_M.size() > 1 && *z_lo == *z_hi && *y_lo != *y_hi;
    const double kx_unit = column_scale(cx, false);  // x's unit, without --x-positive's sign
    const double mean_x = mean_of(out.ddx_M, kx_unit / kx);
    const bool unitless_x = headings[static_cast<std::size_t>(cx)].unit.empty() &&
                            headings[static_cast<std::size_t>(cx)].name != "ddx_M";
    // Gravity in x's mean alone: a logger mounted with x vertical (below), before z_still. In
    // m/s^2 only (with a unit or without): a horizontal channel's mean of about 1 without a unit
    // may be an offset of 1 m/s^2 (a slope of 6 degrees) as well as gravity in g, and reading a
    // horizontal channel as the vertical would swap the axes.
    const bool x_by_gravity =
        o.units == "auto" && o.x_col.empty() && std::isfinite(ky) && std::isfinite(mean_y) &&
        std::isfinite(mean_x) && gravity(mean_x, false) && !gravity(mean_y, unitless_y) &&
        !gravity(mean_z, unitless_z) && unitless_x == unitless_y && unitless_y == unitless_z;
    if (std::isfinite(ky) && std::isfinite(mean_y) && (by_gravity || (z_still && !x_by_gravity))) {
      const std::string z_name = header[static_cast<std::size_t>(cz)];
      if (!by_gravity && o.z_positive == "auto") z_up = true;
      kz = ky * (z_up ? -1.0 : 1.0);
      cz = cy;
      for (std::size_t i = 0; i < out.ddz_M.size(); ++i) out.ddz_M[i] = kz * y_raw[i];
      out.z_column = header[static_cast<std::size_t>(cz)];
      out.z_factor = kz;
      out.notes.push_back(
          "z_M'': the y column '" + out.z_column + "' is read as the vertical" +
          (by_gravity
               ? ": its mean " + format_factor(mean_y) + (unitless_y ? "" : " m/s^2") +
                     " is gravity (an accelerometer at rest reads 1 g along the vertical) "
                     "and that of the z column '" +
                     z_name + "', " + format_factor(mean_z) +
                     ", is not: a three-axis logger mounted with y vertical"
               : ": the z column '" + z_name +
                     "' has the same value in every row (an axis the drum does not move "
                     "along: the axle), y does not; " +
                     (o.z_positive == "auto" ? "pointing up as y usually does (give "
                                               "--z-positive down if it points down)"
                                             : "pointing " + o.z_positive + " (--z-positive)")) +
          " (give --z-col '" + z_name + "' to read z)");
    } else if (x_by_gravity) {
      // A three-axis logger mounted with x vertical: gravity is in x's mean and in neither of
      // the others'. x is the vertical (its direction decided by gravity below, as any
      // vertical's); the horizontal is the one of y and z that moves more (the direction of
      // travel; the other is the axle's, along which the drum does not move).
      const double kz_unit = column_scale(cz, false);
      const auto spread = [](const std::vector<double>& v, double k) {
        double sum = 0.0, sum2 = 0.0;
        for (double e : v) {
          sum += k * e;
          sum2 += k * e * k * e;
        }
        const double n = static_cast<double>(v.size());
        return n > 0 ? sum2 / n - (sum / n) * (sum / n) : 0.0;
      };
      const bool travel_y = spread(y_raw, ky) >= spread(out.ddz_M, kz_unit / kz);
      const double sign_x = o.x_positive == "backward" ? -1.0 : 1.0;
      const std::string x_name = header[static_cast<std::size_t>(cx)];
      const std::string other = header[static_cast<std::size_t>(travel_y ? cz : cy)];
      std::vector<double> vertical(out.ddx_M.size()), horizontal(out.ddx_M.size());
      for (std::size_t i = 0; i < out.ddx_M.size(); ++i) {
        vertical[i] = kx_unit * (out.ddx_M[i] / kx);
        horizontal[i] = sign_x * (travel_y ? ky * y_raw[i] : kz_unit * (out.ddz_M[i] / kz));
      }
      out.ddz_M = std::move(vertical);
      out.ddx_M = std::move(horizontal);
      const int old_z = cz;
      z_up = false;  // x's direction: gravity's rule below turns it round when it points up
      kz = kx_unit;
      cz = cx;
      cx = travel_y ? cy : old_z;
      kx = sign_x * (travel_y ? ky : kz_unit);
      out.x_column = header[static_cast<std::size_t>(cx)];
      out.z_column = header[static_cast<std::size_t>(cz)];
      out.x_factor = kx;
      out.z_factor = kz;
      out.notes.push_back(
          "z_M'': the x column '" + x_name + "' is read as the vertical: its mean " +
          format_factor(mean_x) + (unitless_x ? "" : " m/s^2") +
          " is gravity (an accelerometer at rest reads 1 g along the vertical) and those of "
          "the y and z columns are not: a three-axis logger mounted with x vertical; x_M'' is "
          "the column '" +
          out.x_column + "', the one of y and z that moves more (the direction of travel; '" +
          other + "' along the axle) (give --x-col and --z-col to choose)");
    }
  }
  // The time column's note first (how t was read is known only now).
  {
    const std::vector<std::string> later = std::move(out.notes);
    out.notes.clear();
    if (by_rate) {
      out.notes.push_back("t: from the row number at " +
                          (rate_line.empty()
                               ? "--rate " + format_factor(rate) + " Hz"
                               : format_factor(rate) +
                                     " Hz, the sampling rate the record states at " + rate_line +
                                     " (no time column; --rate overrides it)") +
                          " (the first data row at t = 0)");
      out.t_factor = 1.0 / rate;
    } else if (clock.value_or(false)) {
      out.notes.push_back("t: column '" + out.t_column + "' read as clock times" +
                          (clock0.dated ? " (with dates)" : "") + ", in s from the first row's" +
                          (o.t_units != "auto" ? " (--t-units does not apply)" : ""));
      out.t_factor = 1.0;
    } else {
      // A time column without a unit is read in s, unless its samples are then too far apart for
      // any roller's excitation (over 0.02 s: under 50 samples/s, the frequency search finds
      // nothing of 10 Hz or more, which needs 5 samples per period) and a logger's rate in ms,
      // us or ns (a ROS message's stamp, `rostopic echo -p`'s %time): then it is read in that
      // unit, said with the flag that reads it in s.
      // The step between distinct times: a clock coarser than the sampling repeats its stamps
      // (a 2 kHz logger stamping in whole ms: 0, 0, 1, 1, ...), and the median of all steps was
      // 0, the column read in s (2 samples/s over 1000 s); its stamps' step says its unit.
      double step = 0.0, rows_per_time = 0.0;
      const bool unitless = o.t_units == "auto" && cns < 0 &&
                            headings[static_cast<std::size_t>(ct)].unit.empty() && out.t.size() > 2;
      if (unitless) {
        const std::size_t n = std::min<std::size_t>(out.t.size(), 10000);
        std::vector<double> distinct;
        for (std::size_t i = 0; i < n; ++i)
          if (distinct.empty() || out.t[i] != distinct.back()) distinct.push_back(out.t[i]);
        step = distinct.size() > 1 ? detail::median_step(distinct) : 0.0;
        // Rows per unit of the column's time: the rows per stamp over the stamps' step.
        if (step > 0.0)
          rows_per_time = static_cast<double>(n) / (static_cast<double>(distinct.size()) * step);
      }
      double factor = !(step > 0.02) ? 1.0
                      : step <= 10.0 ? 1e-3
                      : step <= 1e4  ? 1e-6
                      : step <= 1e7  ? 1e-9
                                     : 1.0;
      // Unless the rows would then come faster than any logger samples (1 MHz): seconds rounded
      // to 0.1 s, thousands of rows a stamp, were read in ms (4e7 samples/s).
      if (factor != 1.0 && rows_per_time / factor > 1e6) factor = 1.0;
      // A spreadsheet's serial date (days since 1899-12-30; MATLAB's datenum counts from year 0):
      // values of at least a day whose steps would be under a microsecond in s (no accelerometer
      // logger samples so fast) but between 1 Hz and 10 MHz in days. In s from the first row's,
      // the first value taken off before the scaling so that the days' digits are not lost.
      const bool serial_days = step > 0.0 && step < 1e-6 && step * 86400.0 >= 1e-7 &&
                               step * 86400.0 <= 1.0 && out.t.front() >= 1.0;
      if (serial_days) {
        const double t0 = out.t.front();
        for (double& v : out.t) v = (v - t0) * 86400.0;
        out.t_factor = 86400.0;
        out.notes.push_back("t: column '" + out.t_column + "' has no unit and is read in days, " +
                            "a spreadsheet's serial date (" +
                            format_factor(1.0 / (step * 86400.0)) +
                            " samples/s), in s from the first row's: in s its samples would be " +
                            format_factor(step) + " s apart; give --t-units s to read it in s");
      } else if (factor != 1.0) {
        for (double& v : out.t) v *= factor;
        out.t_factor = factor;
        const char* unit = factor == 1e-3 ? "ms" : factor == 1e-6 ? "us" : "ns";
        out.notes.push_back("t: column '" + out.t_column + "' has no unit and is read in " + unit +
                            " (" + format_factor(rows_per_time / factor) +
                            " samples/s): in s its samples would be " + format_factor(step) +
                            " s apart (" + format_factor(rows_per_time) +
                            " samples/s, too few for an excitation of 10 Hz or more); give "
                            "--t-units s to read it in s");
      } else {
        if (std::string t_note = cns >= 0 ? std::string() : note("t", ct, kt, "s"); !t_note.empty())
          out.notes.push_back(std::move(t_note));
      }
    }
    x_note_at += out.notes.size();  // the time column's notes now stand before them
    z_note_at += out.notes.size();
    out.notes.insert(out.notes.end(), later.begin(), later.end());
  }
  // Rows with the time of the row before: an event-driven integrator writes both sides of a
  // switch (where the accelerations jump) at the switch's time. Each run of them is one sample,
  // its accelerations averaged (the middle of the jump, where a harmonic series converges); the
  // other columns keep the run's first row.
  // A clock coarser than the sampling (a 2 kHz logger stamping to the millisecond) repeats
  // nearly every time stamp instead: there the rows of each stamp are spread evenly to the next
  // stamp, each its own time. Averaged, each pair was one sample at the wrong time (a low-pass
  // and a delay of a quarter of a millisecond): G came out 1 % high, its intervals missing the
  // truth.
  // A clock rounded to a tick about as long as the sampling step (a logger at 800 samples/s
  // stamping whole milliseconds: steps of 1, 1, 1 and 2 ms): every step between distinct times
  // is a whole number of ticks, of at least two lengths (or one, with repeated stamps), and the
  // tick is at least a fifth of the median step. The fit takes the stamps as the sampling times,
  // each up to a tick off: on such records G came out about 1 % high in every window, its intervals
  // missing the truth, with no word (a 1 kHz logger stamping 1 ms exactly, every step one tick, is
  // not rounded).
  std::optional<std::pair<double, double>> rounded_clock;  // (tick, median step) [s]
  if (out.t.size() > 8) {
    std::vector<double> steps;
    std::size_t other = 0;  // steps of no tick (a 1024 samples/s logger's stamps in whole ms)
    for (std::size_t i = 1; i < out.t.size(); ++i) {
      if (out.t[i] > out.t[i - 1]) steps.push_back(out.t[i] - out.t[i - 1]);
      if (out.t[i] == out.t[i - 1]) ++other;
    }
    if (steps.size() >= 8) {
      const double tick = *std::min_element(steps.begin(), steps.end());
      bool whole = true;
      for (const double d : steps) {
        const double k = std::round(d / tick);
        if (std::abs(d / tick - k) > 1e-6) {
          whole = false;
          break;
        }
        if (k != 1.0) ++other;  // and of several ticks
      }
      // Regularly, not once: an integrator's switch, a row written twice, is not the clock.
      const bool two = other >= 4 && 100 * other >= out.t.size();
      std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2),
                       steps.end());
      const double median = steps[steps.size() / 2];
      if (whole && two && tick >= 0.2 * median) rounded_clock = std::pair{tick, median};
    }
  }
  {
    // The runs of equal times: their first row and length.
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (std::size_t i = 0; i < out.t.size();) {
      std::size_t j = i + 1;
      while (j < out.t.size() && out.t[j] == out.t[i]) ++j;
      runs.emplace_back(i, j - i);
      i = j;
    }
    const std::size_t repeated = out.t.size() - runs.size();
    // Not a record at one instant: the column read as the time does not advance (a constant, a
    // date column, a time of day in a unit the reader does not know).
    if (runs.size() == 1 && out.t.size() > 1)
      throw Error(name + ": the time column holds one time for all " +
                  std::to_string(out.t.size()) + " rows (t = " + format_factor(out.t.front()) +
                  " s); choose the time column with --t-col, or give the sampling rate with "
                  "--rate HZ");
    std::size_t multi = 0;
    for (const auto& run : runs) multi += run.second > 1 ? 1 : 0;
    // Every stamp but a few (9 in 10) holds 2 rows or more: the clock. Fewer: switches (or a
    // clock too irregular to spread; averaged, with the note below).
    const bool spread = runs.size() >= 3 && 10 * multi >= 9 * runs.size();
    const double first_repeated = [&] {
      for (const auto& run : runs)
        if (run.second > 1) return out.t[run.first];
      return 0.0;
    }();
    if (spread) {
      rounded_clock.reset();  // the rows are given times between the stamps, said below
      // The step between stamps, for the last one and for one before a gap (a paused logger):
      // the median step between consecutive stamps.
      std::vector<double> steps;
      for (std::size_t r = 1; r < runs.size(); ++r)
        steps.push_back(out.t[runs[r].first] - out.t[runs[r - 1].first]);
      std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2),
                       steps.end());
      const double typical = steps[steps.size() / 2];
      for (std::size_t r = 0; r < runs.size(); ++r) {
        const auto [begin, length] = runs[r];
        const double t0 = out.t[begin];
        const double next = r + 1 < runs.size() ? out.t[runs[r + 1].first] : t0 + typical;
        const double step = std::min(next - t0, typical) / static_cast<double>(length);
        for (std::size_t k = 1; k < length; ++k)
          out.t[begin + k] = t0 + static_cast<double>(k) * step;
      }
      out.notes.push_back(
          std::to_string(repeated) + " rows repeat the time of the row before (the first at t = " +
          format_factor(first_repeated) + " s): nearly every time stamp holds " +
          "several rows, a clock coarser than the sampling (rounded), so the rows of each stamp " +
          "are spread evenly to the next stamp, each its own time; if the rows are equally " +
          "spaced, --rate HZ gives them the logger's own times");
    } else if (repeated > 0) {
      std::size_t kept = 0;
      std::vector<double>* const others[] = {
          &out.position, &out.lat, &out.lon, &out.east, &out.north, &out.unbalance_angle, &speed};
      for (const auto& [begin, length] : runs) {
        double sx = 0.0, sz = 0.0;
        for (std::size_t k = begin; k < begin + length; ++k) {
          sx += out.ddx_M[k];
          sz += out.ddz_M[k];
        }
        const double m = static_cast<double>(length);
        out.t[kept] = out.t[begin];
        out.ddx_M[kept] = sx / m;
        out.ddz_M[kept] = sz / m;
        for (std::vector<double>* v : others)
          if (!v->empty()) (*v)[kept] = (*v)[begin];
        ++kept;
      }
      for (std::vector<double>* v : {&out.t, &out.ddx_M, &out.ddz_M}) v->resize(kept);
      for (std::vector<double>* v : others)
        if (!v->empty()) v->resize(kept);
      // Many (a tenth of the samples or more), but not nearly every stamp: perhaps a clock
      // coarser than the sampling, too irregular to spread.
      const bool many = 10 * repeated >= kept;
      out.notes.push_back(
          std::to_string(repeated) + " row" + (repeated > 1 ? "s repeat" : " repeats") +
          " the time of the row before (the first at t = " + format_factor(first_repeated) +
          (rounded_clock ? " s; the time stamps are rounded, as the next note says): each such "
                           "run is one sample, its accelerations averaged"
           : many        ? " s; so many that the time stamps may be coarser than the sampling, a "
                           "clock rounded): each such run is one sample, its accelerations averaged; if "
                           "the rows are equally spaced, --rate HZ gives each row its own time"
                  : " s; an event-driven integrator writes both sides of a switch so): each such "
                    "run is one sample, its accelerations averaged (the middle of the jump)"));
    }
  }
  if (rounded_clock)
    out.notes.push_back(
        "t: the time stamps are whole multiples of " + format_factor(rounded_clock->first) +
        " s, a tick as long as a fair part of the sampling step (median " +
        format_factor(rounded_clock->second) +
        " s), with steps of several ticks: a clock rounded to its tick, each stamp up to a tick "
        "off the sample's time, which the fit takes as exact (a 800 samples/s logger stamping "
        "whole ms gave G about 1 % off); if the logger samples at a fixed rate, --rate HZ gives "
        "each row its own time");
  if (skipped > 0)
    out.notes.push_back("skipped " + std::to_string(skipped) + " row" + (skipped > 1 ? "s" : "") +
                        " with a missing or non-finite value (the first at line " +
                        std::to_string(first_skipped) +
                        "): the gap gate (--max-gap) judges the windows they fall in");
  // An accelerometer reads the specific force f = a - g (g pointing down): at rest +1 g along an
  // axis pointing up, -1 g along one pointing down. A record that keeps it (the harmonic fit takes
  // the mean out) therefore tells which way its z axis points (gravity_points_up): read as
  // positive down, a mean near +1 g is g - z_M'', the axis points up (or the logger writes -f, as
  // some phone APIs do: the same column). With z_positive "auto" (the default) the direction read
  // is turned round then (down to up, or a two-dimensional record's y from up to down), with a
  // note; an explicit direction is kept, with a note when the mean contradicts it. A record
  // without gravity, or with the offset removed, says nothing: it is read as auto's first guess,
  // its direction left open (RecordColumns::z_open) for identify's fit to decide.
  std::string gravity_note;
  double mean = 0.0;
  bool gravity_up = gravity_points_up(out.ddz_M, &mean);
  // Accelerations without a unit (no --units, none in the header, not the model's own names) are
  // read in m/s^2. A vertical column whose mean is then about +-1 (within kGravityBand) is gravity
  // in g: an accelerometer at rest reads 1 g, and an offset of 1 m/s^2 is none a logger keeps.
  // Both channels are then read in g, with a note; without gravity the unit stays open
  // (RecordColumns::units_open) for identify's fit to decide.
  const auto unitless = [&](int c) {
    const Heading& h = headings[static_cast<std::size_t>(c)];
    return h.unit.empty() && h.name != "ddx_M" && h.name != "ddz_M";
  };
  out.units_open = o.units == "auto" && unitless(cx) && unitless(cz);
  const bool gravity_in_si =
      std::abs(std::abs(mean) - kStandardGravity) < kGravityBand * kStandardGravity;
  std::string units_note;
  if (out.units_open && std::abs(std::abs(mean) - 1.0) < kGravityBand) {
    for (double& v : out.ddx_M) v *= kStandardGravity;
    for (double& v : out.ddz_M) v *= kStandardGravity;
    kx *= kStandardGravity;
    kz *= kStandardGravity;
    out.x_factor = kx;
    out.z_factor = kz;
    out.units_open = false;
    units_note = "accelerations: no unit in the header, and the mean of z_M'' " +
                 format_factor(mean) +
                 " is gravity in g (an accelerometer at rest reads 1 g): both read in g "
                 "(x 9.80665; give --units m/s2 to read them as m/s^2)";
    gravity_up = gravity_points_up(out.ddz_M, &mean);
  } else if (out.units_open && gravity_in_si) {
    // Gravity in m/s^2 (a mean of about +-9.81): the unit is told, m/s^2 as read.
    out.units_open = false;
    units_note = "accelerations: no unit in the header, and the mean of z_M'' " +
                 format_factor(mean) +
                 " m/s^2 is gravity in m/s^2 (an accelerometer at rest reads 1 g): both read in "
                 "m/s^2 (give --units g to read them as g)";
  } else if (out.units_open) {
    units_note =
        "accelerations: no unit in the header and no gravity to tell it: read in m/s^2 (give "
        "--units g if the logger wrote g; identify and calibrate fit them in g where only that "
        "fits)";
  }
  // Gravity confirms the direction read when the column so read has a mean of -1 g (an axis
  // pointing down at rest); without gravity either way, "auto" leaves the direction open.
  const bool gravity_down = gravity_points_up({-mean});
  out.z_open = o.z_positive == "auto" && !gravity_up && !gravity_down;
  if (gravity_up) {
    const std::string why =
        "its mean read as pointing " + std::string(z_up ? "up" : "down") + " is " +
        format_factor(mean) +
        " m/s^2 (z down), about +1 g, where an accelerometer at rest reads -1 g "
        "along a downward axis and +1 g along an upward one";
    if (o.z_positive == "auto") {
      z_up = !z_up;
      for (double& v : out.ddz_M) v = -v;
      kz = -kz;
      out.z_factor = kz;
      gravity_note = "z_M'': read as pointing " + std::string(z_up ? "up" : "down") +
                     (z_up ? " (negated)" : " (as it is)") + ": " + why + " (give --z-positive " +
                     (z_up ? "down" : "up") + " to read it the other way)";
    } else {
      gravity_note = "z_M'': " + why + ", so this column's axis likely points " +
                     (o.z_positive == "up" ? std::string("down (give --z-positive down or auto)")
                                           : std::string("up (give --z-positive up or auto)"));
    }
  }
  // The channels' notes in their places (z after x; an empty one dropped), then why.
  if (std::string z_note = note("z_M''", cz, kz, "m/s^2 (positive down)"); !z_note.empty())
    out.notes[z_note_at] = std::move(z_note);
  else
    out.notes.erase(out.notes.begin() + static_cast<std::ptrdiff_t>(z_note_at));
  if (std::string x_note = note("x_M''", cx, kx, "m/s^2 (positive forward)"); !x_note.empty())
    out.notes[x_note_at] = std::move(x_note);
  else
    out.notes.erase(out.notes.begin() + static_cast<std::ptrdiff_t>(x_note_at));
  if (!units_note.empty()) out.notes.push_back(std::move(units_note));
  if (!gravity_note.empty()) out.notes.push_back(std::move(gravity_note));
  out.z_positive = z_up ? "up" : "down";
  // A channel that never changes (a dead or disconnected sensor, or a drum that does not move
  // that way, as a directed vertical exciter's x_M''): its harmonics are zero and what compares
  // phases with it is NaN (psi_xz, kb, the ratios to its fundamental). Said, the record is still
  // read.
  for (const auto& [channel, values] :
       {std::pair<const char*, const std::vector<double>*>{"x_M''", &out.ddx_M},
        {"z_M''", &out.ddz_M}}) {
    if (values->size() > 1 && detail::one_value(*values))
      out.notes.push_back(std::string(channel) + ": the same value (" +
                          format_factor(values->front()) +
                          " m/s^2) in every row: a dead or disconnected channel, or a drum that "
                          "does not move that way; what compares phases with it (psi_xz, kb, "
                          "the ratios to its fundamental) is NaN");
  }
  if (cs >= 0 && cp < 0) {
    for (std::size_t i = 1; i < out.t.size(); ++i)
      if (!(out.t[i] > out.t[i - 1])) return out;  // analyze_windows reports it
    out.position = integrate_speed(out.t, speed);
  }
  if (ceast >= 0 && cp < 0 && cs < 0) {
    // The path length along the track [m] (a GNSS fix repeated between updates adds nothing,
    // nor does the fixes' scatter).
    out.position = track_length(out.t, out.east, out.north);
  }
  return out;
}

bool gravity_points_up(const std::vector<double>& ddz_M, double* mean) {
  double sum = 0.0;
  for (double v : ddz_M) sum += v;
  const double m = ddz_M.empty() ? std::nan("") : sum / static_cast<double>(ddz_M.size());
  if (mean) *mean = m;
  return std::abs(m - kStandardGravity) < kGravityBand * kStandardGravity;
}

}  // namespace oscidrum
