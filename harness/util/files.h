#pragma once
#include <functional>
#include <string>

namespace ldm {

// Calls write(temporary_path), then renames the temporary onto `path`; on any exception the
// temporary is removed and `path` is left as it was. No reader ever sees a half-written file.
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temporary)>& write);
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace ldm
