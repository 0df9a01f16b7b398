#pragma once
// The `ldmbench run` command line of a sweep's settings: what `ldmbench view`'s "Save as run"
// writes, so that the configuration on screen is measured (records, images) by
// `ldmbench run` exactly as shown. Every setting that changes a record is written
// explicitly, so the line means the same whatever the defaults become; read back by
// `ldmbench run` it gives the same configurations (config_id) and measurement requests.
#include <string>

#include "harness/settings/run_settings.h"

namespace ldm {

// "ldmbench run --scene ... --out OUT" (no --out when `out_dir` is empty); values are
// shell-quoted where needed. `program` is how ldmbench is called (e.g. build/ldmbench).
std::string run_command_line(const RunSettings& settings, const std::string& program,
                             const std::string& out_dir = "");

// The same settings as a sweep file (docs/guide/sweeps.md): every axis with its values and
// the reference, image and timer settings, so that `ldmbench sweep FILE` plans the same
// configurations (config_id) with the same settings as the command line. The cache folder
// and EGL options are not part of a sweep file (the sweep's own command line gives them).
std::string sweep_file_json(const RunSettings& settings, const std::string& description = "");

// A value as a POSIX shell word: unchanged when it is safe, else in single quotes.
std::string shell_quoted(const std::string& word);

}  // namespace ldm
