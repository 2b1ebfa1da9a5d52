// oscidrum_io/hdf5.hpp: a study's results and every case's steady state in one HDF5 file
// (`oscidrum sweep --hdf5 FILE`), and the merge of the HDF5 files of a study's shards. The layout
// is documented in docs/outputs.md ("HDF5"); h5py reads it directly. HDF5 (the C library) stays
// out of this header.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "oscidrum/study.hpp"
#include "oscidrum_io/shard.hpp"
#include "oscidrum_io/sweep.hpp"

namespace oscidrum::io {

/// What identifies the file: the study and, for a shard, the slice.
struct Hdf5StudyInfo {
  std::uint64_t fingerprint = 0;  ///< of the study and its output columns (as the journal)
  std::size_t n_cases = 0;        ///< cases of the whole study
  bool sharded = false;
  Shard shard;  ///< when sharded
};

/// Writes `path` while a sweep runs: each finished case's steady state goes into
/// PATH.partial at once (flushed, so a killed sweep keeps it for --resume), the tables of
/// parameters and results at the end, and finish() renames PATH.partial to PATH.
class StudyHdf5Writer {
 public:
  /// Create PATH.partial; with `resume`, if an interrupted sweep left one, replace it by a fresh
  /// file holding every case of it that reads back whole (a kill between two flushes leaves a
  /// file that libhdf5 cannot append to). Throws oscidrum::Error "cannot write PATH: ..." (or
  /// "... belongs to a different study; run with --restart").
  StudyHdf5Writer(std::string path, const Hdf5StudyInfo& info, bool resume);
  ~StudyHdf5Writer();
  StudyHdf5Writer(const StudyHdf5Writer&) = delete;
  StudyHdf5Writer& operator=(const StudyHdf5Writer&) = delete;

  /// True if the partial file already holds case `index` (from an earlier, interrupted run).
  bool has_case(std::size_t index) const;

  /// After `resume`: true if the partial file left was damaged (it did not open, or some of its
  /// cases did not read back whole): the cases lost are not in the file (has_case is false).
  bool partial_was_damaged() const;

  /// A case's steady state made ready for the file without touching it: every sample column
  /// shuffled and deflated into its chunks (the work of HDF5's shuffle and deflate filters).
  /// Thread-safe (no HDF5 call): the workers of a sweep prepare their cases in parallel, and
  /// only add_case, which writes the finished chunks, needs to be serialised.
  struct PreparedCase {
    std::vector<std::vector<std::vector<unsigned char>>> chunks;  ///< per column, per chunk
  };
  static PreparedCase prepare(const CaseOutcome& outcome);

  /// Store case `index`'s steady state (its samples; none for a case without them) and status.
  void add_case(std::size_t index, const CaseOutcome& outcome);
  /// The same with its columns prepared already (prepare(outcome)).
  void add_case(std::size_t index, const CaseOutcome& outcome, const PreparedCase& prepared);

  /// Write the tables: /case, /parameters/<key> for every field of every case in `indices`, and
  /// /results/<column> from the result CSV `header` and `rows` (one per index, as the CSV has
  /// them); then close and rename to PATH.
  void finish(const Study& study, const std::vector<std::size_t>& indices,
              const std::string& header, const std::vector<std::string>& rows);

  /// The same with the rows fetched one at a time, `row(k)` for indices[k]: the tables are
  /// written in blocks of rows, so that the memory does not grow with the number of cases.
  void finish(const Study& study, const std::vector<std::size_t>& indices,
              const std::string& header, const std::function<std::string(std::size_t)>& row);

  /// Delete PATH.partial (with --restart).
  static void discard_partial(const std::string& path);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// True if the file starts with the HDF5 signature.
bool is_hdf5_file(const std::string& path);

/// Merge the HDF5 files of every shard of one study into `out` (the layout of an unsharded
/// sweep's file: rows in case order, every case's steady state). Refuses, as the CSV merge does,
/// a file that is not a shard's output, shards of another study or split, a shard given twice or
/// missing, a shard whose rows are not exactly its cases. Throws oscidrum::Error.
void merge_hdf5_shards(const std::vector<std::string>& paths, const std::string& out);

}  // namespace oscidrum::io
