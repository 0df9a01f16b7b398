#include "harness/scene/obj_syntax.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "harness/scene/scene.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

std::vector<std::string_view> split_whitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

std::string plural(const std::string& what) { return what == "vertex" ? "vertices" : what + "s"; }

class LineReader {
 public:
  LineReader(const std::string& path, size_t line) : path_(path), line_(line) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw UserError(path_ + ":" + std::to_string(line_) + ": " + what);
  }

  // A decimal number (no hex, no nan/inf words) that is finite as a 32-bit float.
  float number(std::string_view token) const {
    const std::string text(token);
    const bool decimal = text.find_first_not_of("0123456789+-.eE") == std::string::npos;
    char* end = nullptr;
    const double value = decimal ? std::strtod(text.c_str(), &end) : 0.0;
    if (!decimal || end != text.c_str() + text.size())
      fail("'" + text + "' is not a number");
    const float as_float = float(value);
    if (!std::isfinite(as_float))
      fail("'" + text + "' is not representable as a 32-bit float (|x| <= 3.4e38)");
    return as_float;
  }

  // A 1-based index, or a negative one counting back from the `count` elements read so far;
  // returns it resolved to 1-based. Positive indices are checked by the caller at the end.
  long index(std::string_view token, size_t count, const std::string& what) const {
    const std::string text(token);
    char* end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
      fail("'" + text + "' is not a " + what + " index");
    if (value == 0) fail(what + " index 0: OBJ indices start at 1 (or count back from -1)");
    if (value > 0) return long(value);
    const long long target = (long long)count + 1 + value;  // -1 is the latest
    if (target < 1)
      fail(what + " index " + text + " counts back past the first of the " +
           std::to_string(count) + " " + plural(what) + " defined before this line");
    return long(target);
  }

  size_t line() const { return line_; }

 private:
  const std::string& path_;
  size_t line_;
};

struct IndexReference {
  size_t line;
  long index;
  const char* what;
};

}  // namespace

ObjSyntax check_obj_syntax(const std::string& text, const std::string& path) {
  ObjSyntax syntax;
  std::vector<IndexReference> forward;  // checked once every list's length is known
  size_t line_number = 0, begin = 0;
  while (begin <= text.size()) {
    // Lines end at \n, \r\n or a lone \r, as some readers split them (tinyobjloader did): a
    // lone \r ends a line here too, so that no line a reader may take for a vertex passes
    // unchecked.
    size_t end = text.find_first_of("\r\n", begin);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + begin, end - begin);
    begin = end + 1;
    if (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ++begin;
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    const LineReader reader(path, line_number);
    const std::string_view keyword = tokens[0];
    const size_t values = tokens.size() - 1;
    if (keyword == "v") {
      // x y z, optionally w (weight) or r g b (the vertex-colour extension readers accept).
      if (values != 3 && values != 4 && values != 6 && values != 7)
        reader.fail("a vertex needs 3 coordinates (x y z, optionally w or r g b), got " +
                    std::to_string(values));
      glm::vec3 position(0.0f);
      for (size_t i = 1; i <= values; ++i) {
        const float x = reader.number(tokens[i]);
        if (i <= 3 && std::abs(x) > kMaxSceneCoordinate)
          reader.fail("coordinate " + std::string(tokens[i]) +
                      " is beyond the representable scene extent (|x| <= 1e18)");
        if (i <= 3) position[int(i - 1)] = x;
      }
      syntax.vertex_lines.push_back(line_number);
      syntax.vertices.push_back(position);
    } else if (keyword == "vn") {
      if (values != 3) reader.fail("a normal needs 3 numbers, got " + std::to_string(values));
      for (size_t i = 1; i <= values; ++i) reader.number(tokens[i]);
      ++syntax.normal_count;
    } else if (keyword == "vt") {
      if (values < 1 || values > 3)
        reader.fail("a texture coordinate needs 1 to 3 numbers, got " + std::to_string(values));
      for (size_t i = 1; i <= values; ++i) reader.number(tokens[i]);
      ++syntax.texcoord_count;
    } else if (keyword == "f") {
      if (values < 3)
        reader.fail("a face needs at least 3 vertices, got " + std::to_string(values));
      for (size_t i = 1; i <= values; ++i) {
        const std::string_view corner = tokens[i];
        const size_t slash1 = corner.find('/');
        const size_t slash2 = slash1 == std::string_view::npos ? slash1 : corner.find('/', slash1 + 1);
        const std::string_view v = corner.substr(0, slash1);
        const std::string_view t = slash1 == std::string_view::npos
                                       ? std::string_view()
                                       : corner.substr(slash1 + 1, slash2 == std::string_view::npos
                                                                       ? std::string_view::npos
                                                                       : slash2 - slash1 - 1);
        const std::string_view n =
            slash2 == std::string_view::npos ? std::string_view() : corner.substr(slash2 + 1);
        if (slash2 != std::string_view::npos && n.find('/') != std::string_view::npos)
          reader.fail("'" + std::string(corner) + "' is not a face corner (v, v/t, v//n or v/t/n)");
        forward.push_back({line_number, reader.index(v, syntax.vertex_lines.size(), "vertex"), "vertex"});
        if (slash1 != std::string_view::npos && !t.empty())
          forward.push_back({line_number,
                             reader.index(t, syntax.texcoord_count, "texture coordinate"),
                             "texture coordinate"});
        if (slash2 != std::string_view::npos) {
          if (n.empty()) reader.fail("'" + std::string(corner) + "' has an empty normal index");
          forward.push_back({line_number, reader.index(n, syntax.normal_count, "normal"), "normal"});
        }
      }
      ++syntax.face_count;
    }
  }
  // Positive indices may name elements defined later in the file; by now all are known.
  for (const auto& ref : forward) {
    const std::string what = ref.what;
    const size_t count = what == "vertex"   ? syntax.vertex_lines.size()
                         : what == "normal" ? syntax.normal_count
                                            : syntax.texcoord_count;
    if (size_t(ref.index) > count)
      LineReader(path, ref.line)
          .fail(what + " index " + std::to_string(ref.index) + " is past the " +
                std::to_string(count) + " " + plural(what) + " in the file");
  }
  return syntax;
}

}  // namespace ldm
