// `ldmbench scenes`, `structures`, `passes`, `columns`, `axes`, `info`.
#include <iostream>
#include <memory>

#include "harness/settings/axis_registry.h"
#include "harness/run/exit_codes.h"
#include "harness/cli/commands.h"
#include "harness/gl/driver_probe.h"
#include "harness/gl/egl_context.h"
#include "harness/passes/pass.h"
#include "harness/settings/record_schema.h"
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
  auto labels = std::make_shared<bool>(false);
  columns->add_flag("--labels", *labels,
                    "The headline columns' short labels and which way is better, as JSON "
                    "(scripts/report/ldmreport/labels.json)");
  auto json = std::make_shared<bool>(false);
  columns->add_flag("--json", *json,
                    "Every column with its unit, description, kind, whether it varies between runs, "
                    "whether it is deterministic and which way is better, as JSON");
  auto* info = app.add_subcommand(
      "info", "List every EGL device (index, kind: CUDA ordinal, DRM node or software; renderer "
              "where a context can be made) and print the OpenGL device ldmbench runs on");
  auto info_gpu = std::make_shared<GpuOption>();
  add_gpu_option(info, *info_gpu);
  auto* axes = app.add_subcommand("axes", "List every axis a sweep can vary: the harness's and each structure's and pass's parameters");
  auto axes_format = std::make_shared<std::string>("text");
  axes->add_flag("--json{json}", *axes_format, "As JSON (what the report reads)");
  axes->add_flag("--markdown{markdown}", *axes_format, "As the Markdown table of docs/reference/axes.md");
  return [scenes, structures, passes, columns, markdown, labels, json, info, info_gpu, axes, axes_format]() {
    if (axes->parsed()) {
      if (*axes_format == "json") std::cout << axes_json().dump(2) << "\n";
      else if (*axes_format == "markdown") std::cout << axes_markdown();
      else std::cout << axes_text();
      return kExitOk;
    }
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
      std::cout << (*labels     ? column_labels_json()
                    : *json     ? columns_json()
                    : *markdown ? columns_markdown()
                                : columns_text());
    } else if (info->parsed()) {
      ContextOptions options = default_context_options();
      options.gpu = gpu_request_from_environment(info_gpu->text());
      // Every device first: the list is what a wrong --gpu is judged against.
      const auto devices = list_egl_devices(true);
      std::cout << "egl devices: " << devices.size() << (devices.empty() ? " (EGL_EXT_device_enumeration lists none)" : "") << "\n";
      for (const auto& device : devices) std::cout << "  " << device.describe() << "\n";
      auto context = HeadlessContext::create(options);
      const DeviceInfo& d = context->device();
      std::cout << "chosen: " << d.device_choice << "\ndevice id: " << d.device_id
                << "\ngl driver: " << d.gl_driver << "\nrenderer: " << d.gl_renderer << "\nvendor: " << d.gl_vendor
                << "\nversion: " << d.gl_version << "\nglsl: " << d.glsl_version
                << "\negl platform: " << d.egl_platform << " (" << d.egl_vendor << ")"
                << "\nmax storage block: " << d.max_ssbo_block_bytes << " bytes"
                << "\n64-bit atomics: " << (d.has_int64_atomics ? "yes" : "no")
                << "\ntimer queries: " << (d.has_timer_queries ? "yes" : "no") << "\n";
      // Each self-test's own line: a run's records say only what failed (driver_defects).
      for (const BarrierProbeResult& probe : driver_conformance().barrier_probes)
        std::cout << "self-test: "
                  << (probe.conformant() ? std::string(probe_barrier_name(probe.barrier)) +
                                               " in a divergent " + probe_stage_name(probe.stage) +
                                               " loop: ok"
                                         : "FAILED: " + probe.describe())
                  << "\n";
    }
    return kExitOk;
  };
}

}  // namespace ldm::cli
