// End-to-end tests of `oscidrum sweep`: the examples run, parallel output equals serial output,
// each case's steady state, and kill-and-resume losing nothing.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "process.hpp"

namespace oscidrum::test {
namespace {

const std::string kSource = OSCIDRUM_SOURCE_DIR;

std::size_t count_lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(CliSweep, Table2StudyIsTheSameOnAnyNumberOfThreads) {
  TempDir dir;
  const std::string study = kSource + "/examples/table2_sweep.toml";
  const Outcome parallel = run({"sweep", study, "--out", dir / "r.csv", "--threads", "2", "-q"});
  ASSERT_EQ(parallel.code, 0) << parallel.err;
  EXPECT_EQ(parallel.out, "");  // with --out nothing goes to stdout unless --format says so
  const std::string csv = slurp(dir / "r.csv");
  EXPECT_EQ(count_lines(csv), 1u + 56u);  // header + 14 x 2 x 2
  EXPECT_EQ(csv.rfind("case[-],soil.table2_G[Pa],contact.pure_rolling[-],MMd_fraction[-],status[-],"
                      "message[-],",
                      0),
            0u);
  EXPECT_NE(csv.find("\n55,70000000,false,0.05,steady_state,"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "r.csv.journal"));  // removed when complete
  const Outcome serial = run({"sweep", study, "--threads", "1", "-q"});
  ASSERT_EQ(serial.code, 0) << serial.err;
  EXPECT_EQ(serial.out, csv);  // byte for byte
}

// Range values as the user would write them, in --list and in the results CSV.
TEST(CliSweep, RangeValuesPrintAsWritten) {
  TempDir dir;
  std::ofstream(dir / "s.toml")
      << "[sweep]\n\"contact.mu\" = { start = 0.2, stop = 0.8, num = 13 }\n";
  const Outcome list = run({"sweep", dir / "s.toml", "--list"});
  ASSERT_EQ(list.code, 0) << list.err;
  EXPECT_NE(list.out.find(" 0.25\n"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find(" 0.3\n"), std::string::npos) << list.out;
  EXPECT_EQ(list.out.find("0000000"), std::string::npos) << list.out;
  const Outcome o = run({"sweep", dir / "s.toml", "-q"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("\n1,0.25,steady_state,"), std::string::npos) << o.out.substr(0, 400);
  EXPECT_NE(o.out.find("\n2,0.3,steady_state,"), std::string::npos);
  EXPECT_EQ(o.out.find("0.30000000000000004"), std::string::npos);
}

TEST(CliSweep, EveryExampleRuns) {
  for (const auto& entry : std::filesystem::directory_iterator(kSource + "/examples")) {
    const std::string path = entry.path().string();
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(path);
    const bool study = slurp(path).find("[sweep]") != std::string::npos;
    const Outcome o = study ? run({"sweep", path, "--format", "json", "-q"})
                            : run({"run", path, "--format", "json", "-q"});
    EXPECT_EQ(o.code, 0) << o.err;
    const nlohmann::json j = nlohmann::json::parse(o.out);
    if (study) {
      EXPECT_EQ(j["schema"], "oscidrum-sweep/1");
      for (const auto& row : j["rows"]) EXPECT_EQ(row["status[-]"], "steady_state");
    } else {
      EXPECT_EQ(j["status"], "steady_state");
    }
  }
}

TEST(CliSweep, CasesDirHoldsEachSteadyState) {
  TempDir dir;
  const Outcome o = run({"sweep", kSource + "/examples/trough_shape_sweep.toml", "--cases-dir",
                         dir / "cases", "--format", "table", "-q"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("trough.k[-]"), std::string::npos);
  for (const char* name : {"case_0000.csv", "case_0001.csv"}) {
    const std::string csv = slurp(dir / ("cases/" + std::string(name)));
    EXPECT_EQ(csv.rfind("t[s],delta[rad],", 0), 0u) << name;
    EXPECT_GT(count_lines(csv), 1000u);
  }
  const Outcome list = run({"sweep", kSource + "/examples/radius_sweep.toml", "--list"});
  EXPECT_EQ(list.code, 0);
  EXPECT_NE(list.out.find("56 cases"), std::string::npos);
  // --format csv and json (ignored before: the table), none.
  const Outcome csv =
      run({"sweep", kSource + "/examples/radius_sweep.toml", "--list", "--format", "csv"});
  EXPECT_EQ(csv.code, 0) << csv.err;
  EXPECT_EQ(count_lines(csv.out), 57u);
  EXPECT_EQ(csv.out.rfind("case,", 0), 0u) << csv.out.substr(0, 200);
  const Outcome json =
      run({"sweep", kSource + "/examples/radius_sweep.toml", "--list", "--format", "json"});
  EXPECT_EQ(json.code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["count"], 56);
  ASSERT_EQ(j["cases"].size(), 56u);
  EXPECT_EQ(j["cases"][55]["case"], 55);
  EXPECT_EQ(j["cases"][0].size(), 3u);  // case, trough.a, soil.table2_G
  EXPECT_EQ(j["cases"][0]["trough.a"], 0.603);
  EXPECT_EQ(j["cases"][1]["soil.table2_G"], 10e6);
  const Outcome none =
      run({"sweep", kSource + "/examples/radius_sweep.toml", "--list", "--format", "none"});
  EXPECT_EQ(none.code, 0) << none.err;
  EXPECT_TRUE(none.out.empty()) << none.out;
}

TEST(CliSweep, FailedCaseGivesExitCodeOneWithItsStatus) {
  TempDir dir;
  // The transient method's budget (shooting would find the orbit within 3 periods' budget).
  std::ofstream(dir / "s.toml")
      << "[numerics]\nmethod = \"transient\"\n[sweep]\n\"numerics.max_periods\" = [3, 2000]\n";
  const Outcome o = run({"sweep", dir / "s.toml", "-q"});
  EXPECT_EQ(o.code, 1) << o.err;
  EXPECT_NE(o.out.find("\n0,3,max_periods_reached,"), std::string::npos);
  EXPECT_NE(o.out.find("\n1,2000,steady_state,"), std::string::npos);
}

// 60 pure-rolling cases on Appendix B soils: long enough (a second or two on one thread) to be
// stopped in the middle.
// The transient method: independent cases (no continuation), so that resuming gives the same
// bytes.
std::string write_slow_study(const TempDir& dir, int cases = 60) {
  std::ofstream(dir / "slow.toml")
      << "[soil]\ninput = \"modulus\"\n[contact]\npure_rolling = true\n"
         // slow: the transient method takes 300-1600 periods per pure-rolling case
         "[numerics]\nmethod = \"transient\"\n"
         "[sweep]\n\"soil.G\" = { start = 5e6, stop = 70e6, num = "
      << cases << " }\n";
  return dir / "slow.toml";
}

// Start the sweep, wait until the journal holds `rows` finished cases, then send `sig`.
Outcome interrupt_after(const std::vector<std::string>& args, const TempDir& dir,
                        const std::string& journal, std::size_t rows, int sig) {
  const pid_t pid = start(args, dir / "out", dir / "err");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (count_lines(slurp(journal)) < rows + 1 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, sig);
  return finish(pid, dir / "out", dir / "err");
}

TEST(CliSweep, KillAndResumeLosesNothing) {
  TempDir dir;
  const std::string study = write_slow_study(dir);
  const std::string out = dir / "r.csv", journal = out + ".journal";
  const Outcome reference = run({"sweep", study, "-q"});
  ASSERT_EQ(reference.code, 0) << reference.err;

  // SIGKILL: no chance to clean up; the journal keeps every finished case.
  Outcome o =
      interrupt_after({"sweep", study, "--out", out, "--threads", "1"}, dir, journal, 3, SIGKILL);
  ASSERT_EQ(o.signal, SIGKILL) << "the sweep ended before it could be killed: " << o.err;
  EXPECT_FALSE(std::filesystem::exists(out));  // never a half-written result
  const std::size_t kept = count_lines(slurp(journal)) - 1;
  EXPECT_GE(kept, 3u);

  // Starting again without --resume refuses to throw the journal away.
  o = run({"sweep", study, "--out", out});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--resume"), std::string::npos);

  // SIGINT while resuming: stops cleanly with 130 and keeps what it finished.
  o = interrupt_after({"sweep", study, "--out", out, "--threads", "2", "--resume"}, dir, journal,
                      kept + 3, SIGINT);
  EXPECT_EQ(o.code, 130) << o.err;
  EXPECT_NE(o.err.find("resuming: " + std::to_string(kept) + " of 60"), std::string::npos);
  EXPECT_NE(o.err.find("run the same command with --resume added"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(out));
  const std::size_t kept2 = count_lines(slurp(journal)) - 1;
  EXPECT_GE(kept2, kept + 3);

  // Resume to the end: the result equals the uninterrupted run, byte for byte.
  o = run({"sweep", study, "--out", out, "--resume"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("resuming: " + std::to_string(kept2) + " of 60"), std::string::npos);
  EXPECT_EQ(slurp(out), reference.out);
  EXPECT_FALSE(std::filesystem::exists(journal));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
}

// A resume whose --cases-dir lacks the case files of finished cases (another directory than the
// interrupted run's) runs them again for their files: said (it ran them again without a word).
TEST(CliSweep, AResumeSaysWhichFinishedCasesItRunsAgainForTheirCaseFiles) {
  TempDir dir;
  const std::string study = write_slow_study(dir);
  const std::string out = dir / "r.csv", journal = out + ".journal";
  const Outcome reference = run({"sweep", study, "-q"});
  ASSERT_EQ(reference.code, 0) << reference.err;
  Outcome o = interrupt_after(
      {"sweep", study, "--out", out, "--threads", "1", "--cases-dir", dir / "first"}, dir, journal,
      3, SIGKILL);
  ASSERT_EQ(o.signal, SIGKILL) << "the sweep ended before it could be killed: " << o.err;
  const std::size_t kept = count_lines(slurp(journal)) - 1;
  o = run({"sweep", study, "--out", out, "--resume", "--cases-dir", dir / "second"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("--cases-dir " + (dir / "second") + " lacks the case files of " +
                       std::to_string(kept) + " finished cases of the journal"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(o.err.find("resuming:"), std::string::npos) << o.err;
  EXPECT_EQ(slurp(out), reference.out);
  EXPECT_TRUE(std::filesystem::exists(dir / "second/case_0000.csv"));
}

// Without --out a sweep keeps no journal and cannot be resumed: an interrupt left FILE.h5.partial
// (30-50 MB in a user's study) while saying "nothing written". It is removed; the case files of
// --cases-dir are whole files of finished cases and stay, said.
TEST(CliSweep, AnInterruptWithoutOutLeavesNoPartialHdf5File) {
  TempDir dir;
  const std::string study = write_slow_study(dir), h5 = dir / "s.h5", cases = dir / "cases";
  const pid_t pid =
      start({"sweep", study, "--hdf5", h5, "--cases-dir", cases, "--threads", "1", "-q"},
            dir / "out", dir / "err");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!(std::filesystem::exists(cases) && !std::filesystem::is_empty(cases)) &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_TRUE(std::filesystem::exists(h5 + ".partial"));
  ::kill(pid, SIGINT);
  const Outcome o = finish(pid, dir / "out", dir / "err");
  EXPECT_EQ(o.code, 130) << o.err;
  EXPECT_NE(o.err.find("no results written (the finished cases' files are in " + cases + ")"),
            std::string::npos)
      << o.err;
  EXPECT_FALSE(std::filesystem::exists(h5 + ".partial"));
  EXPECT_FALSE(std::filesystem::exists(h5));
}

TEST(CliSweep, ResumeRefusesAJournalOfAnotherStudy) {
  TempDir dir;
  const std::string study = write_slow_study(dir);
  const std::string out = dir / "r.csv";
  const Outcome o = interrupt_after({"sweep", study, "--out", out, "--threads", "1"}, dir,
                                    out + ".journal", 1, SIGINT);
  ASSERT_EQ(o.code, 130) << o.err;
  Outcome changed = run({"sweep", study, "--out", out, "--resume", "--set", "roller.m=1900"});
  EXPECT_EQ(changed.code, 2);
  EXPECT_NE(changed.err.find("belongs to a different study"), std::string::npos);
  // A row edited by hand (its swept value, or its status) is refused, not copied into the
  // results; the journal is left as it is.
  const std::string journal = slurp(out + ".journal");
  const std::size_t row = journal.find('\n') + 1, value = journal.find(',', row) + 1;
  for (const auto& [from, to, why] :
       {std::tuple<std::size_t, std::size_t, std::string>{
            value, journal.find(',', value), "its soil.G is '99', the case's is '5000000'"},
        {journal.find(',', value) + 1, journal.find(',', journal.find(',', value) + 1),
         "its status '99' is not one of oscidrum's statuses"}}) {
    std::string edited = journal;
    edited.replace(from, to - from, "99");
    std::ofstream(out + ".journal", std::ios::trunc) << edited;
    const Outcome refused = run({"sweep", study, "--out", out, "--resume"});
    EXPECT_EQ(refused.code, 2) << refused.err;
    EXPECT_NE(refused.err.find("is damaged or edited: the row of case 0 cannot be this sweep's (" +
                               why + "); run with --restart"),
              std::string::npos)
        << refused.err;
    EXPECT_EQ(slurp(out + ".journal"), edited);
  }
  changed = run({"sweep", study, "--out", out, "--restart", "--set", "roller.m=1900", "--set",
                 "numerics.max_periods=5", "-q"});
  EXPECT_EQ(changed.code, 1) << changed.err;  // max_periods_reached everywhere
  EXPECT_EQ(count_lines(slurp(out)), 61u);
}

// A sweep interrupted while also writing --hdf5, resumed without it: its FILE.partial was left
// unfinished without a word (the resumed sweep ended with exit 0 and no HDF5 file). The journal
// knows the HDF5 file: resumed without it, it is refused; with it (named from another directory),
// the sweep finishes both files.
TEST(CliSweep, ResumeNeedsTheHdf5FileTheSweepWasWriting) {
  TempDir dir;
  const std::string study = write_slow_study(dir);
  const std::string out = dir / "r.csv", h5 = dir / "r.h5";
  const Outcome o = interrupt_after({"sweep", study, "--out", out, "--hdf5", h5, "--threads", "1"},
                                    dir, out + ".journal", 1, SIGINT);
  ASSERT_EQ(o.code, 130) << o.err;
  ASSERT_TRUE(std::filesystem::exists(h5 + ".partial"));
  const Outcome without = run({"sweep", study, "--out", out, "--resume", "-q"});
  EXPECT_EQ(without.code, 2);
  EXPECT_NE(without.err.find("HDF5 file changed"), std::string::npos) << without.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // The same file by another relative path (from its directory's parent).
  const std::filesystem::path cwd = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::path(dir.path()).parent_path());
  const std::string name = std::filesystem::path(dir.path()).filename().string();
  const Outcome with =
      run({"sweep", study, "--out", out, "--resume", "--hdf5", name + "/r.h5", "-q"});
  std::filesystem::current_path(cwd);
  EXPECT_EQ(with.code, 0) << with.err;
  EXPECT_TRUE(std::filesystem::exists(h5));
  EXPECT_FALSE(std::filesystem::exists(h5 + ".partial"));
}

// The datasets of an HDF5 file that a --resume test compares with an uninterrupted run's.
class Hdf5File {
 public:
  explicit Hdf5File(const std::string& path)
      : id_(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~Hdf5File() {
    if (id_ >= 0) H5Fclose(id_);
  }
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  bool ok() const { return id_ >= 0; }
  // The names in a group (empty if it is missing).
  std::vector<std::string> names(const std::string& group) const {
    std::vector<std::string> out;
    hsize_t at = 0;
    H5Literate_by_name(
        id_, group.c_str(), H5_INDEX_NAME, H5_ITER_INC, &at,
        [](hid_t, const char* name, const H5L_info_t*, void* v) {
          static_cast<std::vector<std::string>*>(v)->emplace_back(name);
          return herr_t{0};
        },
        &out, H5P_DEFAULT);
    return out;
  }
  // A numeric 1-D dataset as doubles ({NaN} if it does not read).
  std::vector<double> doubles(const std::string& name) const {
    const hid_t d = H5Dopen2(id_, name.c_str(), H5P_DEFAULT);
    if (d < 0) return {std::nan("")};
    const hid_t space = H5Dget_space(d);
    std::vector<double> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    if (!v.empty() && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
      v = {std::nan("")};
    H5Sclose(space);
    H5Dclose(d);
    return v;
  }

 private:
  hid_t id_;
};

// The same values bit for bit (NaN too).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// The end of an HDF5 file as its superblock records it (version 0, HDF5 1.10's default): where the
// file ended at its last flush. `end` given: recorded instead.
std::uint64_t recorded_end(const std::string& path, std::uint64_t end = 0) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  unsigned char head[48] = {};
  f.read(reinterpret_cast<char*>(head), sizeof head);
  if (!f || head[8] != 0 || head[13] != 8) return 0;  // superblock version, size of offsets
  if (end > 0) {
    f.seekp(40);
    f.write(reinterpret_cast<const char*>(&end), sizeof end);
    return end;
  }
  std::memcpy(&end, head + 40, sizeof end);
  return end;
}

// Two ways a kill leaves the partial HDF5 file damaged.
// The writes since the last flush half done: the superblock records the end of the file as it
// was at an earlier flush, and what lies past it is lost (the tester's file: the B-tree of
// /steady_state past it, the root attributes still read).
void cut_recorded_end(const std::string& path) {
  const std::uint64_t end = recorded_end(path);
  ASSERT_GT(end, 65536u);
  recorded_end(path, end / 2);
}
// The file cut short (short of the end it records): it does not open.
void cut_file(const std::string& path) {
  const std::uint64_t end = recorded_end(path);
  ASSERT_GT(end, 65536u);
  std::filesystem::resize_file(path, end / 2);
}

// A sweep killed (kill -9) while writing --hdf5 left its partial file damaged: --resume appended
// to it and aborted inside libhdf5 (exit 134), or stopped with exit 2 and HDF5's internals on
// stderr. The resumed sweep keeps the cases that read back, runs the others again, says so, and
// ends with both files as an uninterrupted run writes them.
TEST(CliSweep, ResumeAfterAKillRecoversADamagedPartialHdf5File) {
  TempDir dir;
  // Longer than the second between two flushes of the HDF5 file.
  const std::string study = write_slow_study(dir, 120);
  const std::string out = dir / "r.csv", journal = out + ".journal", h5 = dir / "r.h5";
  const Outcome reference =
      run({"sweep", study, "--out", dir / "ref.csv", "--hdf5", dir / "ref.h5", "-q"});
  ASSERT_EQ(reference.code, 0) << reference.err;
  const Hdf5File ref(dir / "ref.h5");
  ASSERT_TRUE(ref.ok());
  const std::vector<std::string> cases = ref.names("steady_state");
  ASSERT_EQ(cases.size(), 120u);
  const std::vector<std::string> columns = ref.names("steady_state/" + cases.front());
  ASSERT_GE(columns.size(), 20u);

  for (const auto& [how, damage] :
       {std::pair<std::string, void (*)(const std::string&)>{"end cut", cut_recorded_end},
        {"file cut", cut_file}}) {
    SCOPED_TRACE(how);
    std::filesystem::remove(out);
    std::filesystem::remove(h5);
    // Killed after a flush of the partial file (a second into the sweep: its recorded end grows
    // past the 7 kB of a new file) and two more cases.
    const pid_t pid = start({"sweep", study, "--out", out, "--hdf5", h5, "--threads", "1"},
                            dir / "out", dir / "err");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (recorded_end(h5 + ".partial") <= 65536 && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const std::size_t rows = count_lines(slurp(journal));
    while (count_lines(slurp(journal)) < rows + 2 && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ::kill(pid, SIGKILL);
    Outcome o = finish(pid, dir / "out", dir / "err");
    ASSERT_EQ(o.signal, SIGKILL) << "the sweep ended before it could be killed: " << o.err;
    damage(h5 + ".partial");

    o = run({"sweep", study, "--out", out, "--hdf5", h5, "--resume", "-q"});
    ASSERT_EQ(o.code, 0) << o.err;
    EXPECT_NE(o.err.find("oscidrum: warning: the partial HDF5 file " + h5 +
                         ".partial was damaged (the sweep was killed before it was written out): "),
              std::string::npos)
        << o.err;
    EXPECT_NE(o.err.find(" finished cases are run again for their steady states\n"),
              std::string::npos)
        << o.err;
    EXPECT_EQ(count_lines(o.err), 1u) << o.err;  // nothing of HDF5's own
    EXPECT_EQ(slurp(out), slurp(dir / "ref.csv"));
    EXPECT_FALSE(std::filesystem::exists(journal));
    EXPECT_FALSE(std::filesystem::exists(h5 + ".partial"));
    const Hdf5File f(h5);
    ASSERT_TRUE(f.ok());
    EXPECT_TRUE(same_bits(f.doubles("case"), ref.doubles("case")));
    EXPECT_TRUE(same_bits(f.doubles("results/area"), ref.doubles("results/area")));
    ASSERT_EQ(f.names("steady_state"), cases);
    for (const std::string& c : cases)
      for (const std::string& column : columns) {
        const std::string name = "steady_state/" + c + "/" + column;
        ASSERT_TRUE(same_bits(f.doubles(name), ref.doubles(name))) << name;
      }
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
      EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  }
}

// Issue 11 (2): a study split into 4 shards that run as separate processes (at the same time),
// merged, is byte for byte the unsharded result when the cases are independent (without
// continuation: with it, a shard's chains start from rest where the unsharded ones continue, which
// agrees to the steady-state tolerance only).
TEST(CliSweep, FourShardsMergeToTheUnshardedResult) {
  TempDir dir;
  const std::string study = kSource + "/examples/table2_sweep.toml";
  std::vector<pid_t> pids;
  for (int i = 1; i <= 4; ++i) {
    const std::string n = std::to_string(i);
    pids.push_back(start({"sweep", study, "--shard", n + "/4", "--out", dir / ("s" + n + ".csv"),
                          "--threads", "1", "-q", "--no-continuation"},
                         dir / ("out" + n), dir / ("err" + n)));
  }
  const Outcome whole = run({"sweep", study, "--out", dir / "all.csv", "-q", "--no-continuation"});
  ASSERT_EQ(whole.code, 0) << whole.err;
  for (int i = 1; i <= 4; ++i) {
    const std::string n = std::to_string(i);
    const Outcome o =
        finish(pids[static_cast<std::size_t>(i - 1)], dir / ("out" + n), dir / ("err" + n));
    ASSERT_EQ(o.code, 0) << o.err;
  }
  const std::string s2 = slurp(dir / "s2.csv");
  EXPECT_EQ(s2.rfind("# oscidrum shard 2/4 of study ", 0), 0u);
  EXPECT_EQ(count_lines(s2), 2u + 14u);  // cases 1, 5, ..., 53
  const Outcome merged = run({"merge", dir / "s3.csv", dir / "s1.csv", dir / "s4.csv",
                              dir / "s2.csv", "--out", dir / "merged.csv", "-q"});
  ASSERT_EQ(merged.code, 0) << merged.err;
  EXPECT_EQ(slurp(dir / "merged.csv"), slurp(dir / "all.csv"));  // byte for byte
  const Outcome to_stdout =
      run({"merge", dir / "s1.csv", dir / "s2.csv", dir / "s3.csv", dir / "s4.csv"});
  EXPECT_EQ(to_stdout.out, slurp(dir / "all.csv"));

  // Missing, duplicated and foreign shards: exit 2 with one line that says which.
  Outcome o = run({"merge", dir / "s1.csv", dir / "s2.csv", dir / "s4.csv"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("1 of 4 shards missing: 3"), std::string::npos) << o.err;
  o = run(
      {"merge", dir / "s1.csv", dir / "s2.csv", dir / "s3.csv", dir / "s4.csv", dir / "s2.csv"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("shard 2/4 is given twice"), std::string::npos) << o.err;
  o = run({"sweep", study, "--shard", "3/4", "--out", dir / "foreign.csv", "-q", "--set",
           "numerics.max_periods=4000"});
  ASSERT_EQ(o.code, 0) << o.err;
  o = run({"merge", dir / "s1.csv", dir / "s2.csv", dir / "foreign.csv", dir / "s4.csv"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("belongs to a different study"), std::string::npos) << o.err;
  o = run({"merge", dir / "all.csv"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("is not the output of 'oscidrum sweep --shard I/N'"), std::string::npos);
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1);
  o = run({"sweep", study, "--shard", "5/4"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("1 <= I <= N"), std::string::npos) << o.err;
  // The merged study written over one of its shards would lose that shard: refused, the shard
  // left as it was.
  const std::string s1 = slurp(dir / "s1.csv");
  o = run({"merge", dir / "s1.csv", dir / "s2.csv", dir / "s3.csv", dir / "s4.csv", "--out",
           dir / "s1.csv"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("is the shard"), std::string::npos) << o.err;
  EXPECT_EQ(slurp(dir / "s1.csv"), s1);
}

std::vector<std::string> column(const std::string& csv, const std::string& name) {
  std::istringstream lines(csv);
  std::string line;
  std::vector<std::string> out;
  std::size_t index = std::string::npos;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells(1);  // RFC 4180: a quoted cell may hold commas
    bool quoted = false;
    for (char ch : line) {
      if (ch == '"')
        quoted = !quoted;
      else if (ch == ',' && !quoted)
        cells.emplace_back();
      else
        cells.back() += ch;
    }
    if (index == std::string::npos) {
      index = static_cast<std::size_t>(std::find(cells.begin(), cells.end(), name) - cells.begin());
      continue;
    }
    out.push_back(index < cells.size() ? cells[index] : "");
  }
  return out;
}

// More shards than cases: a shard that holds none failed none (exit 0, a CSV with its header),
// and the merge of all the shards is the study.
TEST(CliSweep, AShardWithoutCasesSucceeds) {
  TempDir dir;
  const std::string study = dir / "two.toml";
  std::ofstream(study) << "[sweep]\n\"soil.table2_G\" = [5e6, 10e6]\n";
  for (const std::string n : {"1", "2", "3"}) {
    const Outcome o =
        run({"sweep", study, "--shard", n + "/3", "--out", dir / ("s" + n + ".csv"), "-q"});
    EXPECT_EQ(o.code, 0) << n << ": " << o.err;
  }
  const Outcome o =
      run({"merge", dir / "s1.csv", dir / "s2.csv", dir / "s3.csv", "--out", dir / "all.csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(column(slurp(dir / "all.csv"), "status[-]").size(), 2u);
}

// Issue 7 (3): with shooting, the cases of examples/table2_sweep.toml (14 G slowest x 2 contacts
// x 2 torques) are chained along G, the factor with the most values: 4 chains of 14, each case
// after the first of its chain started from its neighbour. --no-continuation starts all from
// rest; a shard chains its own cases.
TEST(CliSweep, ShootingContinuesAlongTheLongestFactor) {
  TempDir dir;
  const std::string study = kSource + "/examples/table2_sweep.toml";
  const std::string shooting = "numerics.method=shooting";
  const Outcome warm = run({"sweep", study, "--set", shooting, "-q", "--threads", "2"});
  ASSERT_EQ(warm.code, 0) << warm.err;
  const std::vector<std::string> started = column(warm.out, "warm_start[-]");
  ASSERT_EQ(started.size(), 56u);
  for (std::size_t i = 0; i < started.size(); ++i)
    EXPECT_EQ(started[i], i < 4 ? "0" : "1") << "case " << i;
  const Outcome cold =
      run({"sweep", study, "--set", shooting, "-q", "--threads", "2", "--no-continuation"});
  ASSERT_EQ(cold.code, 0) << cold.err;
  const std::vector<std::string> not_started = column(cold.out, "warm_start[-]");
  EXPECT_EQ(std::count(not_started.begin(), not_started.end(), "0"), 56);
  EXPECT_EQ(column(warm.out, "status[-]"), column(cold.out, "status[-]"));
  // A --set of numerics.continuation holds over the flag, said (the flag won without a word).
  const Outcome set = run({"sweep", study, "--set", shooting, "-q", "--threads", "2",
                           "--no-continuation", "--set", "numerics.continuation=true"});
  ASSERT_EQ(set.code, 0) << set.err;
  EXPECT_EQ(column(set.out, "warm_start[-]"), started);
  EXPECT_NE(set.err.find("--set numerics.continuation=true overrides --no-continuation"),
            std::string::npos)
      << set.err;
  // Shard 2/4 holds cases 1, 5, ..., 53: one contact and torque, all 14 G values, one chain.
  const Outcome shard = run({"sweep", study, "--set", shooting, "-q", "--shard", "2/4"});
  ASSERT_EQ(shard.code, 0) << shard.err;
  const std::vector<std::string> in_shard = column(shard.out, "warm_start[-]");
  ASSERT_EQ(in_shard.size(), 14u);
  EXPECT_EQ(std::count(in_shard.begin(), in_shard.end(), "1"), 13);
}

// Issue 14 (6): --out naming a directory failed only after every case had run, and left
// DIR.journal behind.
TEST(CliSweep, UnwritableOutIsRefusedBeforeAnyCaseRuns) {
  TempDir dir;
  std::filesystem::create_directory(dir / "results");
  const std::string study = kSource + "/examples/table2_sweep.toml";
  Outcome o = run({"sweep", study, "--out", dir / "results"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("is a directory"), std::string::npos) << o.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "results.journal"));
  o = run({"sweep", study, "--out", dir / "no/such/r.csv"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("does not exist"), std::string::npos) << o.err;
  // --hdf5 named as the sweep's journal was deleted with it at the end (exit 0, no HDF5 file);
  // --out named as the HDF5 file being written was overwritten by it.
  const std::string csv = dir / "r.csv";
  o = run({"sweep", study, "--out", csv, "--hdf5", csv + ".journal", "-q"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("the sweep keeps its journal in"), std::string::npos) << o.err;
  o = run({"sweep", study, "--out", dir / "r.partial", "--hdf5", dir / "r", "-q"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("writes the HDF5 file as"), std::string::npos) << o.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "r.partial"));
  // --cases-dir named as --out: the directory was made, then the file refused (it is one).
  o = run({"sweep", study, "--out", dir / "y.csv", "--cases-dir", dir / "y.csv", "-q"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("a directory and a file cannot have one name"), std::string::npos) << o.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "y.csv"));
  o = run({"sweep", study, "--out", ""});  // issue 14 (4): an empty path was ignored
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--out needs a file name"), std::string::npos) << o.err;
  EXPECT_EQ(o.out, "");
  // Harmonics beyond the samples' Nyquist limit: named as the flag, not the library's option.
  o = run({"sweep", study, "--harmonics", "600", "-q"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--harmonics (default 10) must be below numerics.samples_per_period / 2 = "
                       "512, the samples' Nyquist limit (case 0); got 600: give --harmonics 511 "
                       "or less, or numerics.samples_per_period of at least 1202"),
            std::string::npos)
      << o.err;
  // The default 10 beyond what 16 samples per period resolve: both ways out named, by run and
  // by continue (whose points' metrics were NaN without a word).
  for (const char* command : {"run", "continue"}) {
    std::vector<std::string> args = {command, "--set", "numerics.samples_per_period=16", "-q"};
    if (std::string(command) == "continue")
      args.insert(args.end(), {"--param", "contact.mu", "--from", "0.5", "--to", "0.45"});
    o = run(args);
    EXPECT_EQ(o.code, 2) << command;
    EXPECT_NE(o.err.find("got 10: give --harmonics 7 or less, or numerics.samples_per_period of "
                         "at least 22"),
              std::string::npos)
        << o.err;
  }
}

// A figure that cannot be drawn (its format, its metric) is refused before the first case: no
// journal, no results, exit code 2.
TEST(CliSweep, PlotOptionsAreCheckedBeforeAnyCaseRuns) {
  TempDir dir;
  const std::string study = kSource + "/examples/table2_sweep.toml";
  const std::string out = dir / "r.csv";
  Outcome o = run({"sweep", study, "--out", out, "--plot", dir / "f.jpg"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--plot " + (dir / "f.jpg") + ": the figure's format"), std::string::npos)
      << o.err;
  o = run({"sweep", study, "--out", out, "--plot", dir / "f.png", "--plot-metric", "aera"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--plot-metric aera: not a column of the results"), std::string::npos)
      << o.err;
  o = run(
      {"sweep", study, "--out", out, "--plot", dir / "f.png", "--plot-metric", "soil.table2_G"});
  EXPECT_EQ(o.code, 2) << "a swept key is not a metric";
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(out + ".journal"));
}

// --out /dev/stdout (a link to the pipe or file the test reads): written through, and the
// journal, if any, beside that file, never beside the device node.
TEST(CliSweep, OutToStdoutWritesThroughAndNoJournalInDev) {
  const std::string study = kSource + "/examples/table2_sweep.toml";
  const Outcome o = run({"sweep", study, "--out", "/dev/stdout", "--quiet"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.out.rfind("case[-],soil.table2_G[Pa]", 0), 0u) << o.out.substr(0, 200);
  EXPECT_EQ(std::count(o.out.begin(), o.out.end(), '\n'), 57);
  EXPECT_FALSE(std::filesystem::exists("/dev/stdout.journal"));
  // '-' is stdout, as for run's --csv and merge's --out (not a file named '-'); an empty name
  // for the figure is refused before any case runs.
  TempDir dir;
  const Outcome dash = run({"sweep", study, "--out", "-", "--quiet"});
  EXPECT_EQ(dash.code, 0) << dash.err;
  EXPECT_EQ(dash.out, o.out);
  EXPECT_FALSE(std::filesystem::exists("-"));  // in the working directory, the child's too
  const Outcome empty_plot = run({"sweep", study, "--out", dir / "r.csv", "--plot", ""});
  EXPECT_EQ(empty_plot.code, 2);
  EXPECT_NE(empty_plot.err.find("--plot needs a file name"), std::string::npos) << empty_plot.err;
}

// A value of the study's base case that the sweep replaces is warned of, with --quiet too (it hid
// the warning; --quiet hides progress and the summary only).
TEST(CliSweep, QuietKeepsTheWarningOfAReplacedBaseValue) {
  TempDir dir;
  std::ofstream(dir / "s.toml")
      << "[soil]\ntable2_G = 25e6\n[sweep]\n\"soil.table2_G\" = [5e6, 10e6]\n";
  const Outcome o = run({"sweep", dir / "s.toml", "-q"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("soil.table2_G is swept by the study: this value is replaced in every case"),
            std::string::npos)
      << o.err;
}

// A friction coefficient swept where every case rolls without a friction limit is said (every
// row the same motion, exit 0 and no word); swept together with pure_rolling it is meant.
TEST(CliSweep, AFrictionKeySweptUnderPureRollingIsSaid) {
  TempDir dir;
  std::ofstream(dir / "rolling.toml")
      << "[contact]\npure_rolling = true\n[sweep]\n\"contact.mu\" = [0.3, 0.4]\n";
  const Outcome o = run({"sweep", dir / "rolling.toml", "-q"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("contact.mu is swept, but has no effect in any of the 2 cases: "
                       "contact.pure_rolling = true"),
            std::string::npos)
      << o.err;
  std::ofstream(dir / "both.toml")
      << "[sweep]\n\"contact.mu\" = [0.3, 0.4]\n\"contact.pure_rolling\" = [true, false]\n";
  const Outcome both = run({"sweep", dir / "both.toml", "-q"});
  EXPECT_EQ(both.code, 0) << both.err;
  EXPECT_EQ(both.err.find("has no effect"), std::string::npos) << both.err;
}

// Keys that change no output of a sweep are said too: the frame's mass (Appendix A only), and
// continuation where every case runs the transient method from rest.
TEST(CliSweep, KeysThatChangeNoOutputAreSaid) {
  TempDir dir;
  std::ofstream(dir / "mf.toml") << "[sweep]\n\"roller.m_f\" = [2000.0, 3000.0]\n";
  const Outcome mf = run({"sweep", dir / "mf.toml", "-q"});
  EXPECT_EQ(mf.code, 0) << mf.err;
  EXPECT_NE(mf.err.find("roller.m_f is swept, but nothing a sweep computes depends on it"),
            std::string::npos)
      << mf.err;
  std::ofstream(dir / "nc.toml") << "[numerics]\nmethod = \"transient\"\n[sweep]\n"
                                    "\"numerics.continuation\" = [true, false]\n";
  const Outcome nc = run({"sweep", dir / "nc.toml", "-q"});
  EXPECT_EQ(nc.code, 0) << nc.err;
  EXPECT_NE(nc.err.find("numerics.continuation is swept, but has no effect in any of the 2 cases"),
            std::string::npos)
      << nc.err;
  // With shooting, continuation is what such a study compares: meant.
  std::ofstream(dir / "shoot.toml") << "[sweep]\n\"numerics.continuation\" = [true, false]\n";
  const Outcome shoot = run({"sweep", dir / "shoot.toml", "-q"});
  EXPECT_EQ(shoot.err.find("has no effect"), std::string::npos) << shoot.err;
}

}  // namespace
}  // namespace oscidrum::test
