// The signal watcher and the progress line.
#include "terminal.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <ctime>
#include <mutex>
#include <string>
#include <thread>

#include "oscidrum_io/files.hpp"

namespace oscidrum::cli {
namespace {

// The signal that arrived (0: none yet), and the child to kill when the watcher ends the run.
std::atomic<int> g_signal{0};
std::atomic<pid_t> g_child{0};
// What the watcher's message adds while that child runs (set_child_process).
std::mutex g_note_mutex;
std::string g_note;

// How long a command has after the signal to stop by itself.
constexpr long kGraceNanoseconds = 800'000'000;

// A second signal this soon after the first is the same one delivered twice: timeout(1) sends
// it to the process and to its process group, and a terminal's Ctrl-C cannot come twice within
// 0.1 s.
constexpr long kSameSignalNanoseconds = 100'000'000;

// Waits for SIGINT or SIGTERM (blocked in every thread); after the first, gives the command the
// grace period and then ends the process, unless it ended first. A second signal ends it at once
// (one within kSameSignalNanoseconds of the first is not a second).
void watch(sigset_t set) {
  int sig = 0;
  while (sigwait(&set, &sig) != 0) {
  }
  g_signal.store(sig);
  timespec left{0, kGraceNanoseconds};
  timespec start{};
  clock_gettime(CLOCK_MONOTONIC, &start);
  while (true) {
    const int r = sigtimedwait(&set, nullptr, &left);
    if (r < 0 && errno == EAGAIN) break;  // the time is up
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    const long spent = (now.tv_sec - start.tv_sec) * 1'000'000'000L + (now.tv_nsec - start.tv_nsec);
    if (r > 0 && spent >= kSameSignalNanoseconds) break;  // a second signal
    if (spent >= kGraceNanoseconds) break;
    left = {0, kGraceNanoseconds - spent};
  }
  if (const pid_t child = g_child.load(); child > 0) ::kill(child, SIGKILL);
  // The command did not stop in time: no temporary output file of it may stay behind.
  io::remove_pending_outputs();
  std::string message = "\noscidrum: interrupted";
  {
    const std::lock_guard<std::mutex> lock(g_note_mutex);
    if (g_child.load() > 0 && !g_note.empty()) message += " " + g_note;
  }
  message += "\n";
  (void)!::write(STDERR_FILENO, message.data(), message.size());
  ::_exit(128 + sig);
}

}  // namespace

void install_interrupt_handlers() {
  static std::atomic<bool> installed{false};
  if (installed.exchange(true)) return;
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  // Blocked here, before any other thread exists: every thread inherits the mask, so only the
  // watcher receives the signals. (Children get their own mask back: plot.cpp.)
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread(watch, set).detach();
}

bool interrupted() { return g_signal.load(std::memory_order_relaxed) != 0; }

int interrupted_exit_code() { return g_signal.load() == SIGTERM ? 128 + SIGTERM : 128 + SIGINT; }

const char* interrupt_name() { return g_signal.load() == SIGTERM ? "SIGTERM" : "SIGINT"; }

void set_child_process(pid_t pid, const std::string& note) {
  {
    const std::lock_guard<std::mutex> lock(g_note_mutex);
    g_note = pid > 0 ? note : std::string();
  }
  g_child.store(pid);
}

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

void ProgressLine::update(const std::string& text, bool force) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && shown_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  std::fprintf(stderr, "\r\033[K%s", text.c_str());
  std::fflush(stderr);
  shown_ = true;
}

void ProgressLine::clear() {
  if (!enabled_ || !shown_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace oscidrum::cli
