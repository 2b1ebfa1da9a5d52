// tests/cli/process.hpp: run the oscidrum binary as a child process (posix_spawn, no shell).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace oscidrum::test {

/// How a child process ended, and what it printed.
struct Outcome {
  int code = -1;           ///< exit status; -1 if killed by a signal
  int signal = 0;          ///< the signal that ended it, or 0
  std::string out;         ///< stdout
  std::string err;         ///< stderr
  double seconds = 0;      ///< wall time from the call of finish() to the end of the child
  long max_rss_kb = 0;     ///< the child's peak resident memory [KiB]
  double cpu_seconds = 0;  ///< the child's CPU time, user and system [s]
  bool hung = false;       ///< killed by finish() at its time limit
};

/// Start `oscidrum args...` with stdout and stderr going to files (stdin: /dev/null).
pid_t start(const std::vector<std::string>& args, const std::string& out_file,
            const std::string& err_file);

/// Wait until the started child `pid` has installed a handler for `signal` (Linux: the SigCgt
/// mask of /proc/<pid>/status), so that a signal sent next reaches the handler rather than
/// killing a child that is still starting up (slow under sanitizers). False if the child ended
/// or `timeout_ms` passed first.
bool wait_until_catching(pid_t pid, int signal, int timeout_ms = 10000);

/// Wait for a started child and collect its output files. With `limit_s` > 0, a child still
/// running `limit_s` seconds after the call is killed (SIGKILL) and reported as hung.
Outcome finish(pid_t pid, const std::string& out_file, const std::string& err_file,
               double limit_s = 0);

/// Run `oscidrum args...` to completion.
Outcome run(const std::vector<std::string>& args);

/// A file's bytes ("" if it cannot be read).
std::string slurp(const std::string& path);

/// A fresh directory for one test, removed with it.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace oscidrum::test
