#include "harness/records/run_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>
#include <filesystem>
#include <ostream>
#include <regex>
#include <sstream>

#include "harness/util/files.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

struct Holder {
  long pid = 0;
  std::string host, started, command;
};

Holder parse_holder(const std::string& text) {
  Holder h;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const auto space = line.find(' ');
    const std::string key = line.substr(0, space), value = space == std::string::npos ? "" : line.substr(space + 1);
    if (key == "pid") h.pid = std::strtol(value.c_str(), nullptr, 10);
    else if (key == "host") h.host = value;
    else if (key == "started") h.started = value;
    else if (key == "command") h.command = value;
  }
  return h;
}

std::string describe(const Holder& h) {
  if (h.pid <= 0) return "another process (which has not yet said who it is)";
  std::string text = "PID " + std::to_string(h.pid);
  if (!h.host.empty()) text += " on host " + h.host;
  if (!h.started.empty()) text += " since " + h.started;
  if (!h.command.empty()) text += ": " + h.command;
  return text;
}

std::string this_host() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

std::string now_text() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char buffer[64];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%S%z", &local);
  return buffer;
}

std::string read_all(int fd) {
  std::string text;
  char block[4096];
  for (off_t offset = 0;;) {
    const ssize_t n = ::pread(fd, block, sizeof block, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(block, size_t(n));
    offset += n;
    if (text.size() > (1u << 20)) break;  // not ours: a lock file is a few lines
  }
  return text;
}

// A folder that cannot be made for a reason the user can fix (a path through a file, no
// permission, a read-only file system) is bad input; anything else the file system's failure.
[[noreturn]] void creation_failed(const std::string& what, int error) { throw_file_error(what, error); }

bool running_here(const Holder& h) {
  if (h.pid <= 0 || h.host != this_host()) return false;
  return ::kill(pid_t(h.pid), 0) == 0 || errno == EPERM;
}

}  // namespace

namespace {
// A hidden temporary a killed or faulted write left behind (".<name>.tmp<pid>[.<ext>]").
bool is_temporary_name(const std::string& name) {
  static const std::regex pattern(R"(^\..+\.tmp[0-9]+(\.[A-Za-z0-9]+)?$)");
  return std::regex_match(name, pattern);
}

bool holds_no_results(const fs::path& dir, bool top) {
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (top && name == kLockFile) continue;
    if (entry.is_directory(error) && !entry.is_symlink(error) && holds_no_results(entry.path(), false)) continue;
    if (entry.is_regular_file(error) && is_temporary_name(name)) continue;
    return false;
  }
  return true;
}
}  // namespace

bool folder_is_empty_but_lock(const std::string& dir) { return holds_no_results(dir, true); }

RunFolderLock::RunFolderLock(const std::string& out_dir, const std::string& command, std::ostream& log)
    : dir_(out_dir) {
  const fs::path dir(out_dir);
  std::error_code error;
  if (fs::is_symlink(fs::symlink_status(dir, error)) && !fs::exists(dir, error))
    throw UserError("--out: '" + out_dir + "' is a symbolic link to '" + fs::read_symlink(dir, error).string() +
                    "', which does not exist; create the folder it points to, or choose another");
  if (fs::exists(dir, error) && !fs::is_directory(dir, error))
    throw UserError("--out: '" + out_dir + "' exists and is not a folder");
  if (!fs::exists(dir, error)) {
    if (dir.has_parent_path() && !dir.parent_path().empty()) {
      fs::create_directories(dir.parent_path(), error);
      if (error) creation_failed("--out: cannot create the folder '" + dir.parent_path().string() + "'", error.value());
    }
    if (::mkdir(out_dir.c_str(), 0777) == 0)
      created_dir_ = true;
    else if (errno != EEXIST)
      creation_failed("--out: cannot create the folder '" + out_dir + "'", errno);
  }
  path_ = (dir / kLockFile).string();

  auto give_up = [&] {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (created_dir_) ::rmdir(out_dir.c_str());
  };
  std::string previous;
  for (int attempt = 0;; ++attempt) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) {
      const int e = errno;
      give_up();
      creation_failed("--out: cannot create the lock file '" + path_ + "'", e);
    }
    bool locked = ::flock(fd_, LOCK_EX | LOCK_NB) == 0;
    if (!locked) {
      const int e = errno;
      Holder holder = parse_holder(read_all(fd_));
      // The holder writes who it is just after it takes the lock: a refusal in between would
      // name nobody. Give it a moment (at most about a second) to say so.
      for (int waited = 0; e == EWOULDBLOCK && holder.pid <= 0 && waited < 100; ++waited) {
        ::usleep(10000);
        holder = parse_holder(read_all(fd_));
      }
      const bool no_flock = e == ENOLCK || e == EOPNOTSUPP || e == ENOSYS || e == EINVAL;
      if (e != EWOULDBLOCK && !no_flock) {
        give_up();
        throw_io_error("--out: cannot lock '" + path_ + "'", e);
      }
      if (holder.pid == long(::getppid()) && holder.host == this_host()) {  // a --step child
        ::close(fd_);
        fd_ = -1;
        under_parent_ = true;
        return;
      }
      if (e == EWOULDBLOCK || running_here(holder)) {
        give_up();
        throw FolderInUse("--out '" + out_dir + "' is in use by " + describe(holder) +
                          "; wait for it to end, or choose another folder");
      }
      // No flock on this file system and no holder running here: take it over.
    }
    // The file may have been removed by its last holder (which unlinks it on release)
    // between our open and our lock: then this lock guards nothing, and we try again.
    struct stat held {}, named {};
    if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev)
      break;
    ::close(fd_);
    fd_ = -1;
    if (attempt >= 100) throw_io_error("--out: cannot lock '" + path_ + "' (it keeps being replaced)", EAGAIN);
  }
  previous = read_all(fd_);
  const Holder stale = parse_holder(previous);
  if (stale.pid > 0 && stale.pid != long(::getpid()))
    log << "ldmbench: --out '" << out_dir << "': taking over the lock of " << describe(stale)
        << ", which ended without releasing it\n";
  std::string one_line = printable_text(command);
  for (char& c : one_line)
    if (c == '\n' || c == '\t') c = ' ';
  const std::string text = "pid " + std::to_string(::getpid()) + "\nhost " + this_host() + "\nstarted " +
                           now_text() + "\ncommand " + one_line + "\n";
  ssize_t written = -1;
  if (::ftruncate(fd_, 0) == 0) written = ::pwrite(fd_, text.data(), text.size(), 0);
  if (written != ssize_t(text.size())) {
    const int e = written < 0 ? errno : ENOSPC;
    ::unlink(path_.c_str());
    give_up();
    throw_io_error("--out: cannot write the lock file '" + path_ + "'", e);
  }
}

RunFolderLock::~RunFolderLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still locked: the next holder makes a new file
  if (created_dir_) ::rmdir(dir_.c_str());  // only when nothing else was written into it
  ::close(fd_);
}

}  // namespace ldm
