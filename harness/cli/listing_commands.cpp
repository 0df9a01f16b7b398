// `ldmbench scenes`, `ldmbench structures`, `ldmbench info`.
#include <iostream>

#include "harness/app/run_command.h"
#include "harness/cli/commands.h"
#include "harness/gl/egl_context.h"
#include "harness/scene/generators.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm::cli {

Runner add_listing_commands(CLI::App& app) {
  auto* scenes = app.add_subcommand("scenes", "List the built-in scenes");
  auto* structures = app.add_subcommand("structures", "List the LDM structures");
  auto* info = app.add_subcommand("info", "Print the OpenGL device ldmbench runs on");
  return [scenes, structures, info]() {
    if (scenes->parsed()) {
      for (const auto& g : scene_generators()) std::cout << g.name << "\t" << g.description << "\n";
    } else if (structures->parsed()) {
      for (const auto& name : structure_names()) std::cout << name << "\n";
    } else if (info->parsed()) {
      auto context = HeadlessContext::create(default_context_options());
      const DeviceInfo& d = context->device();
      std::cout << "renderer: " << d.gl_renderer << "\nvendor: " << d.gl_vendor
                << "\nversion: " << d.gl_version << "\nglsl: " << d.glsl_version
                << "\negl platform: " << d.egl_platform << " (" << d.egl_vendor << ")"
                << "\nmax storage block: " << d.max_ssbo_block_bytes << " bytes"
                << "\n64-bit atomics: " << (d.has_int64_atomics ? "yes" : "no")
                << "\ntimer queries: " << (d.has_timer_queries ? "yes" : "no") << "\n";
    }
    return kExitOk;
  };
}

}  // namespace ldm::cli
