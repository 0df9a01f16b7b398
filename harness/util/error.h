#pragma once
#include <stdexcept>
#include <string>
#include <string_view>

namespace ldm {

// `text` with NUL and the other control characters (but newline and tab) written as \xNN,
// so that a message quoting a file's bytes is printed whole (a NUL ended it).
std::string printable_text(std::string_view text);

// An error the user can act on: bad input, an unsupported device, a configuration that
// cannot run. The message names the file, line or parameter at fault. Exit status 2.
class UserError : public std::runtime_error {
 public:
  explicit UserError(const std::string& what) : std::runtime_error(printable_text(what)) {}
};

// Reading or writing a file failed in the file system (a full disk, a read-only or vanished
// folder, an I/O error): not the input's fault and not a bug. The message names the path,
// the operation and the error number ("No space left on device (ENOSPC)"). Exit status 4
// (docs/guide/reliability.md).
class IoError : public std::runtime_error {
 public:
  IoError(const std::string& what, int error_number);
  int error_number() const { return error_number_; }

 private:
  int error_number_;
};

// "No space left on device (ENOSPC)" for an errno value ("unknown error" for 0).
std::string errno_text(int error_number);
// Throws IoError "<what>: <errno_text(error_number)>".
[[noreturn]] void throw_io_error(const std::string& what, int error_number);

// A failure of the GPU or of a measurement invariant (shader compile error, overflow that
// should have been impossible). Always a bug or a device defect, never the user's input.
class GpuError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ldm
