// oscidrum_io/csv.hpp: CSV writers. The steady-state columns are the contract of
// docs/csv-columns.md (numbers with %.17g); the sweep columns are documented in docs/outputs.md
// (numbers in the shortest form that reads back exactly). Either way equal doubles give equal
// text and the text gives the double back.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "oscidrum/result.hpp"
#include "oscidrum/study.hpp"
#include "oscidrum_io/case_spec.hpp"

namespace oscidrum::io {

/// %.17g; "nan", "inf", "-inf" for non-finite values.
std::string format_double(double v);

/// The shortest text that reads back as exactly `v`: "0.05" (not "0.050000000000000003"),
/// whole numbers below 1e15 without exponent ("5000000").
std::string format_double_short(double v);

/// The field itself, or quoted ("...", inner quotes doubled) if it holds , " or a line break.
std::string csv_quote(std::string_view field);

/// Split one CSV line (no line break) into fields, undoing csv_quote.
std::vector<std::string> csv_split(std::string_view line);

/// The sampled steady state, one row per sample (docs/csv-columns.md).
void write_steady_state_csv(std::ostream& out, const Result& result);

/// The event list: t[s],kind,from,to (phase names stick, slip+, slip-).
void write_events_csv(std::ostream& out, const Result& result);

/// Columns of a sweep's result CSV.
struct StudyColumns {
  std::vector<std::string> keys;  ///< swept keys (column "key[unit]")
  int n_harmonics = 10;           ///< amplitudes A_1 ... A_n of x_M'' and z_M''
};

/// The header line (no line break).
std::string study_csv_header(const StudyColumns& columns);

/// One row (no line break): the case index, its swept values, status, message, diagnostics and
/// metrics. Cells a case has no value for (no samples) are empty.
std::string study_csv_row(const StudyColumns& columns, std::size_t index,
                          const std::vector<Value>& varied, const CaseOutcome& outcome);

/// Why `row` cannot be a row of a study CSV with the header `header` (study_csv_header, split
/// by csv_split), or empty when it can: the same number of cells as the header, a case index, a
/// known status (or "invalid") in the column status[-], and in every numeric column of the
/// diagnostics and metrics a number (nan and inf included) or nothing. For the readers of rows
/// a sweep wrote earlier (a merge's shards, a resumed sweep's journal): an edited or damaged row
/// is refused, never copied into a study's results. The swept values are the caller's to check.
std::string study_row_defect(const std::vector<std::string>& header, std::string_view row);

/// A CSV file of numbers with one header line (e.g. a measured acceleration record).
struct NumericTable {
  std::vector<std::string> header;           ///< column names as written
  std::vector<std::vector<double>> columns;  ///< columns[c][row]

  /// Index of the column whose name is `name` or starts with `name[` (a unit in brackets), or
  /// -1. Case-sensitive.
  int find(std::string_view name) const;
};

/// Read `path` (',' separated; blank lines and lines starting with '#' skipped). Throws
/// oscidrum::Error naming the file, line and column for unreadable files, ragged rows and cells
/// that are not numbers.
NumericTable read_numeric_csv(const std::string& path);

}  // namespace oscidrum::io
