// Tests of src/io/files.cpp: atomic writes and the sweep journal (resume, torn lines, the lock).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "io/io_test_util.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/files.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

TEST(Files, AtomicWriteReplacesWholeFile) {
  TempDir dir;
  const std::string path = dir.file("out.csv");
  write_file_atomic(path, "old\n");
  write_file_atomic(path, "new\n");
  EXPECT_EQ(read_file(path), "new\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.file("")),
                          std::filesystem::directory_iterator{}),
            1);
  // The directory is where the write fails: "no/such/dir", not "No such file" for the file.
  const std::string missing_dir =
      error_of([&] { write_file_atomic(dir.file("no/such/dir/x"), "x"); });
  EXPECT_NE(missing_dir.find("cannot write"), std::string::npos) << missing_dir;
  EXPECT_NE(missing_dir.find("cannot create a file in its directory " + dir.file("no/such/dir")),
            std::string::npos)
      << missing_dir;
  // A regular file that exists where no new file may be created beside it (/proc/version): once
  // "No such file or directory", as if the file itself were missing.
  if (std::filesystem::is_regular_file("/proc/version")) {
    const std::string message = error_of([&] { write_file_atomic("/proc/version", "x"); });
    EXPECT_NE(message.find("cannot create a file in its directory /proc"), std::string::npos)
        << message;
  }
}

// The rows a journal found, by case index (the first of a case's rows counts).
std::map<std::size_t, std::string> done(const Journal& j) {
  std::map<std::size_t, std::string> rows;
  j.for_each_done([&](std::size_t index, const std::string& row) { rows.emplace(index, row); });
  return rows;
}

// A process ended without unwinding (the CLI after an interrupt's grace period) first removes
// the temporary files of the outputs still being written; committed and discarded ones are not
// touched, and the OutputFile's own discard afterwards does no harm.
TEST(Files, PendingOutputsAreRemovedOnRequest) {
  TempDir dir;
  const auto entries = [&] {
    return std::distance(std::filesystem::directory_iterator(dir.file("")),
                         std::filesystem::directory_iterator{});
  };
  write_file_atomic(dir.file("done.csv"), "done\n");
  {
    OutputFile a(dir.file("a.csv")), b(dir.file("b.csv"));
    EXPECT_TRUE(std::filesystem::exists(a.write_path()));
    EXPECT_EQ(entries(), 3);
    b.discard();
    EXPECT_EQ(entries(), 2);
    remove_pending_outputs();
    EXPECT_FALSE(std::filesystem::exists(a.write_path()));
    EXPECT_EQ(entries(), 1);
  }
  EXPECT_EQ(read_file(dir.file("done.csv")), "done\n");
  // A committed file is no longer pending.
  OutputFile c(dir.file("c.csv"));
  std::ofstream(c.write_path()) << "c\n";
  c.commit();
  remove_pending_outputs();
  EXPECT_EQ(read_file(dir.file("c.csv")), "c\n");
}

// A writer killed while its temporary file existed (kill -9 during a sweep's final write) left
// TARGET.tmp.PID.N behind: the next OutputFile of that target deletes it, and nothing else (the
// files of running processes, other targets' and other names).
TEST(Files, TemporariesOfKilledWritersAreRemovedByTheNextWrite) {
  TempDir dir;
  // A PID that no longer runs: a child that has exited and been reaped.
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  const std::string dead = std::to_string(child), alive = std::to_string(::getppid());
  const std::vector<std::string> stale = {"out.csv.tmp." + dead + ".0",
                                          "out.csv.tmp." + dead + ".17"};
  const std::vector<std::string> kept = {"out.csv.tmp." + alive + ".0",   // a running process
                                         "other.csv.tmp." + dead + ".0",  // another target
                                         "out.csv.tmp." + dead,           // not TARGET.tmp.PID.N
                                         "out.csv.tmp.x" + dead + ".0", "out.csv.journal"};
  for (const auto& name : stale) std::ofstream(dir.file(name)) << "half\n";
  for (const auto& name : kept) std::ofstream(dir.file(name)) << "keep\n";
  write_file_atomic(dir.file("out.csv"), "new\n");
  EXPECT_EQ(read_file(dir.file("out.csv")), "new\n");
  for (const auto& name : stale) EXPECT_FALSE(std::filesystem::exists(dir.file(name))) << name;
  for (const auto& name : kept) EXPECT_TRUE(std::filesystem::exists(dir.file(name))) << name;
  // Nothing left to remove.
  EXPECT_EQ(remove_stale_temporaries(dir.file("out.csv")), 0);
}

TEST(Files, JournalResumesAndDropsATornLine) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  {
    Journal j(path, 42, 5, false);
    EXPECT_TRUE(done(j).empty());
    j.append(3, "3,a");
    j.append(0, "0,b");
  }
  {  // a kill in the middle of a row
    std::ofstream(path, std::ios::app) << "4,tor";
  }
  EXPECT_NE(error_of([&] { Journal j(path, 42, 5, false); }).find("run again with --resume"),
            std::string::npos);
  EXPECT_NE(error_of([&] { Journal j(path, 43, 5, true); }).find("belongs to a different study"),
            std::string::npos);
  {
    Journal j(path, 42, 5, true);
    ASSERT_EQ(done(j).size(), 2u);
    EXPECT_EQ(done(j).at(3), "3,a");
    EXPECT_EQ(done(j).at(0), "0,b");
    j.append(4, "4,c");
  }
  Journal j(path, 42, 5, true);
  EXPECT_EQ(done(j).size(), 3u);
  EXPECT_EQ(done(j).at(4), "4,c");
  j.remove();
  EXPECT_FALSE(std::filesystem::exists(path));
}

// Issue 14 (6): a journal killed before its first line was written is empty; --resume used to
// call it "a different study".
TEST(Files, EmptyOrTornHeaderJournalHoldsNoCaseAndIsResumable) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  std::ofstream(path).flush();  // 0 bytes
  {
    Journal j(path, 42, 5, true);
    EXPECT_TRUE(done(j).empty());
    j.append(1, "1,x");
  }
  std::ofstream(path) << "# oscidrum sweep jour";  // the header cut short
  Journal j(path, 42, 5, true);
  EXPECT_TRUE(done(j).empty());
  EXPECT_EQ(read_file(path).rfind("# oscidrum sweep journal v1 fingerprint", 0), 0u);
}

// A sweep stopped before its first case finished (Ctrl-C while a large study was still being set
// up) left a journal with its header and no row; the same command run again asked for --resume
// or --restart although nothing was kept. Such a journal, and one with a torn first row, is
// started afresh with or without --resume, whatever study its header names.
TEST(Files, JournalWithoutAFinishedRowStartsAfresh) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  { Journal j(path, 42, 5, false); }  // the header only
  {
    Journal j(path, 42, 5, false);
    EXPECT_TRUE(done(j).empty());
  }
  std::ofstream(path, std::ios::app) << "2,tor";  // a torn first row
  {
    Journal j(path, 43, 5, false);  // another study's fingerprint: nothing of it is kept
    EXPECT_TRUE(done(j).empty());
  }
  EXPECT_NE(read_file(path).find("fingerprint"), std::string::npos);
  {
    Journal j(path, 42, 5, true);
    EXPECT_TRUE(done(j).empty());
    j.append(1, "1,x");
  }
  // One finished row is kept: the guard against losing it stands.
  EXPECT_NE(error_of([&] { Journal j(path, 42, 5, false); }).find("run again with --resume"),
            std::string::npos);
  EXPECT_NE(error_of([&] { Journal j(path, 43, 5, true); }).find("belongs to a different study"),
            std::string::npos);
}

// A journal whose header line was removed (an edit) was said to belong to a different study;
// it is damaged, and says so.
TEST(Files, JournalWithoutItsHeaderLineIsDamagedNotAnotherStudy) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  {
    Journal j(path, 42, 5, false);
    j.append(0, "0,a");
    j.append(1, "1,b");
  }
  const std::string text = read_file(path);
  std::ofstream(path) << text.substr(text.find('\n') + 1);
  const std::string e = error_of([&] { Journal j(path, 42, 5, true); });
  EXPECT_NE(e.find("is damaged (its first line is not a journal's header"), std::string::npos) << e;
  EXPECT_EQ(e.find("different study"), std::string::npos) << e;
}

// Issue 14 (6): two sweeps on one journal (two --resume at once) both ran every remaining case.
TEST(Files, JournalIsLockedWhileInUse) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  {
    Journal first(path, 42, 5, false);
    first.append(0, "0,a");
    EXPECT_NE(error_of([&] {
                Journal second(path, 42, 5, true);
              }).find("another oscidrum sweep is running"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                Journal second(path, 42, 5, false, true);
              }).find("another oscidrum sweep is running"),
              std::string::npos);  // --restart must not pull it away either
  }
  Journal again(path, 42, 5, true);  // released with the first
  EXPECT_EQ(done(again).size(), 1u);
}

// A journal is read in blocks of 64 KiB, never whole: rows that straddle the blocks are read back
// intact and in order, and a torn last row is dropped.
TEST(Files, LongJournalIsReadBackRowByRow) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  const std::size_t n = 20000;
  auto row = [](std::size_t i) {
    return std::to_string(i) + "," + std::string(10 + i % 97, static_cast<char>('a' + i % 26));
  };
  {
    Journal j(path, 7, n, false);
    for (std::size_t i = 0; i < n; i += 2) j.append(i, row(i));
  }
  std::ofstream(path, std::ios::app) << "1,torn";
  Journal j(path, 7, n, true);
  std::size_t count = 0, expected = 0;
  bool in_order = true;
  j.for_each_done([&](std::size_t index, const std::string& r) {
    in_order = in_order && index == expected && r == row(expected);
    expected += 2;
    ++count;
  });
  EXPECT_TRUE(in_order);
  EXPECT_EQ(count, n / 2);
  EXPECT_EQ(read_file(path).find("torn"), std::string::npos);
}

}  // namespace
}  // namespace oscidrum::io
