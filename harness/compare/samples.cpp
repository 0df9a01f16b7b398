#include "harness/compare/samples.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "harness/util/error.h"

namespace ldm {

FrameSamples parse_frame_samples(const std::string& csv, const std::string& where) {
  std::stringstream in(csv);
  std::string line;
  if (!std::getline(in, line) || line != "frame,subpass,ms")
    throw UserError(where + ":1: expected the header 'frame,subpass,ms'");
  FrameSamples samples;
  for (int number = 2; std::getline(in, line); ++number) {
    const size_t a = line.find(','), b = a == std::string::npos ? a : line.find(',', a + 1);
    const std::string bad = where + ":" + std::to_string(number) + ": ";
    if (b == std::string::npos || line.find(',', b + 1) != std::string::npos)
      throw UserError(bad + "expected 'frame,subpass,ms', got '" + line + "'");
    const std::string ms = line.substr(b + 1);
    char* stop = nullptr;
    const double value = std::strtod(ms.c_str(), &stop);
    if (ms.empty() || *stop != '\0' || !std::isfinite(value) || value < 0)
      throw UserError(bad + "'" + ms + "' is not a time in ms");
    samples[line.substr(a + 1, b - a - 1)].push_back(value);
  }
  return samples;
}

FrameSamples load_frame_samples(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw UserError(path + ": cannot read the per-frame samples the record names");
  std::stringstream text;
  text << in.rdbuf();
  return parse_frame_samples(text.str(), path);
}

}  // namespace ldm
