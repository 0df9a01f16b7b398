#pragma once
// JSON that a user wrote (scene files, sweep files) or that a run folder holds (journal
// lines, records.json), parsed strictly by nlohmann-json's SAX parser, so that every
// failure is a UserError naming the file, line and column:
//   - a syntax error, or a number beyond double (1e400);
//   - nesting deeper than `max_depth` arrays and objects, refused while parsing: nothing
//     that deep is ever built, so no recursive copy or destructor can overflow the stack
//     (a sweep file nested 200,000 arrays deep crashed ldmbench);
//   - a key given twice in one object, named with both lines (nlohmann-json keeps the last
//     one silently).
// And input files whose size is refused before they are read (read_input_file).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace ldm {

// No scene or sweep file, journal line or records file nests deeper than a few levels.
inline constexpr size_t kMaxJsonDepth = 64;

struct JsonLimits {
  size_t max_depth = kMaxJsonDepth;
};

// Throws UserError "<name>: malformed JSON at line L, column C: <what>" (syntax, numbers),
// "<name>: line L, column C: nesting deeper than ... " or
// "<name>: line L: key \"k\" at /path appears twice in one object (first at line M)".
// `name` is the file (or "file:line" for one line of a file: lines are then counted from 1
// within `text`, and the message says "<name>, column C").
nlohmann::json parse_json_strictly(std::string_view text, const std::string& name,
                                   const JsonLimits& limits = {});
nlohmann::ordered_json parse_ordered_json_strictly(std::string_view text, const std::string& name,
                                                   const JsonLimits& limits = {});

// The largest input file (a scene or sweep file, a mesh) ldmbench reads, in bytes: 512 MiB,
// or LDMBENCH_MAX_INPUT_MIB from the environment. A 1 GB OBJ took 3 GB of memory and 17 s
// before it was refused (or ended in bad_alloc under an address-space cap).
uint64_t max_input_bytes();
inline constexpr const char* kMaxInputEnv = "LDMBENCH_MAX_INPUT_MIB";
// Throws UserError "<what> '<path>' is <size>, larger than the input limit of <limit>
// (LDMBENCH_MAX_INPUT_MIB)" when the file is too large; IoError when it cannot be examined.
void check_input_size(const std::string& path, const std::string& what);
// The whole file, after check_input_size; throws UserError for a folder or a missing file
// ("<what> '<path>' is a folder, not a file"), IoError when reading fails.
std::string read_input_file(const std::string& path, const std::string& what);

}  // namespace ldm
