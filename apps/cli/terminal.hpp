// terminal.hpp: Ctrl-C handling and progress lines on stderr.
#pragma once

#include <chrono>
#include <string>

namespace oscidrum::cli {

/// Install handlers for SIGINT and SIGTERM that only set a flag (the one piece of global state of
/// the CLI: a signal handler can do nothing else safely). Commands poll interrupted(), stop
/// starting work, flush what is finished and exit with kExitInterrupted. The handlers reset to
/// the default after the first signal, so a second Ctrl-C ends the process at once.
void install_interrupt_handlers();

/// True once SIGINT or SIGTERM arrived.
bool interrupted();

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
