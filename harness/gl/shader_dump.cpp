#include "harness/gl/shader_dump.h"

#include <cstdlib>
#include <filesystem>
#include <mutex>

#include <nlohmann/json.hpp>

#include "harness/util/error.h"
#include "harness/util/files.h"
#include "harness/util/hash.h"

namespace ldm {

const char* shader_stage_name(GLenum type) {
  switch (type) {
    case GL_VERTEX_SHADER: return "vert";
    case GL_FRAGMENT_SHADER: return "frag";
    case GL_COMPUTE_SHADER: return "comp";
    case GL_GEOMETRY_SHADER: return "geom";
    case GL_TESS_CONTROL_SHADER: return "tesc";
    case GL_TESS_EVALUATION_SHADER: return "tese";
  }
  throw GpuError("unknown shader stage 0x" + hex64(type));
}

namespace {

const char* dump_folder() {
  const char* folder = std::getenv(kShaderDumpEnv);
  return folder && *folder ? folder : nullptr;
}

// One writer per process at a time: the temporary's name is per process, not per thread.
std::mutex& dump_writing() {
  static std::mutex writing;
  return writing;
}

}  // namespace

std::string dump_shader_source(GLenum type, const std::string& file,
                               const std::vector<std::string>& preludes, const std::string& source,
                               const std::vector<std::string>& source_strings) {
  const char* folder = dump_folder();
  if (!folder) return "";
  Fnv1a hash;
  hash.add_bytes(source.data(), source.size());
  const std::string name = hex64(hash.value()) + "." + shader_stage_name(type);
  const std::filesystem::path path = std::filesystem::path(folder) / name;
  std::lock_guard<std::mutex> lock(dump_writing());
  if (std::filesystem::exists(path)) return name;  // the same text, already written
  const nlohmann::json sidecar = {
      {"stage", shader_stage_name(type)}, {"file", file}, {"preludes", preludes},
      {"source_strings", source_strings}};
  write_text_atomically(path.string() + ".json", sidecar.dump(1) + "\n");
  write_text_atomically(path.string(), source);
  return name;
}

void dump_shader_program(const std::vector<std::string>& stage_files) {
  const char* folder = dump_folder();
  if (!folder || stage_files.empty()) return;
  Fnv1a hash;
  for (const std::string& stage : stage_files) hash.add_string(stage);
  const std::filesystem::path path =
      std::filesystem::path(folder) / (hex64(hash.value()) + ".program.json");
  std::lock_guard<std::mutex> lock(dump_writing());
  if (std::filesystem::exists(path)) return;
  write_text_atomically(path.string(), nlohmann::json({{"stages", stage_files}}).dump(1) + "\n");
}

}  // namespace ldm
