#include "harness/util/files.h"

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "harness/util/error.h"

namespace ldm {

void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temporary)>& write) {
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  // Keep the extension last so that format-sniffing writers (OpenImageIO) still work.
  const std::string temporary = (target.parent_path() / ("." + target.stem().string() + ".tmp" +
                                                         std::to_string(::getpid()) +
                                                         target.extension().string())).string();
  try {
    write(temporary);
    std::filesystem::rename(temporary, target);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw UserError("cannot write '" + path + "'");
  });
}

}  // namespace ldm
