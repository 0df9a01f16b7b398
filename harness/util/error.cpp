#include "harness/util/error.h"

#include <cstdio>
#include <cstring>

namespace ldm {

std::string printable_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out;
}

IoError::IoError(const std::string& what, int error_number)
    : std::runtime_error(printable_text(what)), error_number_(error_number) {}

std::string errno_text(int error_number) {
  if (error_number == 0) return "unknown error";
  std::string text = std::strerror(error_number);
  if (const char* name = strerrorname_np(error_number)) text += std::string(" (") + name + ")";
  return text;
}

void throw_io_error(const std::string& what, int error_number) {
  throw IoError(what + ": " + errno_text(error_number), error_number);
}

}  // namespace ldm
