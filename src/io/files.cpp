// Atomic output files and the sweep journal (POSIX: open, write, fsync, rename).
#include "oscidrum_io/files.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "oscidrum/error.hpp"
#include "oscidrum_io/config.hpp"

namespace oscidrum::io {
namespace {

void write_all(int fd, std::string_view text, const std::string& path) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

std::string journal_header(std::uint64_t fingerprint, std::size_t n_cases) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "# oscidrum sweep journal v1 fingerprint %016" PRIx64 " cases %zu",
                fingerprint, n_cases);
  return buf;
}

}  // namespace

void write_file_atomic(const std::string& path, std::string_view text) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
  try {
    write_all(fd, text, path);
    if (::fsync(fd) != 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (::close(fd) != 0 || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw Error("cannot write " + path + ": " + reason);
  }
}

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw Error("cannot write " + path + ": " + std::strerror(errno));
      write(out);
      out.flush();
      if (!out) throw Error("cannot write " + path + ": " + std::strerror(errno));
    }
    const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || ::fsync(fd) != 0) {
      if (fd >= 0) ::close(fd);
      throw Error("cannot write " + path + ": " + std::strerror(errno));
    }
    ::close(fd);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw Error("cannot write " + path + ": " + reason);
  }
}

void remove_file(const std::string& path) { ::unlink(path.c_str()); }

Journal::Journal(std::string path, std::uint64_t fingerprint, std::size_t n_cases, bool resume,
                 bool restart)
    : path_(std::move(path)) {
  const std::string header = journal_header(fingerprint, n_cases);
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error("cannot write " + path_ + ": " + std::strerror(errno));
  // One sweep per journal: a second process (two --resume at once) would run every remaining case
  // again and append them twice. The lock goes with the descriptor (also when killed).
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK)
      throw Error("another oscidrum sweep is running with the journal " + path_ +
                  " (it holds its lock); wait for it to finish or stop it first");
    throw Error("cannot lock " + path_ + ": " + std::strerror(err));
  }
  try {
    open_locked(header, n_cases, resume, restart);
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

void Journal::open_locked(const std::string& header, std::size_t n_cases, bool resume,
                          bool restart) {
  std::string text;
  if (!restart) {
    char buf[65536];
    while (true) {
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw Error("cannot read " + path_ + ": " + std::strerror(errno));
      if (n == 0) break;
      text.append(buf, static_cast<std::size_t>(n));
    }
  }
  std::size_t good_bytes = 0;
  // An empty journal, or one whose header line was cut short (killed while it was being
  // written), holds no finished case: start it afresh.
  const std::size_t pos = text.find('\n');
  const bool no_cases = pos == std::string::npos && header.starts_with(text);
  if (!text.empty() && !no_cases) {
    std::size_t count = 0;
    const bool same = pos != std::string::npos && text.compare(0, pos, header) == 0;
    if (!resume || !same) {
      for (char ch : text) count += (ch == '\n');
      if (!resume)
        throw Error("an unfinished sweep left the journal " + path_ + " (" +
                    std::to_string(count ? count - 1 : 0) +
                    " cases done); run again with --resume to finish it, or with --restart to "
                    "discard it");
      throw Error("the journal " + path_ +
                  " belongs to a different study (its cases or output "
                  "columns changed); run with --restart to discard it and start over");
    }
    good_bytes = pos + 1;
    while (true) {
      const std::size_t end = text.find('\n', good_bytes);
      if (end == std::string::npos) break;  // a torn last line (killed while writing): dropped
      const std::string line = text.substr(good_bytes, end - good_bytes);
      char* stop = nullptr;
      const unsigned long long index = std::strtoull(line.c_str(), &stop, 10);
      if (stop == line.c_str() || *stop != ',' || index >= n_cases)
        throw Error("the journal " + path_ + " is damaged (line: " + line.substr(0, 60) +
                    "); run with --restart to discard it");
      done_.emplace(static_cast<std::size_t>(index), line);
      good_bytes = end + 1;
    }
  }
  if (::ftruncate(fd_, static_cast<off_t>(good_bytes)) != 0 || ::lseek(fd_, 0, SEEK_END) < 0)
    throw Error("cannot write " + path_ + ": " + std::strerror(errno));
  if (good_bytes == 0) {
    write_all(fd_, header + "\n", path_);
    ::fsync(fd_);
  }
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(std::size_t index, const std::string& row) {
  (void)index;
  write_all(fd_, row + "\n", path_);  // one write(2): a kill cannot interleave two rows
}

void Journal::remove() {
  ::unlink(path_.c_str());  // still locked: no other sweep can open it in between
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

}  // namespace oscidrum::io
