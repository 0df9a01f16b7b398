#pragma once
// Builds GL programs from the GLSL files in shaders/ (compiled into the binary).
//
// Sources may `#include "path"` other files (paths relative to shaders/); the C++ side
// prepends `#version 450 core` and a block of `#define`s, then, for structures, the
// structure's query implementation. Compile errors are reported with file names and lines.
// With LDM_SHADER_DUMP set, every stage's final text is also written out for a second
// compiler (harness/gl/shader_dump.h).
#include <string>
#include <utility>
#include <vector>

#include "harness/gl/gl_objects.h"

namespace ldm {

struct ShaderDefines {
  std::vector<std::pair<std::string, std::string>> values;
  ShaderDefines& set(std::string name, std::string value = "1") {
    values.emplace_back(std::move(name), std::move(value));
    return *this;
  }
  ShaderDefines& set(std::string name, long long value) {
    return set(std::move(name), std::to_string(value));
  }
  std::string text() const;
};

// One stage: a file from shaders/ plus code injected before it (after the defines), such as
// a structure's query implementation.
struct ShaderStage {
  GLenum type;
  std::string file;
  std::vector<std::string> prelude_files;  // included in order before `file`
};

// Expands includes; returns the source text and the list of file names, indexed by the
// source-string number used in the `#line` directives.
std::string preprocess_shader(const std::string& file, const ShaderDefines& defines,
                              const std::vector<std::string>& prelude_files,
                              std::vector<std::string>* file_table);

GlProgram build_program(const std::vector<ShaderStage>& stages, const ShaderDefines& defines);

// Defines added after `defines` to every shader preprocessed while set (null: none): the
// counting variants of harness/measure/work_counters.h's WorkCountingScope. Not owned.
void set_program_wide_defines(const ShaderDefines* defines);

}  // namespace ldm
