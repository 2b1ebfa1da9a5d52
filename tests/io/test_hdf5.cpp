// Tests of src/io/hdf5.cpp: the HDF5 file of a sweep (docs/outputs.md, "Sweep HDF5 file"), read
// back with the HDF5 C library: the tables hold the values of the CSV exactly, every case's steady
// state its samples; the partial file keeps the cases of an interrupted sweep for --resume and
// refuses another study's; the shards' files merge into the file of the whole study.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "io/io_test_util.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/study.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/hdf5.hpp"
#include "oscidrum_io/sweep.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

constexpr int kHarmonics = 4;

// The file, opened read-only for the test's lifetime.
class File {
 public:
  explicit File(const std::string& path)
      : id_(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~File() {
    if (id_ >= 0) H5Fclose(id_);
  }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  hid_t id() const { return id_; }

  bool has(const std::string& path) const { return H5Lexists(id_, path.c_str(), H5P_DEFAULT) > 0; }

  // A 1-D dataset read as `type` (H5T_NATIVE_DOUBLE, ...) into T.
  template <class T>
  std::vector<T> read(const std::string& path, hid_t type) const {
    const hid_t d = H5Dopen2(id_, path.c_str(), H5P_DEFAULT);
    EXPECT_GE(d, 0) << path;
    if (d < 0) return {};
    const hid_t space = H5Dget_space(d);
    std::vector<T> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    if (!v.empty()) {
      EXPECT_GE(H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0) << path;
    }
    H5Sclose(space);
    H5Dclose(d);
    return v;
  }
  std::vector<double> doubles(const std::string& path) const {
    return read<double>(path, H5T_NATIVE_DOUBLE);
  }

 private:
  hid_t id_;
};

// Two cases of the default soil at two friction coefficients, run with their samples.
struct StudyRun {
  Study study;
  std::vector<CaseOutcome> outcomes;
  StudyColumns columns;
  std::string header;
  std::vector<std::string> rows;
};

StudyRun run_study_of(const std::string& text) {
  StudyRun r;
  r.study = expand(read_study_text(text, "study.toml", ""));
  StudyOptions options;
  options.keep_samples = true;
  options.n_harmonics = kHarmonics;
  r.outcomes = run_study(
      r.study.cases.size(), [&](std::size_t i) { return r.study.cases[i]; }, options);
  r.columns = StudyColumns{r.study.keys, kHarmonics};
  r.header = study_csv_header(r.columns);
  for (std::size_t i = 0; i < r.outcomes.size(); ++i)
    r.rows.push_back(study_csv_row(r.columns, i, r.study.varied[i], r.outcomes[i]));
  return r;
}

const char* kStudy = "[sweep]\n\"contact.mu\" = [0.3, 0.5]\n";

TEST(Hdf5, TablesHoldTheCsvValuesAndEveryCaseItsSamples) {
  TempDir dir;
  const StudyRun r = run_study_of(kStudy);
  ASSERT_EQ(r.outcomes.size(), 2u);
  const std::string path = dir.file("study.h5");
  {
    StudyHdf5Writer w(path, {0xabcdef, 2, false, {}}, false);
    for (std::size_t i = 0; i < 2; ++i) w.add_case(i, r.outcomes[i]);
    EXPECT_FALSE(std::filesystem::exists(path));  // PATH.partial until finish()
    EXPECT_TRUE(std::filesystem::exists(path + ".partial"));
    w.finish(r.study, {0, 1}, r.header, r.rows);
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  EXPECT_TRUE(is_hdf5_file(path));
  const File f(path);
  ASSERT_GE(f.id(), 0);
  EXPECT_EQ(f.read<std::int64_t>("case", H5T_NATIVE_INT64), (std::vector<std::int64_t>{0, 1}));
  // Every parameter of every case, as the field table reads it; NaN where the case does not
  // read it (key_in_effect).
  for (const Field& field : fields()) {
    const std::vector<double> v = f.doubles(std::string("parameters/") + field.key);
    ASSERT_EQ(v.size(), 2u) << field.key;
    for (std::size_t i = 0; i < 2; ++i) {
      if (key_in_effect(r.study.cases[i], field.key))
        EXPECT_EQ(v[i], field.get(r.study.cases[i])) << field.key;
      else
        EXPECT_TRUE(std::isnan(v[i])) << field.key;
    }
  }
  // The results: the CSV's numbers exactly (the same doubles), by column name.
  const std::vector<std::string> labels = csv_split(r.header);
  for (std::size_t c = 1; c < labels.size(); ++c) {
    const std::string name = labels[c].substr(0, labels[c].find('['));
    if (is_text_column(name)) continue;  // strings (status, message, ...)
    const std::vector<double> v = f.doubles("results/" + name);
    ASSERT_EQ(v.size(), 2u) << name;
    for (std::size_t i = 0; i < 2; ++i) {
      const std::string cell = csv_split(r.rows[i])[c];
      if (cell.empty() || cell == "nan")
        EXPECT_TRUE(std::isnan(v[i])) << name;
      else
        EXPECT_EQ(v[i], std::strtod(cell.c_str(), nullptr)) << name;
    }
  }
  // Each case's steady state: its samples, the phase as int8.
  for (std::size_t i = 0; i < 2; ++i) {
    const Samples& s = r.outcomes[i].result.samples;
    ASSERT_GT(s.size(), 0u);
    const std::string g = "steady_state/00000" + std::to_string(i) + "/";
    EXPECT_EQ(f.doubles(g + "t"), s.t);
    EXPECT_EQ(f.doubles(g + "ddx_M"), s.ddx_M);
    EXPECT_EQ(f.doubles(g + "N"), s.N);
    const std::vector<std::int8_t> phase = f.read<std::int8_t>(g + "phase", H5T_NATIVE_INT8);
    ASSERT_EQ(phase.size(), s.phase.size());
    for (std::size_t j = 0; j < phase.size(); ++j)
      EXPECT_EQ(phase[j], static_cast<int>(s.phase[j])) << j;
  }
  EXPECT_FALSE(is_hdf5_file(dir.file("none.h5")));
}

// A sweep killed after its first case: --resume reopens the partial file with that case in it; a
// partial file of another study is refused; --restart discards it.
TEST(Hdf5, PartialFileResumesItsOwnStudyOnly) {
  TempDir dir;
  const StudyRun r = run_study_of(kStudy);
  const std::string path = dir.file("study.h5");
  const Hdf5StudyInfo info{42, 2, false, {}};
  {
    StudyHdf5Writer w(path, info, false);
    w.add_case(0, r.outcomes[0]);
  }  // killed: no finish()
  EXPECT_NE(error_of([&] {
              StudyHdf5Writer w(path, {43, 2, false, {}}, true);
            }).find("belongs to a different study; run with --restart"),
            std::string::npos);
  {
    StudyHdf5Writer w(path, info, true);
    EXPECT_TRUE(w.has_case(0));
    EXPECT_FALSE(w.has_case(1));
    w.add_case(1, r.outcomes[1]);
    w.finish(r.study, {0, 1}, r.header, r.rows);
  }
  const File f(path);
  EXPECT_EQ(f.doubles("steady_state/000000/ddz_M"), r.outcomes[0].result.samples.ddz_M);
  EXPECT_EQ(f.doubles("steady_state/000001/ddz_M"), r.outcomes[1].result.samples.ddz_M);
  { StudyHdf5Writer w(dir.file("other.h5"), info, false); }
  EXPECT_TRUE(std::filesystem::exists(dir.file("other.h5.partial")));
  StudyHdf5Writer::discard_partial(dir.file("other.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("other.h5.partial")));
}

// Where the first piece of raw data of dataset `name` lies in the file: the offset and size of
// its first chunk (a deflated column), or of its contiguous storage; {0, 0} if not found.
std::pair<haddr_t, hsize_t> raw_data_of(const std::string& path, const std::string& name) {
  std::pair<haddr_t, hsize_t> at{0, 0};
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = f >= 0 ? H5Dopen2(f, name.c_str(), H5P_DEFAULT) : -1;
  if (d >= 0) {
    const hid_t space = H5Dget_space(d);
    hsize_t n = 0;
    if (H5Dget_num_chunks(d, space, &n) >= 0 && n > 0) {
      hsize_t offset[1] = {0};
      unsigned mask = 0;
      H5Dget_chunk_info(d, space, 0, offset, &mask, &at.first, &at.second);
    } else if (H5Dget_offset(d) != HADDR_UNDEF) {
      at = {H5Dget_offset(d), H5Dget_storage_size(d)};
    }
    H5Sclose(space);
    H5Dclose(d);
  }
  if (f >= 0) H5Fclose(f);
  return at;
}

// A sweep killed between two of the partial file's flushes leaves it damaged (writes that never
// reached the disk): --resume appended to it, and libhdf5 aborted or failed. Now a fresh file keeps
// the cases that read back whole and the others are run again. A column of case 1 with a torn chunk
// (its bytes overwritten in the middle): cases 0 and 2 are kept, case 1 is missing.
TEST(Hdf5, ResumingADamagedPartialFileKeepsTheCasesThatReadBack) {
  TempDir dir;
  const StudyRun r = run_study_of("[sweep]\n\"contact.mu\" = [0.3, 0.4, 0.5]\n");
  ASSERT_EQ(r.outcomes.size(), 3u);
  const std::string path = dir.file("study.h5"), partial = path + ".partial";
  const Hdf5StudyInfo info{42, 3, false, {}};
  {
    StudyHdf5Writer w(path, info, false);
    for (std::size_t i = 0; i < 3; ++i) w.add_case(i, r.outcomes[i]);
  }  // killed: no finish()
  const auto [offset, size] = raw_data_of(partial, "steady_state/000001/ddz_M");
  if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0)
    GTEST_SKIP() << "no deflate filter: the columns are stored without a checksum";
  ASSERT_GT(size, 64u);
  {
    std::fstream f(partial, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(offset + size / 2));
    const std::string garbage(32, '\x5a');
    f.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  }
  {
    StudyHdf5Writer w(path, info, true);
    EXPECT_TRUE(w.partial_was_damaged());
    EXPECT_TRUE(w.has_case(0));
    EXPECT_FALSE(w.has_case(1));
    EXPECT_TRUE(w.has_case(2));
    w.add_case(1, r.outcomes[1]);
    w.finish(r.study, {0, 1, 2}, r.header, r.rows);
  }
  EXPECT_FALSE(std::filesystem::exists(partial));
  const File f(path);
  ASSERT_GE(f.id(), 0);
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string g = "steady_state/00000" + std::to_string(i) + "/";
    const Samples& s = r.outcomes[i].result.samples;
    EXPECT_EQ(f.doubles(g + "t"), s.t) << i;
    EXPECT_EQ(f.doubles(g + "ddz_M"), s.ddz_M) << i;
    EXPECT_EQ(f.doubles(g + "N"), s.N) << i;
    EXPECT_EQ(f.read<std::int8_t>(g + "phase", H5T_NATIVE_INT8).size(), s.size()) << i;
    // The copied cases' time scale points into this file (attached anew).
    const hid_t d = H5Dopen2(f.id(), (g + "ddz_M").c_str(), H5P_DEFAULT);
    EXPECT_GT(H5Aexists(d, "DIMENSION_LIST"), 0) << i;
    H5Dclose(d);
  }
  EXPECT_EQ(f.read<std::int64_t>("case", H5T_NATIVE_INT64), (std::vector<std::int64_t>{0, 1, 2}));
}

// A partial file cut short (a kill while the file grew, a full disk) does not open: resuming
// keeps none of its cases, runs them again, and finishes the file. A partial file whole is kept
// whole, not said to be damaged.
TEST(Hdf5, ResumingAPartialFileThatDoesNotOpenStartsItAfresh) {
  TempDir dir;
  const StudyRun r = run_study_of(kStudy);
  const std::string path = dir.file("study.h5"), partial = path + ".partial";
  const Hdf5StudyInfo info{42, 2, false, {}};
  {
    StudyHdf5Writer w(path, info, false);
    w.add_case(0, r.outcomes[0]);
  }  // killed: no finish()
  {
    StudyHdf5Writer w(path, info, true);
    EXPECT_FALSE(w.partial_was_damaged());
    EXPECT_TRUE(w.has_case(0));
    w.add_case(1, r.outcomes[1]);
  }  // killed again
  std::filesystem::resize_file(partial, std::filesystem::file_size(partial) / 2);
  {
    StudyHdf5Writer w(path, info, true);
    EXPECT_TRUE(w.partial_was_damaged());
    EXPECT_FALSE(w.has_case(0));
    EXPECT_FALSE(w.has_case(1));
    for (std::size_t i = 0; i < 2; ++i) w.add_case(i, r.outcomes[i]);
    w.finish(r.study, {0, 1}, r.header, r.rows);
  }
  const File f(path);
  ASSERT_GE(f.id(), 0);
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_EQ(f.doubles("steady_state/00000" + std::to_string(i) + "/ddx_M"),
              r.outcomes[i].result.samples.ddx_M)
        << i;
  for (const auto& entry : std::filesystem::directory_iterator(dir.file("")))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
}

// The shards' files merge into the file of the whole study (rows in case order); a set with a
// shard missing is refused.
// The study's HDF5 files of two shards, shard1.h5 and shard2.h5 in `dir`.
std::vector<std::string> write_two_shards(const TempDir& dir, const StudyRun& r) {
  const std::size_t n = r.outcomes.size();
  std::vector<std::string> paths;
  for (std::size_t k : {1u, 2u}) {
    const Shard shard{k, 2};
    std::vector<std::size_t> mine;
    std::vector<std::string> rows;
    const std::string path = dir.file("shard" + std::to_string(k) + ".h5");
    StudyHdf5Writer w(path, {7, n, true, shard}, false);
    for (std::size_t i = 0; i < n; ++i) {
      if (!shard.holds(i)) continue;
      w.add_case(i, r.outcomes[i]);
      mine.push_back(i);
      rows.push_back(r.rows[i]);
    }
    w.finish(r.study, mine, r.header, rows);
    paths.push_back(path);
  }
  return paths;
}

TEST(Hdf5, ShardsMergeIntoTheWholeStudy) {
  TempDir dir;
  const StudyRun r = run_study_of("[sweep]\n\"contact.mu\" = [0.3, 0.4, 0.5]\n");
  ASSERT_EQ(r.outcomes.size(), 3u);
  const std::vector<std::string> paths = write_two_shards(dir, r);
  EXPECT_NE(error_of([&] { merge_hdf5_shards({paths[0]}, dir.file("bad.h5")); }).find("missing"),
            std::string::npos);
  const std::string merged = dir.file("merged.h5");
  merge_hdf5_shards({paths[1], paths[0]}, merged);
  const File f(merged);
  EXPECT_EQ(f.read<std::int64_t>("case", H5T_NATIVE_INT64), (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_EQ(f.doubles("parameters/contact.mu"), (std::vector<double>{0.3, 0.4, 0.5}));
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(f.doubles("steady_state/00000" + std::to_string(i) + "/ddx_M"),
              r.outcomes[i].result.samples.ddx_M)
        << i;
}

// A shard written before the excitation's angle became a steady-state column (alpha) merges with
// one written after: its cases keep the columns they have.
TEST(Hdf5, AShardWithoutTheLaterAlphaColumnMerges) {
  TempDir dir;
  const StudyRun r = run_study_of("[sweep]\n\"contact.mu\" = [0.3, 0.4]\n");
  ASSERT_EQ(r.outcomes.size(), 2u);
  const std::vector<std::string> paths = write_two_shards(dir, r);
  {  // the older shard: case 0 without alpha
    const hid_t f = H5Fopen(paths[0].c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    ASSERT_GT(H5Lexists(f, "steady_state/000000/alpha", H5P_DEFAULT), 0);
    ASSERT_GE(H5Ldelete(f, "steady_state/000000/alpha", H5P_DEFAULT), 0);
    H5Fclose(f);
  }
  const std::string merged = dir.file("merged.h5");
  merge_hdf5_shards({paths[0], paths[1]}, merged);
  const File f(merged);
  EXPECT_FALSE(f.has("steady_state/000000/alpha"));
  EXPECT_TRUE(f.has("steady_state/000001/alpha"));
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_EQ(f.doubles("steady_state/00000" + std::to_string(i) + "/ddx_M"),
              r.outcomes[i].result.samples.ddx_M)
        << i;
  // Another column missing is still an error naming it.
  {
    const hid_t g = H5Fopen(paths[1].c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(H5Ldelete(g, "steady_state/000001/ddz_M", H5P_DEFAULT), 0);
    H5Fclose(g);
  }
  EXPECT_NE(error_of([&] {
              merge_hdf5_shards({paths[0], paths[1]}, dir.file("bad.h5"));
            }).find("no steady-state column ddz_M"),
            std::string::npos);
}

}  // namespace
}  // namespace oscidrum::io
