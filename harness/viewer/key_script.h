#pragma once
// `ldmbench view --script`: key presses for scripts and tests, injected at given frames
// through the same handler GLFW's key events reach ("3:s,6:shift+p,9:f12": at frame 3 the
// key S, at frame 6 Shift+P, ...). Frames count from 0; keys are letters, digits, f1..f12,
// escape, up, down, left, right, page_up, page_down.
#include <string>
#include <vector>

namespace ldm::viewer {

struct KeyPress {
  int frame = 0;
  int key = 0;   // GLFW_KEY_*
  int mods = 0;  // GLFW_MOD_*
};

// Throws UserError naming the item that is not FRAME:KEY.
std::vector<KeyPress> parse_key_script(const std::string& script);

}  // namespace ldm::viewer
