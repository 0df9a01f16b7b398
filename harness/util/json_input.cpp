#include "harness/util/json_input.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <vector>

#include "harness/util/error.h"

namespace ldm {
namespace {

// Where the parser is: the iterator handed to nlohmann-json moves it forward, so the SAX
// handler knows the line and column of every event (the parser reads no further than the
// end of the token it reports).
struct Cursor {
  const char* position = nullptr;
  const char* line_start = nullptr;
  size_t line = 1;
};

class CountingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator(const char* p, Cursor* cursor) : p_(p), cursor_(cursor) {}
  reference operator*() const { return *p_; }
  CountingIterator& operator++() {
    if (*p_ == '\n') {
      ++cursor_->line;
      cursor_->line_start = p_ + 1;
    }
    ++p_;
    cursor_->position = p_;
    return *this;
  }
  bool operator==(const CountingIterator& other) const { return p_ == other.p_; }
  bool operator!=(const CountingIterator& other) const { return p_ != other.p_; }

 private:
  const char* p_;
  Cursor* cursor_;
};

// The 1-based line and column of a byte offset into `text`.
std::pair<size_t, size_t> line_and_column(std::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// nlohmann-json's DOM builder behind a handler that bounds the depth, refuses duplicate
// keys and remembers where a parse error happened.
template <class Json>
class StrictHandler {
 public:
  using number_integer_t = typename Json::number_integer_t;
  using number_unsigned_t = typename Json::number_unsigned_t;
  using number_float_t = typename Json::number_float_t;
  using string_t = typename Json::string_t;
  using binary_t = typename Json::binary_t;

  StrictHandler(Json& root, const Cursor& cursor, size_t max_depth)
      : dom_(root, /*allow_exceptions=*/false), cursor_(cursor), max_depth_(max_depth) {}

  bool null() { return value() && dom_.null(); }
  bool boolean(bool v) { return value() && dom_.boolean(v); }
  bool number_integer(number_integer_t v) { return value() && dom_.number_integer(v); }
  bool number_unsigned(number_unsigned_t v) { return value() && dom_.number_unsigned(v); }
  bool number_float(number_float_t v, const string_t& s) { return value() && dom_.number_float(v, s); }
  bool string(string_t& v) { return value() && dom_.string(v); }
  bool binary(binary_t& v) { return value() && dom_.binary(v); }

  bool start_object(std::size_t n) {
    if (!value() || !enter(true)) return false;
    return dom_.start_object(n);
  }
  bool key(string_t& k) {
    Frame& frame = frames_.back();
    const auto [it, fresh] = frame.keys.emplace(k, cursor_.line);
    if (!fresh) {
      problem_ = "line " + std::to_string(cursor_.line) + ": key \"" + std::string(k) + "\" at " +
                 raw_path(frames_.size() - 1) + "/" + std::string(k) + " appears twice in one object (first at line " +
                 std::to_string(it->second) + "); give each key once";
      return false;
    }
    frame.key = k;
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return dom_.end_object();
  }
  bool start_array(std::size_t n) {
    if (!value() || !enter(false)) return false;
    return dom_.start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return dom_.end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
    error_position_ = position;
    error_token_ = token;
    error_message_ = e.what();
    return false;
  }

  const std::string& problem() const { return problem_; }
  std::size_t error_position() const { return error_position_; }
  const std::string& error_token() const { return error_token_; }
  const std::string& error_message() const { return error_message_; }

 private:
  struct Frame {
    bool object = false;
    size_t next_index = 0;          // arrays: the index of the next element
    std::string key;                // objects: the latest key
    std::map<std::string, size_t> keys;  // objects: key -> line
  };

  // A value begins: an array counts its elements (for the path in messages).
  bool value() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().next_index;
    return true;
  }
  bool enter(bool object) {
    if (frames_.size() >= max_depth_) {
      problem_ = "line " + std::to_string(cursor_.line) + ", column " +
                 std::to_string(size_t(cursor_.position - cursor_.line_start) + 1) +
                 ": arrays and objects nested deeper than " + std::to_string(max_depth_) +
                 " levels (at " + path_of(frames_.size()) + "); nothing ldmbench reads nests that deep";
      return false;
    }
    Frame frame;
    frame.object = object;
    frames_.push_back(std::move(frame));
    return true;
  }
  // The JSON pointer of the value the first `depth` frames lead to ("/meshes/0/file").
  std::string path_of(size_t depth) const {
    const std::string path = raw_path(depth);
    return path.empty() ? "the top level" : path;
  }
  std::string raw_path(size_t depth) const {
    std::string path;
    for (size_t i = 0; i < depth; ++i) {
      if (i == 6 && depth > 8) {  // a path 64 levels deep says no more than its start
        path += "/...";
        break;
      }
      path += "/" + (frames_[i].object ? frames_[i].key : std::to_string(frames_[i].next_index - 1));
    }
    return path;
  }

  nlohmann::detail::json_sax_dom_parser<Json> dom_;
  const Cursor& cursor_;
  size_t max_depth_;
  std::vector<Frame> frames_;
  std::string problem_;
  std::size_t error_position_ = 0;
  std::string error_token_, error_message_;
};

template <class Json>
Json parse_strictly(std::string_view text, const std::string& name, const JsonLimits& limits) {
  Json root;
  Cursor cursor;
  cursor.position = cursor.line_start = text.data();
  StrictHandler<Json> handler(root, cursor, limits.max_depth);
  const CountingIterator first(text.data(), &cursor), last(text.data() + text.size(), &cursor);
  if (Json::sax_parse(first, last, &handler, nlohmann::detail::input_format_t::json, true, false))
    return root;
  if (!handler.problem().empty()) throw UserError(name + ": " + handler.problem());
  // nlohmann's message reads "[json.exception.parse_error.101] parse error at line 3, column
  // 9: syntax error ..."; keep its description, and say where from our own count (a number
  // beyond double, 1e400, is reported as out_of_range without a position).
  std::string what = handler.error_message();
  // Where: nlohmann's own line and column (of the offending character) when it gives them.
  static const std::regex where_pattern(R"(at line ([0-9]+), column ([0-9]+))");
  std::smatch where;
  const std::string message = what;
  const bool located = std::regex_search(message, where, where_pattern);
  const auto colon = what.find(": ", what.find(']'));
  if (colon != std::string::npos && what.find("parse error") != std::string::npos)
    what = what.substr(colon + 2);
  else if (const auto bracket = what.find("] "); bracket != std::string::npos)
    what = what.substr(bracket + 2);
  // The parser reports the offset just past the offending token.
  const size_t position = handler.error_position();
  const size_t start = position >= handler.error_token().size() ? position - handler.error_token().size() : 0;
  const auto [line, column] = line_and_column(text, start);
  throw UserError(name + ": malformed JSON at line " + (located ? where[1].str() : std::to_string(line)) +
                  ", column " + (located ? where[2].str() : std::to_string(column)) + ": " + what);
}

std::string mib_text(uint64_t bytes) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.4g MiB", double(bytes) / double(1u << 20));
  return buffer;
}

}  // namespace

nlohmann::json parse_json_strictly(std::string_view text, const std::string& name,
                                   const JsonLimits& limits) {
  return parse_strictly<nlohmann::json>(text, name, limits);
}

nlohmann::ordered_json parse_ordered_json_strictly(std::string_view text, const std::string& name,
                                                   const JsonLimits& limits) {
  return parse_strictly<nlohmann::ordered_json>(text, name, limits);
}

uint64_t max_input_bytes() {
  constexpr uint64_t kDefaultMib = 512;
  const char* env = std::getenv(kMaxInputEnv);
  if (!env || !*env) return kDefaultMib << 20;
  char* end = nullptr;
  const double mib = std::strtod(env, &end);
  if (*end != '\0' || !(mib > 0) || !(mib <= 1048576.0 * 1024))
    throw UserError(std::string(kMaxInputEnv) + "='" + env +
                    "': expected a positive number of MiB (the largest input file to read)");
  return uint64_t(std::ceil(mib * double(1u << 20)));
}

void check_input_size(const std::string& path, const std::string& what) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw UserError(what + " '" + path + "' does not exist");
    throw_io_error("cannot examine " + what + " '" + path + "'", errno);
  }
  if (S_ISDIR(info.st_mode)) throw UserError(what + " '" + path + "' is a folder, not a file");
  const uint64_t limit = max_input_bytes();
  if (S_ISREG(info.st_mode) && uint64_t(info.st_size) > limit)
    throw UserError(what + " '" + path + "' is " + mib_text(uint64_t(info.st_size)) +
                    ", larger than the input limit of " + mib_text(limit) + " (set " + kMaxInputEnv +
                    " to read larger files)");
}

std::string read_input_file(const std::string& path, const std::string& what) {
  check_input_size(path, what);
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError("cannot open " + what + " '" + path + "': " + errno_text(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw_io_error("cannot read " + what + " '" + path + "'", errno);
  return text.str();
}

}  // namespace ldm
