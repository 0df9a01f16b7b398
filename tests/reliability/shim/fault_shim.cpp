// LD_PRELOAD fault injector for the write path (tests/reliability/fault_injection_test.cpp), preloaded into ldmbench.
// Every call that writes under LDM_FAULT_DIR counts as one injection point: open / openat /
// creat / fopen for writing, write / pwrite / writev / fwrite, fflush / fclose of such a
// stream, fsync / fdatasync, ftruncate, rename / renameat, mkdir, link. The LDM_FAULT_AT-th
// such call (1-based; 0: none) fails with errno LDM_FAULT_ERRNO (default ENOSPC), and with
// LDM_FAULT_STICKY=1 every later one too (a disk that stays full). With LDM_FAULT_LOG, each
// counted call is appended to that file ("k call path"), so that a fault-free run says how
// many injection points there are. Calls made inside libc (a stream flushing its buffer)
// cannot be seen; fwrite, fflush and fclose stand for them.
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

#include <atomic>

extern "C" {

#define MAX_FD 65536
#define MAX_STREAMS 256

static std::atomic<unsigned char> tracked_fd[MAX_FD];
static std::atomic<FILE*> tracked_stream[MAX_STREAMS];
static std::atomic<long> calls;
static int log_fd = -2;
static char dir[PATH_MAX];
static size_t dir_len;
static long fault_at;
static int fault_errno = ENOSPC, sticky;

#define REAL(name) \
  static decltype(&name) real_##name = nullptr; \
  if (!real_##name) real_##name = reinterpret_cast<decltype(&name)>(dlsym(RTLD_NEXT, #name))

static void init(void) {
  static std::atomic<int> done;
  if (done.load()) return;
  const char* d = getenv("LDM_FAULT_DIR");
  if (d && *d) {
    strncpy(dir, d, sizeof dir - 1);
    dir_len = strlen(dir);
    while (dir_len > 1 && dir[dir_len - 1] == '/') dir[--dir_len] = 0;
  }
  const char* at = getenv("LDM_FAULT_AT");
  fault_at = at ? atol(at) : 0;
  const char* e = getenv("LDM_FAULT_ERRNO");
  if (e && *e) fault_errno = atoi(e);
  const char* s = getenv("LDM_FAULT_STICKY");
  sticky = s && *s == '1';
  done.store(1);
}

static int under_dir(const char* path, int dirfd) {
  init();
  if (!dir_len || !path) return 0;
  char absolute[PATH_MAX * 2];
  if (path[0] == '/') {
    snprintf(absolute, sizeof absolute, "%s", path);
  } else {
    char base[PATH_MAX];
    if (dirfd != AT_FDCWD && dirfd >= 0) {
      char link[64];
      snprintf(link, sizeof link, "/proc/self/fd/%d", dirfd);
      const ssize_t n = readlink(link, base, sizeof base - 1);
      if (n <= 0) return 0;
      base[n] = 0;
    } else if (!getcwd(base, sizeof base)) {
      return 0;
    }
    snprintf(absolute, sizeof absolute, "%s/%s", base, path);
  }
  return strncmp(absolute, dir, dir_len) == 0 && (absolute[dir_len] == '/' || absolute[dir_len] == 0);
}

static void log_call(long k, const char* call, const char* what) {
  if (log_fd == -2) {
    const char* path = getenv("LDM_FAULT_LOG");
    REAL(open);
    log_fd = path && *path ? real_open(path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644) : -1;
  }
  if (log_fd < 0) return;
  char line[PATH_MAX + 128];
  const int n = snprintf(line, sizeof line, "%ld %s %s\n", k, call, what ? what : "");
  REAL(write);
  if (n > 0) (void)real_write(log_fd, line, (size_t)n);
}

// One injection point: returns 1 when this call is to fail (errno set).
static int fault(const char* call, const char* what) {
  const long k = calls.fetch_add(1) + 1;
  log_call(k, call, what);
  if (fault_at > 0 && (k == fault_at || (sticky && k > fault_at))) {
    errno = fault_errno;
    return 1;
  }
  return 0;
}

static const char* fd_name(int fd, char* buffer, size_t size) {
  char link[64];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, buffer, size - 1);
  buffer[n > 0 ? n : 0] = 0;
  return buffer;
}

static int is_tracked(int fd) { return fd >= 0 && fd < MAX_FD && tracked_fd[fd].load(); }
// Whether `call` on a tracked descriptor is failed (counted and logged as fault() does).
static int fd_fault(int fd, const char* call) {
  char name[PATH_MAX];
  return is_tracked(fd) && fault(call, fd_name(fd, name, sizeof name));
}
static void track(int fd, int on) {
  if (fd >= 0 && fd < MAX_FD) tracked_fd[fd].store(static_cast<unsigned char>(on));
}
static int writing(int flags) { return (flags & (O_WRONLY | O_RDWR | O_CREAT | O_TRUNC | O_APPEND)) != 0; }

static int stream_slot(FILE* f) {
  for (int i = 0; i < MAX_STREAMS; ++i)
    if (tracked_stream[i].load() == f) return i;
  return -1;
}
static void track_stream(FILE* f) {
  for (int i = 0; i < MAX_STREAMS; ++i) {
    FILE* expected = nullptr;
    if (tracked_stream[i].compare_exchange_strong(expected, f)) return;
  }
}

static int open_common(int dirfd, const char* path, int flags, mode_t mode, int at) {
  const int inside = under_dir(path, at ? dirfd : AT_FDCWD);
  if (inside && writing(flags) && fault("open", path)) return -1;
  int fd;
  if (at) {
    REAL(openat);
    fd = real_openat(dirfd, path, flags, mode);
  } else {
    REAL(open);
    fd = real_open(path, flags, mode);
  }
  if (fd >= 0) track(fd, inside);
  return fd;
}

// The mode argument, which the open calls take only when they create a file.
static mode_t creation_mode(int flags, va_list args) {
  if ((flags & O_CREAT) == 0 && (flags & O_TMPFILE) != O_TMPFILE) return 0;
  return static_cast<mode_t>(va_arg(args, int));
}
int open(const char* path, int flags, ...) {
  va_list args;
  va_start(args, flags);
  const mode_t mode = creation_mode(flags, args);
  va_end(args);
  return open_common(AT_FDCWD, path, flags, mode, 0);
}
int openat(int dirfd, const char* path, int flags, ...) {
  va_list args;
  va_start(args, flags);
  const mode_t mode = creation_mode(flags, args);
  va_end(args);
  return open_common(dirfd, path, flags, mode, 1);
}
// The 64-bit names do what the plain ones do (both open through the real open and openat,
// the same calls on a 64-bit ABI): the same functions under a second symbol.
int open64(const char* path, int flags, ...) __attribute__((alias("open")));
int openat64(int dirfd, const char* path, int flags, ...) __attribute__((alias("openat")));
int creat(const char* path, mode_t mode) { return open_common(AT_FDCWD, path, O_CREAT | O_WRONLY | O_TRUNC, mode, 0); }
int creat64(const char* path, mode_t mode) { return open_common(AT_FDCWD, path, O_CREAT | O_WRONLY | O_TRUNC, mode, 0); }

int close(int fd) {
  REAL(close);
  track(fd, 0);
  return real_close(fd);
}

static FILE* fopen_common(const char* path, const char* mode, int is64) {
  const int inside = under_dir(path, AT_FDCWD);
  const int writes = mode && (strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+'));
  if (inside && writes && fault("fopen", path)) return NULL;
  FILE* f;
  if (is64) {
    REAL(fopen64);
    f = real_fopen64(path, mode);
  } else {
    REAL(fopen);
    f = real_fopen(path, mode);
  }
  if (f && inside && writes) {  // a stream read from is no injection point
    track_stream(f);
    track(fileno(f), 1);  // its writes reach write(2) through the library (libstdc++ streams)
  }
  return f;
}
FILE* fopen(const char* path, const char* mode) { return fopen_common(path, mode, 0); }
FILE* fopen64(const char* path, const char* mode) { return fopen_common(path, mode, 1); }

size_t fwrite(const void* data, size_t size, size_t n, FILE* f) {
  REAL(fwrite);
  if (stream_slot(f) >= 0 && fault("fwrite", "")) return 0;
  return real_fwrite(data, size, n, f);
}
int fflush(FILE* f) {
  REAL(fflush);
  if (f && stream_slot(f) >= 0 && fault("fflush", "")) return EOF;
  return real_fflush(f);
}
int fclose(FILE* f) {
  REAL(fclose);
  const int slot = stream_slot(f);
  if (slot >= 0) {
    tracked_stream[slot].store(nullptr);
    track(fileno(f), 0);
    if (fault("fclose", "")) {
      const int e = errno;
      real_fclose(f);
      errno = e;
      return EOF;
    }
  }
  return real_fclose(f);
}

ssize_t write(int fd, const void* data, size_t n) {
  REAL(write);
  if (fd_fault(fd, "write")) return -1;
  return real_write(fd, data, n);
}
ssize_t pwrite(int fd, const void* data, size_t n, off_t offset) {
  REAL(pwrite);
  if (fd_fault(fd, "pwrite")) return -1;
  return real_pwrite(fd, data, n, offset);
}
ssize_t pwrite64(int fd, const void* data, size_t n, off64_t offset) {
  REAL(pwrite64);
  if (fd_fault(fd, "pwrite")) return -1;
  return real_pwrite64(fd, data, n, offset);
}
ssize_t writev(int fd, const struct iovec* iov, int count) {
  REAL(writev);
  if (fd_fault(fd, "writev")) return -1;
  return real_writev(fd, iov, count);
}
int fsync(int fd) {
  REAL(fsync);
  if (fd_fault(fd, "fsync")) return -1;
  return real_fsync(fd);
}
int fdatasync(int fd) {
  REAL(fdatasync);
  if (fd_fault(fd, "fdatasync")) return -1;
  return real_fdatasync(fd);
}
// A disk that stays full still lets a file shrink (that frees space): once the sticky
// fault has begun, an ftruncate that cuts a file is counted but not failed with ENOSPC. The
// k-th call itself still fails, so a cut that fails once is injected too.
static int shrink_passes(int fd, off64_t size) {
  struct stat st;
  if (!(sticky && fault_errno == ENOSPC && fault_at > 0 && calls.load() >= fault_at)) return 0;
  return fstat(fd, &st) == 0 && size <= st.st_size;
}
// Whether an ftruncate of a tracked descriptor is failed.
static int truncate_fault(int fd, off64_t size) {
  if (!is_tracked(fd)) return 0;
  const int passes = shrink_passes(fd, size);
  char name[PATH_MAX];
  return fault("ftruncate", fd_name(fd, name, sizeof name)) && !passes;
}
int ftruncate(int fd, off_t size) {
  REAL(ftruncate);
  if (truncate_fault(fd, size)) return -1;
  return real_ftruncate(fd, size);
}
int ftruncate64(int fd, off64_t size) {
  REAL(ftruncate64);
  if (truncate_fault(fd, size)) return -1;
  return real_ftruncate64(fd, size);
}
int rename(const char* from, const char* to) {
  REAL(rename);
  if ((under_dir(from, AT_FDCWD) || under_dir(to, AT_FDCWD)) && fault("rename", to)) return -1;
  return real_rename(from, to);
}
int renameat(int fromfd, const char* from, int tofd, const char* to) {
  REAL(renameat);
  if ((under_dir(from, fromfd) || under_dir(to, tofd)) && fault("renameat", to)) return -1;
  return real_renameat(fromfd, from, tofd, to);
}
int mkdir(const char* path, mode_t mode) {
  REAL(mkdir);
  if (under_dir(path, AT_FDCWD) && fault("mkdir", path)) return -1;
  return real_mkdir(path, mode);
}
int mkdirat(int dirfd, const char* path, mode_t mode) {
  REAL(mkdirat);
  if (under_dir(path, dirfd) && fault("mkdirat", path)) return -1;
  return real_mkdirat(dirfd, path, mode);
}
int link(const char* from, const char* to) {
  REAL(link);
  if (under_dir(to, AT_FDCWD) && fault("link", to)) return -1;
  return real_link(from, to);
}
int linkat(int fromfd, const char* from, int tofd, const char* to, int flags) {
  REAL(linkat);
  if (under_dir(to, tofd) && fault("linkat", to)) return -1;
  return real_linkat(fromfd, from, tofd, to, flags);
}

}  // extern "C"
