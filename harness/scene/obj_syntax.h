#pragma once
// A strict reader of the OBJ statements ldmbench uses (v, vn, vt, f), run before the importer
// (mesh_import.h, Assimp): OBJ readers (Assimp's, tinyobjloader's) read "v a b c" as 0, pad
// short vertices, keep nan and inf, and drop faces with fewer than three corners, all
// without a word. Here each of those is an error naming the file and the line.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ldm {

struct ObjSyntax {
  std::vector<size_t> vertex_lines;  // 1-based line of each `v` statement, in order
  std::vector<glm::vec3> vertices;   // its x y z
  size_t normal_count = 0, texcoord_count = 0, face_count = 0;
};

// Checks every v/vn/vt/f statement of `text`: the right count of decimal numbers, each
// finite as a 32-bit float; vertex coordinates within kMaxSceneCoordinate; faces with at
// least three corners whose indices (1-based, or negative = relative to the statements read
// so far) name existing elements. Other statements (o, g, s, usemtl, mtllib, l, p, comments)
// pass through. Throws UserError "<path>:<line>: ...".
ObjSyntax check_obj_syntax(const std::string& text, const std::string& path);

}  // namespace ldm
