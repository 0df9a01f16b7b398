#pragma once
#include <map>
#include <string>
#include <string_view>

namespace ldm {
// Every file under shaders/, keyed by its path relative to shaders/ (generated at build time).
const std::map<std::string, std::string_view>& embedded_shader_sources();
}  // namespace ldm
