#include "harness/gl/shader_program.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "harness/gl/embedded_shaders.h"
#include "harness/gl/shader_dump.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

// LDM_SHADER_DIR: a folder laid out as shaders/ whose files replace the compiled-in ones
// (files it lacks stay compiled-in): to try a shader change without rebuilding, and for the
// tests that change a shader on purpose (a deliberate slowdown the work guard must catch).
std::string shader_override(const std::string& file) {
  const char* folder = std::getenv("LDM_SHADER_DIR");
  if (!folder || !*folder) return {};
  const std::filesystem::path path = std::filesystem::path(folder) / file;
  if (!std::filesystem::is_regular_file(path)) return {};
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw UserError("LDM_SHADER_DIR: cannot read " + path.string());
  return text.str();
}

const std::string& shader_text(const std::string& file) {
  static std::map<std::string, std::string> cache;
  auto cached = cache.find(file);
  if (cached != cache.end()) return cached->second;
  if (std::string replaced = shader_override(file); !replaced.empty())
    return cache.emplace(file, std::move(replaced)).first->second;
  const auto& table = embedded_shader_sources();
  auto found = table.find(file);
  if (found == table.end()) throw GpuError("shader file not found in shaders/: " + file);
  return cache.emplace(file, std::string(found->second)).first->second;
}

int file_index(const std::string& file, std::vector<std::string>& table) {
  for (size_t i = 0; i < table.size(); ++i)
    if (table[i] == file) return int(i);
  table.push_back(file);
  return int(table.size() - 1);
}

void expand(const std::string& file, std::vector<std::string>& table,
            std::set<std::string>& included, std::ostringstream& out) {
  if (!included.insert(file).second) return;  // include once
  const int id = file_index(file, table);
  static const std::regex include_line(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
  std::istringstream in(shader_text(file));
  std::string line;
  int line_number = 0;
  out << "#line 1 " << id << "\n";
  while (std::getline(in, line)) {
    ++line_number;
    std::smatch match;
    if (std::regex_match(line, match, include_line)) {
      expand(match[1].str(), table, included, out);
      out << "#line " << line_number + 1 << " " << id << "\n";
    } else {
      out << line << "\n";
    }
  }
}

// Rewrites "0:12(3): error" / "0(12) : error" prefixes into "file.glsl:12: error".
std::string annotate_log(const std::string& log, const std::vector<std::string>& table) {
  static const std::regex mesa(R"((\d+):(\d+)\((\d+)\))");
  static const std::regex nvidia(R"((\d+)\((\d+)\))");
  std::string out;
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, mesa) && m.position(0) == 0) {
      size_t id = std::stoul(m[1].str());
      std::string name = id < table.size() ? table[id] : "string " + m[1].str();
      line = name + ":" + m[2].str() + m.suffix().str();
    } else if (std::regex_search(line, m, nvidia) && m.position(0) == 0) {
      size_t id = std::stoul(m[1].str());
      std::string name = id < table.size() ? table[id] : "string " + m[1].str();
      line = name + ":" + m[2].str() + m.suffix().str();
    }
    out += line + "\n";
  }
  return out;
}

const ShaderDefines*& program_wide_defines() {
  static const ShaderDefines* defines = nullptr;
  return defines;
}

}  // namespace

void set_program_wide_defines(const ShaderDefines* defines) { program_wide_defines() = defines; }

std::string ShaderDefines::text() const {
  std::string out;
  for (const auto& [name, value] : values) out += "#define " + name + " " + value + "\n";
  return out;
}

std::string preprocess_shader(const std::string& file, const ShaderDefines& defines,
                              const std::vector<std::string>& prelude_files,
                              std::vector<std::string>* file_table) {
  std::vector<std::string> table = {"<defines>"};
  std::set<std::string> included;
  std::ostringstream out;
  out << "#version 450 core\n";
  out << defines.text();
  if (const ShaderDefines* wide = program_wide_defines()) out << wide->text();
  for (const auto& prelude : prelude_files) expand(prelude, table, included, out);
  expand(file, table, included, out);
  if (file_table) *file_table = table;
  return out.str();
}

namespace {

// The info log of a shader or program: `get_iv` and `get_log` are glGetShaderiv and
// glGetShaderInfoLog, or glGetProgramiv and glGetProgramInfoLog.
template <typename GetIv, typename GetLog>
std::string info_log(GLuint object, GetIv get_iv, GetLog get_log) {
  GLint length = 0;
  get_iv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  get_log(object, length, nullptr, log.data());
  return log;
}

}  // namespace

GlProgram build_program(const std::vector<ShaderStage>& stages, const ShaderDefines& defines) {
  GLuint program = glCreateProgram();
  GlProgram owner(program);
  std::vector<GLuint> shaders;
  std::string names;
  std::vector<std::string> dumped;  // LDM_SHADER_DUMP's file names, else empty
  for (const auto& stage : stages) {
    std::vector<std::string> table;
    const std::string source = preprocess_shader(stage.file, defines, stage.prelude_files, &table);
    const std::string dumped_as = dump_shader_source(stage.type, stage.file, stage.prelude_files,
                                                       source, table);
    if (!dumped_as.empty()) dumped.push_back(dumped_as);
    GLuint shader = glCreateShader(stage.type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      const std::string log = info_log(shader, glGetShaderiv, glGetShaderInfoLog);
      glDeleteShader(shader);
      for (GLuint s : shaders) glDeleteShader(s);
      throw GpuError("compiling " + stage.file + " failed:\n" + annotate_log(log, table));
    }
    glAttachShader(program, shader);
    shaders.push_back(shader);
    names += (names.empty() ? "" : " + ") + stage.file;
  }
  dump_shader_program(dumped);
  glLinkProgram(program);
  for (GLuint s : shaders) {
    glDetachShader(program, s);
    glDeleteShader(s);
  }
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(program, glGetProgramiv, glGetProgramInfoLog);
    throw GpuError("linking " + names + " failed:\n" + log);
  }
  return owner;
}

}  // namespace ldm
