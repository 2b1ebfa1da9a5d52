// oscidrum_io/files.hpp: output files that are never half-written, and the journal that lets an
// interrupted sweep resume without losing a finished case.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <string_view>

namespace oscidrum::io {

/// Write `text` to `path` through a temporary file in the same directory (path.tmp.PID), flushed
/// to disk and renamed over `path`: readers see the old file or the new one, never a part.
/// Throws oscidrum::Error "cannot write PATH: reason".
void write_file_atomic(const std::string& path, std::string_view text);

/// The same, streaming: `write` fills the temporary file, so a large output (a steady state of
/// a million samples per period) is never held in memory whole.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write);

/// An append-only record of the finished cases of one sweep, kept beside its output
/// (results.csv.journal). Line 1 identifies the study (a fingerprint of every case and of the
/// output header, and the number of cases); every further line is one finished case's result row,
/// whose first cell is the case index. Each row is appended with a single write(2), so a kill
/// loses at most the row being written; a torn last line is dropped on resume.
class Journal {
 public:
  /// Start a new journal at `path`. If one exists: with `resume`, read its finished rows (it must
  /// belong to the same study, else oscidrum::Error) and go on appending; without `resume`,
  /// oscidrum::Error (an unfinished sweep is not silently discarded); with `restart`, discard it.
  /// An empty journal (or one with a cut-off first line) holds no case and is started afresh.
  /// The journal is locked (flock) while this object lives: a second sweep on the same journal
  /// gets oscidrum::Error "another oscidrum sweep is running ...".
  Journal(std::string path, std::uint64_t fingerprint, std::size_t n_cases, bool resume,
          bool restart = false);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// Rows finished in earlier runs, by case index.
  const std::map<std::size_t, std::string>& done() const { return done_; }

  /// Record a finished case (its row, without line break, starting with its index).
  void append(std::size_t index, const std::string& row);

  /// Delete the journal (after the final output is in place).
  void remove();

  const std::string& path() const { return path_; }

 private:
  void open_locked(const std::string& header, std::size_t n_cases, bool resume, bool restart);

  std::string path_;
  int fd_ = -1;
  std::map<std::size_t, std::string> done_;
};

/// Delete a file if it exists (no error if it does not).
void remove_file(const std::string& path);

}  // namespace oscidrum::io
