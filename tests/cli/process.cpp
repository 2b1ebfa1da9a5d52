// Child processes for the CLI tests.
#include "process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace oscidrum::test {

pid_t start(const std::vector<std::string>& args, const std::string& out_file,
            const std::string& err_file) {
  std::vector<std::string> all = {OSCIDRUM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_file.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + all[0]);
  return pid;
}

bool wait_until_catching(pid_t pid, int signal, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  const std::string status_file = "/proc/" + std::to_string(pid) + "/status";
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream in(status_file);
    if (!in) return false;  // the child is gone
    for (std::string line; std::getline(in, line);) {
      // Caught by a handler, or blocked for the watcher thread that takes it with sigwait
      // (apps/cli/terminal.cpp): either way the command is ready for it.
      if (line.rfind("SigCgt:", 0) != 0 && line.rfind("SigBlk:", 0) != 0) continue;
      const unsigned long long mask = std::stoull(line.substr(7), nullptr, 16);
      if (mask & (1ULL << (signal - 1))) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

Outcome finish(pid_t pid, const std::string& out_file, const std::string& err_file,
               double limit_s) {
  int status = 0;
  rusage usage{};
  Outcome o;
  const auto begin = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  };
  while (true) {
    const pid_t r = wait4(pid, &status, limit_s > 0 ? WNOHANG : 0, &usage);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) throw std::runtime_error("wait4 failed");
    if (r == 0 && elapsed() > limit_s && !o.hung) {
      o.hung = true;
      ::kill(pid, SIGKILL);
    }
    if (r == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  o.seconds = elapsed();
  o.max_rss_kb = usage.ru_maxrss;
  o.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                  1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  if (WIFEXITED(status)) o.code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
  o.out = slurp(out_file);
  o.err = slurp(err_file);
  return o;
}

Outcome run(const std::vector<std::string>& args) {
  static std::atomic<int> counter{0};
  const std::string base = std::filesystem::temp_directory_path().string() + "/oscidrum_cli_" +
                           std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const Outcome o = finish(start(args, base + ".out", base + ".err"), base + ".out", base + ".err");
  std::filesystem::remove(base + ".out");
  std::filesystem::remove(base + ".err");
  return o;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path().string() + "/oscidrum_cli_dir_" +
          std::to_string(::getpid()) + "_" + std::to_string(counter++);
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace oscidrum::test
