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

/// Where an output named `path` goes. `path` is followed through its symbolic links to the file
/// they name (the link stays and keeps pointing there). A regular file, or a name that does not
/// exist yet, is replaced atomically: written as a temporary file beside it and renamed over it.
/// A FIFO or a character device (/dev/null, /dev/stdout, a terminal) is written directly: it is
/// never renamed over. Anything else (a directory, a block device, a socket) is refused.
struct OutputTarget {
  std::string path;     ///< the file written: `path` with its symbolic links followed
  bool direct = false;  ///< a FIFO or character device, written in place
};

/// The target of `path` (see OutputTarget). With `regular_only` (a file that must be seekable,
/// such as HDF5) a FIFO or device is refused too. Throws oscidrum::Error
/// "cannot write PATH: it is a directory" (a block device, a socket, a loop of links, ...).
OutputTarget output_target(const std::string& path, bool regular_only = false);

/// One output file being written, the single way oscidrum writes a file under a name the user
/// gave (CSV, JSON, HDF5, plots, journals' outputs, sweep and merge outputs). The constructor
/// resolves the target (output_target) and, for a regular target, reserves a temporary file beside
/// it (TARGET.tmp.PID.N, created empty). The writer writes to write_path() (by name: HDF5 or
/// matplotlib; or through write_file_atomic), then commit() flushes it to disk and renames it over
/// the target, keeping the mode of the file it replaces. Destroyed uncommitted, the temporary file
/// is deleted: an interrupted or failed write leaves the old file as it was. A process killed
/// before it could delete its temporary file (SIGKILL, a power cut) leaves it behind; the next
/// OutputFile of the same target deletes such files of processes that no longer run
/// (remove_stale_temporaries).
class OutputFile {
 public:
  explicit OutputFile(std::string path, bool regular_only = false);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& path() const { return path_; }  ///< the name given (for messages)
  const std::string& write_path() const { return write_path_; }
  bool direct() const { return target_.direct; }

  /// fsync and rename the temporary file over the target (nothing to do for a FIFO or device).
  /// Throws oscidrum::Error "cannot write PATH: reason".
  void commit();
  /// Delete the temporary file now (also done by the destructor unless committed).
  void discard();

 private:
  std::string path_, write_path_;
  OutputTarget target_;
  bool pending_ = false;  ///< a temporary file exists and is not committed
};

/// Delete every temporary file of an OutputFile of this process that is neither committed nor
/// discarded yet: for a process about to end without unwinding (the CLI's forced exit after an
/// interrupt's grace period), which would otherwise leave TARGET.tmp.PID.N files beside the
/// targets. Safe from any thread; never throws.
void remove_pending_outputs() noexcept;

/// Delete TARGET.tmp.PID.N files beside `target` (the path an OutputFile writes through, after
/// output_target) whose process PID no longer runs: what a killed writer of the same target left.
/// Files of running processes (this one included, or another process that reused the PID) and
/// every other name are left alone. The PID is this machine's: on a directory shared between
/// machines, a writer of the same target on another machine is not seen (two writers of one target
/// are a conflict anyway). Returns how many it deleted; never throws.
int remove_stale_temporaries(const std::string& target) noexcept;

/// Write `text` to `path` through an OutputFile: readers of a regular file see the old file or
/// the new one, never a part. Throws oscidrum::Error "cannot write PATH: reason".
void write_file_atomic(const std::string& path, std::string_view text);

/// The same, streaming: `write` fills the file, so a large output (a steady state of a million
/// samples per period) is never held in memory whole.
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

  /// The rows finished in earlier runs, in the order they were written (a case run twice, as
  /// after a kill between its row and the next flush, comes twice: the first one counts), read
  /// from the file one at a time.
  void for_each_done(
      const std::function<void(std::size_t index, const std::string& row)>& row) const;

  /// Record a finished case (its row, without line break, starting with its index).
  void append(std::size_t index, const std::string& row);

  /// Delete the journal (after the final output is in place).
  void remove();

  const std::string& path() const { return path_; }

 private:
  void open_locked(const std::string& header, std::size_t n_cases, bool resume, bool restart);

  std::string path_;
  int fd_ = -1;
  std::size_t good_bytes_ = 0;  // the header and the finished rows found when opened
};

/// Delete a file if it exists (no error if it does not).
void remove_file(const std::string& path);

}  // namespace oscidrum::io
