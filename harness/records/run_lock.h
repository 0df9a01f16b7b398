#pragma once
// One writer per run folder. `ldmbench run`, `sweep` and `merge` hold an exclusive lock on
// their --out folder (OUT) for as long as they write it, before they read what it holds:
// two commands started into one folder used to both measure, journal each other's
// configurations twice and leave tables that disagreed with the journal (issue 19).
//
// The lock is flock(2) on OUT/.ldmbench.lock, a file that names its holder (PID, host, start
// time, command line). The kernel releases a flock when its holder ends, however it ends:
// a lock file left by a SIGKILLed process holds no lock and is taken over by the next
// command, which says whose it was. Where the file system has no flock (ENOLCK), the PID in
// the file decides: a holder on this host that is still running keeps the folder.
//
// A child of `--isolation process` (`ldmbench run ... --step ID`) works under its parent's
// lock: the lock file names the parent's PID.
#include <iosfwd>
#include <string>

#include "harness/util/error.h"

namespace ldm {

inline constexpr const char* kLockFile = ".ldmbench.lock";

// Another process holds the folder (exit status kExitBusy, app/exit_codes.h). The message
// names the folder and the holder: "--out 'OUT' is in use by PID 1234 on host h since
// 2024-05-01T10:00:00+0200: ldmbench sweep ...; wait for it to end, or choose another folder".
class FolderInUse : public UserError {
 public:
  using UserError::UserError;
};

class RunFolderLock {
 public:
  // Creates OUT (and its parents) when missing, then takes the lock; `command` is stored for
  // the messages of others. Throws FolderInUse, UserError (OUT is a file, a dangling
  // symbolic link, or cannot be created for lack of permission) or IoError. A stale lock
  // taken over is reported on `log`.
  RunFolderLock(const std::string& out_dir, const std::string& command, std::ostream& log);
  // Removes the lock file; and OUT itself when this lock created it and it holds nothing else.
  ~RunFolderLock();
  RunFolderLock(const RunFolderLock&) = delete;
  RunFolderLock& operator=(const RunFolderLock&) = delete;

  // Whether this process works under its parent's lock (a --step child).
  bool under_parent() const { return under_parent_; }

 private:
  std::string dir_, path_;
  int fd_ = -1;
  bool created_dir_ = false, under_parent_ = false;
};

// Whether `dir` holds no result: nothing but (perhaps) its lock file, empty subfolders
// (images/, samples/) and hidden temporaries a faulted write left. A run that stopped
// before its journal was created (a full disk) leaves such a folder; the same command
// then starts it afresh.
bool folder_is_empty_but_lock(const std::string& dir);

}  // namespace ldm
