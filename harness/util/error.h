#pragma once
#include <stdexcept>
#include <string>

namespace ldm {

// An error the user can act on: bad input, an unsupported device, a configuration that
// cannot run. The message names the file, line or parameter at fault.
class UserError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A failure of the GPU or of a measurement invariant (shader compile error, overflow that
// should have been impossible). Always a bug or a device defect, never the user's input.
class GpuError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ldm
