#pragma once
// Records every shader stage the builder compiles, for checks outside the process
// (scripts/check-shaders.sh compiles them again with glslang, the Khronos reference front end).
//
// With LDM_SHADER_DUMP=DIR in the environment, each stage's final source — exactly the text
// handed to glShaderSource: `#version`, the define block, includes expanded with their `#line`
// directives — is written to DIR/<hash>.<stage>, named by the 64-bit FNV-1a of that text
// (so a program built a thousand times is one file), with DIR/<hash>.<stage>.json beside it:
// {"stage", "file" (the shader's file under shaders/), "preludes" (the files injected before
// it: a structure's query implementation, the fragment shader a compute shader runs),
// "source_strings" (the file each `#line N S` source-string number S stands for)}; and each program as
// DIR/<hash>.program.json: {"stages": [its stages' dumped file names]}, so that the stages
// can be linked together again. Every file is written atomically (a temporary renamed into
// place), a sidecar before its source and a program after its stages, so that processes
// sharing DIR in parallel never see a partial file and nothing names a file not yet there.
// Without the variable nothing is written. A failure to write is an error of the build that
// asked for it: a check that silently missed programs would pass vacuously.
#include <string>
#include <vector>

#include "harness/gl/gl_api.h"

namespace ldm {

inline constexpr const char* kShaderDumpEnv = "LDM_SHADER_DUMP";

// "vert", "frag", "comp", "geom", "tesc", "tese": glslangValidator's stage names (-S) and
// file extensions.
const char* shader_stage_name(GLenum type);

// Writes the stage to $LDM_SHADER_DUMP as described above and returns its file name there
// ("<hash>.<stage>"); does nothing and returns "" when the variable is unset or empty.
// Throws (UserError, IoError) when the folder cannot be written.
std::string dump_shader_source(GLenum type, const std::string& file,
                               const std::vector<std::string>& preludes, const std::string& source,
                               const std::vector<std::string>& source_strings);

// Writes a program of the stages dump_shader_source() returned; nothing when they are "".
void dump_shader_program(const std::vector<std::string>& stage_files);

}  // namespace ldm
