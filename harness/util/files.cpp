#include "harness/util/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>

#include "harness/util/error.h"
#include "harness/util/hash.h"

namespace ldm {
namespace {

// Closes `fd` once; a failing close (NFS reports write errors there) is an IoError.
void close_checked(int fd, const std::string& path) {
  if (::close(fd) != 0 && errno != EINTR) throw_io_error("cannot write '" + path + "' (close)", errno);
}

}  // namespace

void throw_file_error(const std::string& what, int error) {
  if (error == EACCES || error == EPERM || error == EROFS || error == ENOTDIR || error == EEXIST ||
      error == EISDIR || error == ENAMETOOLONG || error == ELOOP)
    throw UserError(what + ": " + errno_text(error));
  throw_io_error(what, error);
}

void fsync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw_io_error("cannot open '" + path + "' to flush it to disk", errno);
  if (::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    throw_io_error("cannot flush '" + path + "' to disk (fsync)", error);
  }
  close_checked(fd, path);
}

void fsync_folder(const std::string& path) {
  const int fd = ::open(path.empty() ? "." : path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw_io_error("cannot open folder '" + path + "' to flush it to disk", errno);
  // Some file systems cannot fsync a folder (EINVAL): the rename is then as durable as they make it.
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
    const int error = errno;
    ::close(fd);
    throw_io_error("cannot flush folder '" + path + "' to disk (fsync)", error);
  }
  ::close(fd);
}

void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temporary)>& write) {
  const std::filesystem::path target(path);
  if (target.has_parent_path()) {
    std::error_code error;
    std::filesystem::create_directories(target.parent_path(), error);
    // A file where the folder should be is the folder's fault, not the file system's.
    if (error == std::errc::file_exists || error == std::errc::not_a_directory)
      throw UserError("cannot create the folder '" + target.parent_path().string() + "': " +
                      errno_text(error.value()) + " (a file stands in its way)");
    if (error) throw_io_error("cannot create the folder '" + target.parent_path().string() + "'", error.value());
  }
  // Keep the extension last so that writers that tell the format by it still work.
  const std::string temporary = (target.parent_path() / ("." + target.stem().string() + ".tmp" +
                                                         std::to_string(::getpid()) +
                                                         target.extension().string())).string();
  try {
    write(temporary);
    fsync_file(temporary);
    if (::rename(temporary.c_str(), path.c_str()) != 0)
      throw_io_error("cannot rename '" + temporary + "' to '" + path + "'", errno);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  fsync_folder(target.parent_path().string());
}

void write_bytes_atomically(const std::string& path, const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  write_file_atomically(path, [&](const std::string& temporary) {
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw_file_error("cannot create '" + temporary + "' (to write '" + path + "')", errno);
    size_t written = 0;
    while (written < size) {
      const ssize_t n = ::write(fd, bytes + written, size - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const int error = n < 0 ? errno : ENOSPC;
        ::close(fd);
        throw_io_error("cannot write '" + path + "'", error);
      }
      written += size_t(n);
    }
    close_checked(fd, path);
  });
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_bytes_atomically(path, text.data(), text.size());
}

std::string ldmbench_cache_dir(const std::string& what) {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && xdg[0] == '/') return (std::filesystem::path(xdg) / "ldmbench" / what).string();
  const char* home = std::getenv("HOME");
  if (home && home[0] != '\0') return (std::filesystem::path(home) / ".cache" / "ldmbench" / what).string();
  return "";
}

uint64_t hash_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw_io_error("cannot open '" + path + "'", errno);
  Fnv1a h;
  char block[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, block, sizeof block);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      throw_io_error("cannot read '" + path + "'", error);
    }
    if (n == 0) break;
    h.add_bytes(block, size_t(n));
  }
  ::close(fd);
  return h.value();
}

}  // namespace ldm
