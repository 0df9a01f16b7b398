// `ldmbench scenes`, `structures`, `passes`, `columns`, `info`.
#include <iostream>
#include <memory>

#include "harness/app/run_command.h"
#include "harness/cli/commands.h"
#include "harness/gl/egl_context.h"
#include "harness/passes/pass.h"
#include "harness/records/columns.h"
#include "harness/scene/generators.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm::cli {

Runner add_listing_commands(CLI::App& app) {
  auto* scenes = app.add_subcommand("scenes", "List the built-in scenes");
  auto* structures = app.add_subcommand("structures", "List the LDM structures");
  auto* passes = app.add_subcommand("passes", "List the passes and the sub-passes each times");
  auto* columns = app.add_subcommand("columns", "Describe every record column: unit and meaning");
  auto markdown = std::make_shared<bool>(false);
  columns->add_flag("--markdown", *markdown, "As the Markdown table of docs/reference/records.md");
  auto* info = app.add_subcommand("info", "Print the OpenGL device ldmbench runs on");
  return [scenes, structures, passes, columns, markdown, info]() {
    if (scenes->parsed()) {
      for (const auto& g : scene_generators()) std::cout << g.name << "\t" << g.description << "\n";
    } else if (structures->parsed()) {
      for (const auto& name : structure_names()) std::cout << name << "\n";
    } else if (passes->parsed()) {
      for (const auto& name : pass_names()) {
        std::cout << name << "\n";
        for (const auto& s : make_pass(name, StructureParams())->subpasses())
          std::cout << "  " << s.name << "\t" << s.description << "\n";
      }
    } else if (columns->parsed()) {
      std::cout << (*markdown ? columns_markdown() : columns_text());
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
