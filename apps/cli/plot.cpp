// --plot and `oscidrum paper`: spawn a module of the Python package (posix_spawn, no shell).
#include "plot.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "terminal.hpp"

extern char** environ;

namespace oscidrum::cli {

int plot_interrupted(const std::string& data_note) {
  std::cerr << "oscidrum: interrupted while plotting; " << data_note << "\n";
  return interrupted_exit_code();
}

bool run_plot(const std::string& csv, const std::string& json, const std::string& dir, bool quiet) {
  return run_python({"oscidrum.plot", "case", "--csv", csv, "--json", json, "--out", dir},
                    "the data are in " + csv + " and " + json, {}, quiet) == 0;
}

std::string python_interpreter() {
  // 1. The user's choice.
  if (const char* env = std::getenv("OSCIDRUM_PYTHON"); env && *env) return env;
    // 2. The interpreter this build made the package for (CMake's Python3_EXECUTABLE): `python3`
    //    on PATH may be another one (a pyenv or venv interpreter without Debian's NumPy and
    //    matplotlib), so PATH is not searched.
#ifdef OSCIDRUM_PYTHON_EXECUTABLE
  if (::access(OSCIDRUM_PYTHON_EXECUTABLE, X_OK) == 0) return OSCIDRUM_PYTHON_EXECUTABLE;
#endif
  // 3. Debian's interpreter, which scripts/setup-debian.sh installs the packages for.
  return "/usr/bin/python3";
}

namespace {

// `python -m MODULE ARGS` with SIGINT and SIGTERM answered from the first line: the child starts
// with them blocked (below), and until the module installs its own handlers
// (oscidrum._interrupt.run_main) one of them ends it at once with 128 + its number, no output.
// Python's default handler raised KeyboardInterrupt in the middle of importing numpy or
// matplotlib and printed its traceback (exit 1) under the tool's "interrupted".
constexpr const char* kBootstrap =
    "import os, runpy, signal, sys\n"
    "def _stop(signum, frame):\n"
    "    os._exit(128 + signum)\n"
    "for _s in (signal.SIGINT, signal.SIGTERM):\n"
    "    signal.signal(_s, _stop)\n"
    "signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})\n"
    "del sys.argv[0]\n"
    "runpy.run_module(sys.argv[0], run_name='__main__', alter_sys=True)\n";

}  // namespace

int run_python(const std::vector<std::string>& module_args, const std::string& data_note,
               const std::vector<int>& quiet_status, bool quiet, bool plotting) {
  const std::string python = python_interpreter();
  std::vector<std::string> args = {python, "-c", kBootstrap};
  args.insert(args.end(), module_args.begin(), module_args.end());
  const std::string what = "'" + python + " -m " + module_args.front() + "'";
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  // Environment: ours, with the source tree's python/ first on PYTHONPATH if it exists.
  std::vector<std::string> env;
  std::string pythonpath;
#ifdef OSCIDRUM_PYTHON_DIR
  if (std::filesystem::is_directory(OSCIDRUM_PYTHON_DIR "/oscidrum"))
    pythonpath = OSCIDRUM_PYTHON_DIR;
#endif
  for (char** e = environ; *e; ++e) {
    std::string entry = *e;
    if (entry.starts_with("PYTHONPATH=")) {
      const std::string old = entry.substr(11);
      if (!old.empty()) pythonpath += (pythonpath.empty() ? "" : ":") + old;
      continue;
    }
    env.push_back(std::move(entry));
  }
  if (!pythonpath.empty()) env.push_back("PYTHONPATH=" + pythonpath);
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // The module's stdout (the files it wrote) on our stderr, or nowhere with --quiet (-q printed
  // the figure's name alone); its errors go to stderr either way.
  if (quiet)
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  else
    posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  // The child gets the signals' default actions but keeps them blocked (as they are in this
  // process: terminal.hpp) until kBootstrap's handlers are in place.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t held, defaults;
  sigemptyset(&held);
  sigaddset(&held, SIGINT);
  sigaddset(&held, SIGTERM);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigmask(&attr, &held);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, python.c_str(), &actions, &attr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    std::cerr << "oscidrum: error: " << what << " could not start (" << std::strerror(rc)
              << "; set OSCIDRUM_PYTHON to the interpreter the oscidrum package is installed for, "
                 "see docs/python.md); "
              << data_note << "\n";
    return -1;
  }
  // Wait, passing SIGINT or SIGTERM on to the child (it cleans up and exits; the modules exit
  // 130 or 143 without a traceback).
  set_child_process(pid, plotting ? "while plotting; " + data_note : std::string());
  int status = 0;
  bool passed_on = false;
  while (true) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) {
      set_child_process(0);
      std::cerr << "oscidrum: error: " << what << ": waitpid failed: " << std::strerror(errno)
                << "\n";
      return -1;
    }
    if (interrupted() && !passed_on) {
      ::kill(pid, interrupted_exit_code() - 128);
      passed_on = true;
    }
    ::usleep(5000);
  }
  set_child_process(0);
  if (interrupted()) return -1;  // the caller reports the interruption
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 0;
  // The module said why (oscidrum._interrupt.EXIT_EXPLAINED: no data to plot, a bad file): not
  // a missing package, which the message below suggests.
  constexpr int kModuleExplained = 3;
  if (WIFEXITED(status) && (WEXITSTATUS(status) == kModuleExplained ||
                            std::find(quiet_status.begin(), quiet_status.end(),
                                      WEXITSTATUS(status)) != quiet_status.end()))
    return WEXITSTATUS(status);
  std::cerr
      << "oscidrum: error: " << what << " "
      << (WIFEXITED(status) ? "exited with status " + std::to_string(WEXITSTATUS(status))
                            : std::string("was killed by a signal"))
      << " (is the oscidrum Python package installed for it, with matplotlib? set OSCIDRUM_PYTHON "
         "to the interpreter that has it; see docs/python.md); "
      << data_note << "\n";
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace oscidrum::cli
