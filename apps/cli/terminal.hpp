// terminal.hpp: Ctrl-C (SIGINT) and SIGTERM, and progress lines on stderr.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>

namespace oscidrum::cli {

/// Take over SIGINT and SIGTERM for the whole run (main calls it first, before any thread starts;
/// later calls do nothing). The signals are blocked in every thread and received by one watcher
/// thread, which sets the flag interrupted() reads (the one piece of global state of the CLI).
/// Commands poll it, stop starting work, finish or discard what they write, and return
/// interrupted_exit_code(). A command that has not ended 0.8 s after the signal, or a second
/// signal, ends the process at once with that exit code and "oscidrum: interrupted" (killing a
/// child process registered by set_child_process): every command stops within 1 s.
void install_interrupt_handlers();

/// True once SIGINT or SIGTERM arrived.
bool interrupted();

/// The exit code of a command that stopped because of the signal: 130 for SIGINT, 143 for
/// SIGTERM (128 + the signal's number, as a shell reports a process killed by it).
int interrupted_exit_code();

/// "SIGINT" or "SIGTERM", for messages.
const char* interrupt_name();

/// The child process the CLI waits for (a Python module), or 0: the watcher kills it when it ends
/// the process. `note` completes the watcher's "oscidrum: interrupted" then ("while plotting;
/// the data are in ..."), so that a child slow to stop (a figure being drawn on a loaded machine)
/// does not lose the line that says where the data are.
void set_child_process(pid_t pid, const std::string& note = {});

/// True if stderr is a terminal (progress lines are shown only then).
bool stderr_is_terminal();

/// One self-overwriting status line on stderr, redrawn at most 10 times a second. Disabled: does
/// nothing.
class ProgressLine {
 public:
  explicit ProgressLine(bool enabled) : enabled_(enabled) {}
  ~ProgressLine() { clear(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Redraw with `text` (throttled unless `force`).
  void update(const std::string& text, bool force = false);
  /// Erase the line.
  void clear();

 private:
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace oscidrum::cli
