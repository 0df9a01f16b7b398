#include "harness/measure/frame_samples.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "harness/util/error.h"

namespace ldm {
namespace {

// A non-negative integer field, or -1.
long long index_field(const std::string& text) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    return -1;
  return std::stoll(text);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

}  // namespace

std::vector<TimingSeries> parse_frame_samples(const std::string& csv, const std::string& where) {
  std::stringstream in(csv);
  std::string line;
  if (!std::getline(in, line) || (line != "repetition,frame,subpass,ms" && line != "frame,subpass,ms"))
    throw UserError(where + ":1: expected the header 'repetition,frame,subpass,ms'");
  const bool with_repetition = line.rfind("repetition", 0) == 0;
  const size_t width = with_repetition ? 4 : 3;
  std::vector<TimingSeries> repetitions;
  long long first_repetition = -1;  // a single repetition's file holds its own index
  long long current_frame = -1;
  FrameTimes frame;
  auto flush = [&] {
    if (current_frame >= 0) repetitions.back().add_frame(frame);
    frame.clear();
  };
  for (int number = 2; std::getline(in, line); ++number) {
    const std::string bad = where + ":" + std::to_string(number) + ": ";
    const std::vector<std::string> f = split_fields(line);
    if (f.size() != width)
      throw UserError(bad + "expected '" + (with_repetition ? "repetition," : "") +
                      "frame,subpass,ms', got '" + line + "'");
    const long long repetition = with_repetition ? index_field(f[0]) : 0;
    const long long frame_index = index_field(f[width - 3]);
    const std::string& subpass = f[width - 2];
    const std::string& ms = f[width - 1];
    if (repetition < 0 || frame_index < 0 || subpass.empty())
      throw UserError(bad + "expected '" + (with_repetition ? "repetition," : "") +
                      "frame,subpass,ms', got '" + line + "'");
    char* stop = nullptr;
    const double value = std::strtod(ms.c_str(), &stop);
    if (ms.empty() || *stop != '\0' || !std::isfinite(value) || value < 0)
      throw UserError(bad + "'" + ms + "' is not a time in ms");
    if (first_repetition < 0) first_repetition = repetition;
    const long long expected_next = first_repetition + static_cast<long long>(repetitions.size());
    if (repetition == expected_next) {  // the next repetition begins
      flush();
      repetitions.emplace_back();
      current_frame = -1;
    } else if (repetition != expected_next - 1) {
      throw UserError(bad + "repetition " + std::to_string(repetition) +
                      " out of order (repetitions are numbered in turn)");
    }
    if (frame_index != current_frame) {
      if (frame_index != current_frame + 1)
        throw UserError(bad + "frame " + std::to_string(frame_index) + " out of order");
      flush();
      current_frame = frame_index;
    }
    frame.emplace_back(subpass, value);
  }
  if (!repetitions.empty()) flush();
  return repetitions;
}

std::vector<TimingSeries> load_frame_samples(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw UserError(path + ": cannot read the per-frame samples the record names");
  std::stringstream text;
  text << in.rdbuf();
  return parse_frame_samples(text.str(), path);
}

}  // namespace ldm
