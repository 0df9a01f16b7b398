#include "harness/compare/samples.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "harness/util/error.h"

namespace ldm {

std::vector<double> frame_samples(const std::vector<FrameTimes>& frames, const std::string& subpass) {
  std::vector<double> samples;
  for (const FrameTimes& frame : frames)
    for (const auto& [name, ms] : frame)
      if (name == subpass) {
        samples.push_back(ms);
        break;
      }
  return samples;
}

std::string format_samples(const std::vector<double>& samples) {
  std::string text;
  char buffer[32];
  for (double v : samples) {
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    text += (text.empty() ? "" : ";") + std::string(buffer);
  }
  return text;
}

std::vector<double> parse_samples(const std::string& text, const std::string& where) {
  std::vector<double> samples;
  if (text.empty()) return samples;
  size_t start = 0;
  while (true) {
    const size_t end = text.find(';', start);
    const std::string item = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    char* stop = nullptr;
    const double v = item.empty() ? NAN : std::strtod(item.c_str(), &stop);
    if (item.empty() || *stop != '\0' || !std::isfinite(v))
      throw UserError(where + ": '" + item + "' is not a time in ms (expected 'ms;ms;...')");
    samples.push_back(v);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return samples;
}

}  // namespace ldm
