#include "harness/viewer/key_script.h"

#include <cctype>
#include <map>
#include <sstream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "harness/util/error.h"

namespace ldm::viewer {
namespace {

int key_named(std::string name) {
  for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0])))
    return GLFW_KEY_A + (name[0] - 'a');
  if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0])))
    return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name[0] == 'f' && name.find_first_not_of("0123456789", 1) == std::string::npos) {
    const int n = std::stoi(name.substr(1));
    if (n >= 1 && n <= 12) return GLFW_KEY_F1 + n - 1;
  }
  static const std::map<std::string, int> named = {
      {"escape", GLFW_KEY_ESCAPE}, {"up", GLFW_KEY_UP},        {"down", GLFW_KEY_DOWN},
      {"left", GLFW_KEY_LEFT},     {"right", GLFW_KEY_RIGHT},  {"page_up", GLFW_KEY_PAGE_UP},
      {"page_down", GLFW_KEY_PAGE_DOWN}};
  const auto it = named.find(name);
  return it == named.end() ? -1 : it->second;
}

}  // namespace

std::vector<KeyPress> parse_key_script(const std::string& script) {
  std::vector<KeyPress> presses;
  std::stringstream items(script);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto colon = item.find(':');
    KeyPress press;
    std::string key = colon == std::string::npos ? "" : item.substr(colon + 1);
    if (key.rfind("shift+", 0) == 0) {
      press.mods = GLFW_MOD_SHIFT;
      key = key.substr(6);
    }
    const std::string frame = colon == std::string::npos ? "" : item.substr(0, colon);
    press.key = key_named(key);
    if (frame.empty() || frame.find_first_not_of("0123456789") != std::string::npos ||
        frame.size() > 9 || press.key < 0)
      throw UserError("--script: '" + item + "' is not FRAME:KEY (e.g. 3:s, 6:shift+p, 9:f12)");
    press.frame = std::stoi(frame);
    presses.push_back(press);
  }
  return presses;
}

}  // namespace ldm::viewer
