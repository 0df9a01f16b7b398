// Throwaway benchmark kept as the record of how docs/measured/scenes/obj-loaders.txt was measured (it
// needs the tinyobjloader path removed after it, at the commit named there).
// Throwaway: tinyobjloader vs Assimp behind the same strict OBJ check and conversion.
#include <chrono>
#include <cstdio>
#include "harness/scene/obj_loader.h"
#include "harness/scene/mesh_import.h"
#include "harness/util/error.h"
using namespace ldm;
int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    for (int which = 0; which < 2; ++which) {
      double best = 1e30; size_t tris = 0; std::string err;
      for (int rep = 0; rep < 5; ++rep) {
        Scene s; s.name = "x";
        auto t0 = std::chrono::steady_clock::now();
        try {
          if (which == 0) load_obj_into(s, argv[i], {}, "bench"); else import_mesh_into(s, argv[i], {}, "bench");
        } catch (const std::exception& e) { err = e.what(); }
        best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        tris = s.mesh.triangle_count();
      }
      printf("%-40s %-9s %9.2f ms  %zu tris %s\n", argv[i], which ? "assimp" : "tinyobj", best, tris, err.substr(0, 150).c_str());
    }
  }
}
