// Throwaway benchmark kept as the record of how docs/measured/scenes/obj-loaders.txt was measured (it
// needs the tinyobjloader path removed after it, at the commit named there).
#include <cstdio>
#include <glm/glm.hpp>
#include "harness/scene/obj_loader.h"
#include "harness/scene/mesh_import.h"
#include "harness/util/error.h"
using namespace ldm;
int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    for (int which = 0; which < 2; ++which) {
      Scene s; s.name = "x"; std::string err;
      try { if (which == 0) load_obj_into(s, argv[i], {}, "cmp"); else import_mesh_into(s, argv[i], {}, "cmp"); }
      catch (const std::exception& e) { err = e.what(); }
      double area = 0; for (auto t : s.mesh.triangles) area += 0.5 * glm::length(glm::cross(s.mesh.positions[t.y]-s.mesh.positions[t.x], s.mesh.positions[t.z]-s.mesh.positions[t.x]));
      std::string mats; for (auto& m : s.materials) { char b[64]; snprintf(b, 64, "%s(%.2f) ", m.name.c_str(), m.albedo.x); mats += b; }
      printf("%-28s %-8s tris %zu area %.4f mats %s %s\n", argv[i], which ? "assimp" : "tinyobj", s.mesh.triangle_count(), area, mats.c_str(), err.substr(0,120).c_str());
    }
}
