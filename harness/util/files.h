#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace ldm {

// Writes `path` so that no reader (and no crash, kill or full disk) ever leaves a partial
// file under its name: write(temporary) fills ".<stem>.tmp<pid><.ext>" beside it, which is
// then fsync'd, renamed onto `path`, and the folder fsync'd. On any failure the temporary is
// removed, `path` is left as it was, and the error is thrown; a failure of the file system
// (write, fsync, rename: a full disk, a read-only folder) as IoError naming the path and the
// errno. A killed process may leave the temporary, which run folders remove
// (records/run_folder.h).
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temporary)>& write);
void write_text_atomically(const std::string& path, const std::string& text);
// `size` bytes as the whole file, one checked write(2) loop.
void write_bytes_atomically(const std::string& path, const void* data, size_t size);

// fsync of a file's data (IoError naming `path` on failure), and of a folder's entries.
void fsync_file(const std::string& path);
void fsync_folder(const std::string& path);

// Throws for a failed file-system call: UserError "<what>: <errno text>" when the user can fix
// the cause (no permission, a read-only file system, a file where a folder should be, a
// name too long), else IoError (no space, an I/O error).
[[noreturn]] void throw_file_error(const std::string& what, int error_number);

// ldmbench's folder for `what` in the user's cache, as the XDG base directory specification
// puts it: $XDG_CACHE_HOME/ldmbench/<what> (an absolute XDG_CACHE_HOME only), else
// $HOME/.cache/ldmbench/<what>; "" when neither is set.
std::string ldmbench_cache_dir(const std::string& what);

// 64-bit FNV-1a of a file's bytes, read in blocks; throws IoError when it cannot be read.
uint64_t hash_file(const std::string& path);

}  // namespace ldm
