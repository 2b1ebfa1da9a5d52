// Atomic output files and the sweep journal (POSIX: open, write, fsync, rename).
#include "oscidrum_io/files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <mutex>
#include <set>
#include <streambuf>
#include <utility>
#include <vector>

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

OutputTarget output_target(const std::string& path, bool regular_only) {
  if (path.empty()) throw Error("cannot write a file with an empty name");
  // A FIFO or a character device reached through links that name no path (/dev/stdout ->
  // /proc/self/fd/1 -> "pipe:[...]"): classified by following them, written by the name given.
  if (struct stat followed{}; ::stat(path.c_str(), &followed) == 0 &&
                              (S_ISFIFO(followed.st_mode) || S_ISCHR(followed.st_mode))) {
    if (!regular_only) return {path, true};
    throw Error("cannot write " + path + ": it is " +
                (S_ISFIFO(followed.st_mode) ? "a FIFO" : "a character device") +
                " and this output needs a regular file");
  }
  std::string p = path;
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0) {
      if (errno == ENOENT) return {p, false};  // a new file (or a dangling link's target)
      throw Error("cannot write " + path + ": " + std::strerror(errno));
    }
    if (S_ISLNK(st.st_mode)) {
      if (hops >= 40) throw Error("cannot write " + path + ": too many levels of symbolic links");
      std::string link(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 4096) + 1, '\0');
      const ssize_t n = ::readlink(p.c_str(), link.data(), link.size());
      if (n < 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
      link.resize(static_cast<std::size_t>(n));
      if (link.empty()) throw Error("cannot write " + path + ": an empty symbolic link");
      const std::filesystem::path parent = std::filesystem::path(p).parent_path();
      p = link.front() == '/' || parent.empty() ? link : (parent / link).string();
      continue;
    }
    if (S_ISREG(st.st_mode)) return {p, false};
    const char* kind = S_ISDIR(st.st_mode)    ? "a directory"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                       : S_ISFIFO(st.st_mode) ? "a FIFO"
                       : S_ISCHR(st.st_mode)  ? "a character device"
                                              : "not a regular file";
    const bool stream = S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode);
    if (stream && !regular_only) return {p, true};
    const std::string shown = p == path ? path : path + " (-> " + p + ")";
    throw Error("cannot write " + shown + ": it is " + kind + (stream ? " and" : ";") +
                (regular_only ? " this output needs a regular file"
                              : " oscidrum writes regular files, FIFOs and character devices"));
  }
}

namespace {

// The temporary files of the OutputFiles alive and not yet committed or discarded
// (remove_pending_outputs): the one state of this file that is the process's, as the files are.
std::mutex& pending_mutex() {
  static std::mutex m;
  return m;
}
std::set<std::string>& pending_paths() {
  static std::set<std::string> paths;
  return paths;
}
void track_pending(const std::string& path, bool pending) {
  const std::lock_guard<std::mutex> lock(pending_mutex());
  if (pending)
    pending_paths().insert(path);
  else
    pending_paths().erase(path);
}

}  // namespace

int remove_stale_temporaries(const std::string& target) noexcept {
  namespace fs = std::filesystem;
  int removed = 0;
  try {
    const fs::path t(target);
    const fs::path dir = t.has_parent_path() ? t.parent_path() : fs::path(".");
    const std::string prefix = t.filename().string() + ".tmp.";
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
      // PID.N, both decimal.
      const std::string rest = name.substr(prefix.size());
      const std::size_t dot = rest.find('.');
      const auto digits = [](const std::string& s) {
        return !s.empty() && s.size() <= 18 &&
               std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
      };
      if (dot == std::string::npos || !digits(rest.substr(0, dot)) || !digits(rest.substr(dot + 1)))
        continue;
      const long long pid = std::stoll(rest.substr(0, dot));
      if (pid <= 0 || pid > std::numeric_limits<pid_t>::max() || pid == ::getpid()) continue;
      // Running (or another user's: EPERM): not stale.
      if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
      if (!fs::is_regular_file(it->symlink_status(ec)) || ec) continue;
      if (::unlink(it->path().c_str()) == 0) ++removed;
    }
  } catch (...) {  // a name that cannot be converted, an allocation: leave the files
  }
  return removed;
}

void remove_pending_outputs() noexcept {
  const std::lock_guard<std::mutex> lock(pending_mutex());
  for (const std::string& path : pending_paths()) ::unlink(path.c_str());
  pending_paths().clear();
}

OutputFile::OutputFile(std::string path, bool regular_only)
    : path_(std::move(path)), target_(output_target(path_, regular_only)) {
  if (target_.direct) {
    write_path_ = target_.path;
    return;
  }
  remove_stale_temporaries(target_.path);
  // Reserve a fresh temporary name beside the target (O_EXCL: never through a planted link).
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0;; ++attempt) {
    write_path_ = target_.path + ".tmp." + std::to_string(::getpid()) + "." +
                  std::to_string(counter.fetch_add(1));
    const int fd = ::open(write_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      pending_ = true;
      track_pending(write_path_, true);
      return;
    }
    if (errno != EEXIST || attempt >= 100) {
      // The file is written beside its target and renamed over it: say where that failed (a
      // file /proc allows to exist but no new file beside it gave "No such file or directory").
      const std::string dir = std::filesystem::path(target_.path).parent_path().string();
      throw Error("cannot write " + path_ + ": cannot create a file in its directory " +
                  (dir.empty() ? std::string(".") : dir) + " (" + std::strerror(errno) +
                  "; oscidrum writes a temporary file there and renames it)");
    }
  }
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() {
  if (pending_) {
    ::unlink(write_path_.c_str());
    track_pending(write_path_, false);
  }
  pending_ = false;
}

void OutputFile::commit() {
  if (target_.direct) return;
  if (!pending_) throw Error("cannot write " + path_ + ": the file was already committed");
  auto fail = [&](int err) {
    discard();
    throw Error("cannot write " + path_ + ": " + std::strerror(err));
  };
  const int fd = ::open(write_path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(errno);
  // The replaced file's permissions carry over (a new file keeps 0666 less the umask).
  struct stat old {};
  if (::stat(target_.path.c_str(), &old) == 0 && S_ISREG(old.st_mode))
    (void)::fchmod(fd, old.st_mode & 07777);
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    fail(err);
  }
  ::close(fd);
  // Between the check and here the target may have become something else: rename only over a
  // regular file (or nothing).
  struct stat now {};
  if (::lstat(target_.path.c_str(), &now) == 0 && !S_ISREG(now.st_mode)) {
    discard();
    throw Error("cannot write " + path_ + ": " + target_.path + " changed into " +
                "something that is not a regular file while it was written");
  }
  if (std::rename(write_path_.c_str(), target_.path.c_str()) != 0) fail(errno);
  pending_ = false;
  track_pending(write_path_, false);
}

namespace {

// An output stream on a file descriptor (64 KB buffer, EINTR retried, errors kept for the
// caller's one-line message).
class FdBuf : public std::streambuf {
 public:
  FdBuf(int fd, std::string path) : fd_(fd), path_(std::move(path)), buf_(1 << 16) {
    setp(buf_.data(), buf_.data() + buf_.size());
  }
  int error() const { return error_; }

 protected:
  int overflow(int ch) override {
    if (!drain()) return traits_type::eof();
    if (ch != traits_type::eof()) {
      *pptr() = static_cast<char>(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0 && error_ == 0) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        error_ = n < 0 ? errno : EIO;
        break;
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    setp(buf_.data(), buf_.data() + buf_.size());
    return error_ == 0;
  }

  int fd_;
  std::string path_;
  std::vector<char> buf_;
  int error_ = 0;
};

}  // namespace

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write) {
  OutputFile file(path);
  // A FIFO blocks here until it has a reader; a signal (Ctrl-C) ends the wait with EINTR.
  const int fd =
      ::open(file.write_path().c_str(), O_WRONLY | O_CLOEXEC | (file.direct() ? 0 : O_TRUNC));
  if (fd < 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
  int err = 0;
  try {
    FdBuf buf(fd, path);
    std::ostream out(&buf);
    write(out);
    out.flush();
    err = buf.error();
    if (err == 0 && !out) err = EIO;
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0 && err == 0 && !file.direct()) err = errno;
  if (err != 0) throw Error("cannot write " + path + ": " + std::strerror(err));
  file.commit();
}

void write_file_atomic(const std::string& path, std::string_view text) {
  write_file_atomic(path, [text](std::ostream& out) {
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

void remove_file(const std::string& path) { ::unlink(path.c_str()); }

Journal::Journal(std::string path, std::uint64_t fingerprint, std::size_t n_cases, bool resume,
                 bool restart)
    : path_(std::move(path)) {
  const std::string header = journal_header(fingerprint, n_cases);
  // O_NONBLOCK: a FIFO in the journal's place must not block the open; it is refused below.
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NONBLOCK, 0644);
  if (fd_ < 0) throw Error("cannot write " + path_ + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode) ||
      ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw Error("cannot write the journal " + path_ +
                ": it is not a regular file (a sweep's journal must be one; remove it or choose "
                "another --out)");
  }
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

namespace {

// The lines of the open file `fd` from offset 0, read in blocks (never the whole file at once):
// `on_line(line, end)` for each complete line, `end` the offset just past its '\n'; returns the
// bytes after the last complete line (a torn last line) as `tail`. Stops early when `on_line`
// returns false.
void read_lines(int fd, const std::string& path,
                const std::function<bool(const std::string&, std::size_t)>& on_line,
                std::size_t limit, std::string* tail) {
  std::string pending;
  std::size_t offset = 0;  // of the first byte of `pending`
  std::vector<char> buf(1 << 16);
  while (offset + pending.size() < limit) {
    const std::size_t want = std::min(buf.size(), limit - offset - pending.size());
    const ssize_t n = ::pread(fd, buf.data(), want, static_cast<off_t>(offset + pending.size()));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error("cannot read " + path + ": " + std::strerror(errno));
    if (n == 0) break;
    pending.append(buf.data(), static_cast<std::size_t>(n));
    std::size_t start = 0;
    for (std::size_t nl; (nl = pending.find('\n', start)) != std::string::npos; start = nl + 1)
      if (!on_line(pending.substr(start, nl - start), offset + nl + 1)) return;
    offset += start;
    pending.erase(0, start);
  }
  if (tail) *tail = pending;
}

}  // namespace

void Journal::open_locked(const std::string& header, std::size_t n_cases, bool resume,
                          bool restart) {
  // Read line by line: a million-case journal is checked without holding it.
  std::size_t good_bytes = 0, lines = 0;
  bool same = false, is_header = false;
  std::string tail;
  if (!restart) {
    read_lines(
        fd_, path_,
        [&](const std::string& line, std::size_t end) {
          if (lines++ == 0) {
            same = line == header;
            is_header = line.starts_with("# oscidrum sweep journal ");
            good_bytes = end;
            return true;
          }
          if (!(resume && same)) return true;
          char* stop = nullptr;
          const unsigned long long index = std::strtoull(line.c_str(), &stop, 10);
          if (stop == line.c_str() || *stop != ',' || index >= n_cases)
            throw Error("the journal " + path_ + " is damaged (line: " + line.substr(0, 60) +
                        "); run with --restart to discard it");
          good_bytes = end;
          return true;
        },
        std::numeric_limits<std::size_t>::max(), &tail);
  }
  // An empty journal, one whose header line was cut short (killed while it was being written),
  // or one with its header and no whole row (a sweep stopped before its first case finished: on
  // a loaded machine, Ctrl-C while it was still setting up) holds no finished case: start it
  // afresh, whatever study its header names, since nothing of it would be kept.
  const bool no_cases = (lines == 0 && header.starts_with(tail)) || lines == 1;
  if (!restart && !no_cases && (lines > 0 || !tail.empty())) {
    if (!resume)
      throw Error("an unfinished sweep left the journal " + path_ + " (" +
                  std::to_string(lines ? lines - 1 : 0) +
                  " cases done); run again with --resume to finish it, or with --restart to "
                  "discard it");
    // A first line that is no journal's header (edited, or cut off the front) is damage, not
    // another study.
    if (!is_header)
      throw Error("the journal " + path_ +
                  " is damaged (its first line is not a journal's header: an edit "
                  "or a copy lost it); run with --restart to discard it");
    if (!same)
      throw Error("the journal " + path_ +
                  " belongs to a different study (its cases, output columns or HDF5 file "
                  "changed): resume with the command that started it (the same study file and "
                  "--set, --harmonics, --no-continuation, --hdf5), or run with --restart to "
                  "discard it and start over");
  } else {
    good_bytes = 0;
  }
  // A torn last line (killed while writing) is dropped.
  good_bytes_ = good_bytes;
  if (::ftruncate(fd_, static_cast<off_t>(good_bytes)) != 0 || ::lseek(fd_, 0, SEEK_END) < 0)
    throw Error("cannot write " + path_ + ": " + std::strerror(errno));
  if (good_bytes == 0) {
    write_all(fd_, header + "\n", path_);
    ::fsync(fd_);
  }
}

void Journal::for_each_done(
    const std::function<void(std::size_t index, const std::string& row)>& row) const {
  if (good_bytes_ == 0 || fd_ < 0) return;
  bool first = true;
  read_lines(
      fd_, path_,
      [&](const std::string& line, std::size_t) {
        if (std::exchange(first, false)) return true;  // the header
        row(static_cast<std::size_t>(std::strtoull(line.c_str(), nullptr, 10)), line);
        return true;
      },
      good_bytes_, nullptr);
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
