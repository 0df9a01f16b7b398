// Mesh files of every format through Assimp (harness/scene/mesh_import.h): real models from
// Debian's assimp-testmodels load with node transforms, materials and normals as Assimp's own
// pre-transformed import has them; malformed data is refused naming the file, mesh and node;
// a crash or hang of Assimp is contained in its child process. The models are read where the
// package installs them; without it (scripts/setup.sh installs it) those tests are skipped,
// saying so.
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <signal.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <set>
#include <tuple>
#include <thread>

#include "harness/scene/mesh_import.h"
#include "harness/scene/scene_defaults.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/util/isolated_call.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models";

#define REQUIRE_TEST_MODELS()                                                              \
  if (!fs::is_directory(kModels))                                                          \
  GTEST_SKIP() << "assimp-testmodels is not installed (" << kModels                        \
               << " is missing): scripts/setup.sh installs it; these tests read its models"

using test::expect_contains;
using test::user_error;
using test::write_file;

// What Assimp itself makes of the file with its own node-transform step
// (aiProcess_PreTransformVertices), an independent implementation of what the converter
// does: triangle count (zero-area ones excluded, as the converter skips them) and bounds.
struct AssimpOracle {
  size_t triangles = 0;
  glm::vec3 lo{INFINITY}, hi{-INFINITY};
};
AssimpOracle pretransformed(const fs::path& file) {
  Assimp::Importer importer;
  const aiScene* s = importer.ReadFile(file.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices);
  AssimpOracle o;
  if (!s) return o;
  for (unsigned m = 0; m < s->mNumMeshes; ++m) {
    const aiMesh* mesh = s->mMeshes[m];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      glm::vec3 p[3];
      for (int k = 0; k < 3; ++k) {
        const aiVector3D v = mesh->mVertices[face.mIndices[k]];
        p[k] = {v.x, v.y, v.z};
      }
      if (!(glm::length(glm::cross(p[1] - p[0], p[2] - p[0])) > 0.0f)) continue;
      ++o.triangles;
      for (const auto& q : p) o.lo = glm::min(o.lo, q), o.hi = glm::max(o.hi, q);
    }
  }
  return o;
}

void expect_near_vec(glm::vec3 a, glm::vec3 b, float tolerance, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << what << " [" << k << "]";
}

TEST(ImportFormats, EveryFormatLoadsAsAssimpPlacesIt) {
  REQUIRE_TEST_MODELS();
  // One model per format of issue 22 (and IFC), each with what it exercises: node
  // transforms (Collada instance nodes, glTF's node tree, the engine's 34 placed meshes),
  // ASCII and binary encodings, polygons that need triangulating.
  const char* files[] = {
      "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
      "glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf",
      "PLY/Wuson.ply",
      "PLY/cube_binary.ply",
      "FBX/spider.fbx",
      "Collada/teapot_instancenodes.DAE",
      "Collada/teapots.DAE",
      "3DS/fels.3ds",
      "STL/Spider_binary.stl",
      "OFF/Wuson.off",
      "OBJ/spider.obj",
      "IFC/AC14-FZK-Haus.ifc",
  };
  for (const char* name : files) {
    SCOPED_TRACE(name);
    const fs::path file = kModels / name;
    const Scene scene = load_scene(file.string());
    const AssimpOracle oracle = pretransformed(file);
    ASSERT_GT(oracle.triangles, 0u);
    // Triangles of (nearly) zero area may fall on either side of zero in the two float
    // computations (one of the IFC house's 35,903).
    EXPECT_NEAR(double(scene.mesh.triangle_count()), double(oracle.triangles), 1e-4 * double(oracle.triangles));
    // The scene is rebased to its centre at load; origin_offset takes it back to the file's.
    Bounds b = scene.bounds();
    b.lo += glm::vec3(scene.origin_offset);
    b.hi += glm::vec3(scene.origin_offset);
    const float size = glm::length(oracle.hi - oracle.lo);
    expect_near_vec(b.lo, oracle.lo, 1e-4f * size, "lower bound");
    expect_near_vec(b.hi, oracle.hi, 1e-4f * size, "upper bound");
    EXPECT_EQ(scene.name, file.stem().string());
    for (const glm::vec3& n : scene.mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f);
  }
}

// The file's own node tree walked here, recursively and independently of the converter:
// how many non-degenerate triangles each albedo (base colour, else diffuse) covers, with
// every placement of a mesh counted.
void count_albedos(const aiScene& s, const aiNode& node, const aiMatrix4x4& parent,
                   std::map<std::tuple<float, float, float>, size_t>& out) {
  const aiMatrix4x4 world = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *s.mMeshes[node.mMeshes[i]];
    aiColor4D c(0.8f, 0.8f, 0.8f, 1.0f);
    const aiMaterial& m = *s.mMaterials[mesh.mMaterialIndex];
    if (m.Get(AI_MATKEY_BASE_COLOR, c) != AI_SUCCESS) m.Get(AI_MATKEY_COLOR_DIFFUSE, c);
    aiString name;
    m.Get(AI_MATKEY_NAME, name);
    if (std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME) c = aiColor4D(0.8f, 0.8f, 0.8f, 1.0f);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      if (mesh.mFaces[f].mNumIndices != 3) continue;
      aiVector3D p[3];
      for (int k = 0; k < 3; ++k) p[k] = world * mesh.mVertices[mesh.mFaces[f].mIndices[k]];
      if (((p[1] - p[0]) ^ (p[2] - p[0])).Length() > 0) ++out[{c.r, c.g, c.b}];
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) count_albedos(s, *node.mChildren[c], world, out);
}

TEST(ImportFormats, EveryPlacedTriangleCarriesItsMaterialsAlbedo) {
  REQUIRE_TEST_MODELS();
  // Instance nodes (one teapot placed twice), a glTF node tree with 35 materials, an OBJ with
  // a .mtl, an FBX.
  for (const char* name : {"Collada/teapot_instancenodes.DAE", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
                           "OBJ/spider.obj", "FBX/spider.fbx", "Collada/teapots.DAE"}) {
    SCOPED_TRACE(name);
    const fs::path file = kModels / name;
    Assimp::Importer importer;
    const aiScene* raw = importer.ReadFile(file.string(), aiProcess_Triangulate);
    ASSERT_NE(raw, nullptr);
    std::map<std::tuple<float, float, float>, size_t> expected, got;
    count_albedos(*raw, *raw->mRootNode, aiMatrix4x4(), expected);
    const Scene scene = load_scene(file.string());
    for (uint32_t m : scene.mesh.triangle_materials) {
      const glm::vec3 a = scene.materials.at(m).albedo;
      ++got[{a.x, a.y, a.z}];
    }
    ASSERT_EQ(got.size(), expected.size());
    for (const auto& [albedo, count] : expected) {
      ASSERT_TRUE(got.count(albedo)) << std::get<0>(albedo) << " " << std::get<1>(albedo) << " " << std::get<2>(albedo);
      EXPECT_NEAR(double(got[albedo]), double(count), 1e-4 * double(count) + 1.0);
    }
  }
  // The instanced teapot appears twice, in two places.
  Assimp::Importer importer;
  const aiScene* raw = importer.ReadFile((kModels / "Collada/teapot_instancenodes.DAE").string(), aiProcess_Triangulate);
  ASSERT_EQ(raw->mNumMeshes, 1u);
  std::map<std::tuple<float, float, float>, size_t> placed;
  count_albedos(*raw, *raw->mRootNode, aiMatrix4x4(), placed);
  size_t once = 0;
  for (unsigned f = 0; f < raw->mMeshes[0]->mNumFaces; ++f) {
    const aiFace& face = raw->mMeshes[0]->mFaces[f];
    const aiVector3D* v = raw->mMeshes[0]->mVertices;
    once += face.mNumIndices == 3 && ((v[face.mIndices[1]] - v[face.mIndices[0]]) ^ (v[face.mIndices[2]] - v[face.mIndices[0]])).Length() > 0;
  }
  const Scene teapots = load_scene((kModels / "Collada/teapot_instancenodes.DAE").string());
  EXPECT_EQ(teapots.mesh.triangle_count(), 2 * once);
  EXPECT_GT(teapots.bounds().hi.x - teapots.bounds().lo.x, 2.0f * 1.0f) << "the copies lie on each other";
}

TEST(ImportFormats, SmoothNormalsWhereTheFileHasThemFaceNormalsElsewhere) {
  REQUIRE_TEST_MODELS();
  auto face_normal = [](const Scene& s, size_t t) {
    const glm::uvec3 tri = s.mesh.triangles[t];
    return glm::normalize(glm::cross(s.mesh.positions[tri.y] - s.mesh.positions[tri.x],
                                     s.mesh.positions[tri.z] - s.mesh.positions[tri.x]));
  };
  // OFF has no normals: every corner carries its face's normal.
  const Scene off = load_scene((kModels / "OFF/Wuson.off").string());
  for (size_t t = 0; t < off.mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) ASSERT_GT(glm::dot(off.mesh.normals[off.mesh.triangles[t][k]], face_normal(off, t)), 0.9999f);
  // STL has one normal per facet, as the file says (its winding need not agree).
  const Scene stl = load_scene((kModels / "STL/Spider_binary.stl").string());
  for (size_t t = 0; t < stl.mesh.triangle_count(); ++t) {
    const glm::uvec3 tri = stl.mesh.triangles[t];
    ASSERT_EQ(stl.mesh.normals[tri.x], stl.mesh.normals[tri.y]);
    ASSERT_EQ(stl.mesh.normals[tri.x], stl.mesh.normals[tri.z]);
  }
  // The Wuson OBJ (2076 vn shared by its faces) and the engine's glTF have smooth vertex
  // normals: the corners of most triangles differ, and they follow the surface.
  for (const char* name : {"OBJ/WusonOBJ.obj", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}) {
    SCOPED_TRACE(name);
    const Scene s = load_scene((kModels / name).string());
    size_t smooth = 0, along = 0;
    for (size_t t = 0; t < s.mesh.triangle_count(); ++t) {
      const glm::uvec3 tri = s.mesh.triangles[t];
      smooth += glm::dot(s.mesh.normals[tri.x], s.mesh.normals[tri.y]) < 0.99999f;
      along += std::abs(glm::dot(s.mesh.normals[tri.x], face_normal(s, t))) > 0.5f;
    }
    EXPECT_GT(smooth, s.mesh.triangle_count() / 2);
    EXPECT_GT(along, s.mesh.triangle_count() * 9 / 10);
  }
}

// Why OBJ goes through Assimp too (docs/measured/scenes/obj-loaders.txt): a concave polygon
// must be triangulated within its outline. tinyobjloader's fan gave the test model's 66-gon
// 7.4 times its area.
TEST(ImportFormats, ConcavePolygonsKeepTheirArea) {
  REQUIRE_TEST_MODELS();
  const fs::path file = kModels / "OBJ/concave_polygon.obj";
  // The polygon's area by Newell's formula (the vector area of a planar polygon).
  std::vector<glm::dvec3> v;
  glm::dvec3 vector_area(0.0);
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "v") {
      glm::dvec3 p;
      words >> p.x >> p.y >> p.z;
      v.push_back(p);
    } else if (key == "f") {
      std::vector<glm::dvec3> corners;
      for (std::string c; words >> c;) corners.push_back(v.at(std::stoul(c.substr(0, c.find('/'))) - 1));
      for (size_t i = 0; i < corners.size(); ++i) vector_area += glm::cross(corners[i], corners[(i + 1) % corners.size()]);
    }
  }
  const double polygon_area = 0.5 * glm::length(vector_area);
  const Scene scene = load_scene(file.string());
  double area = 0;
  for (const glm::uvec3 t : scene.mesh.triangles)
    area += 0.5 * glm::length(glm::dvec3(glm::cross(scene.mesh.positions[t.y] - scene.mesh.positions[t.x],
                                                    scene.mesh.positions[t.z] - scene.mesh.positions[t.x])));
  EXPECT_NEAR(area, polygon_area, 1e-4 * polygon_area);
}

TEST(ImportFormats, AnObjMaterialNoMtlDefinesIsTheDefaultGrey) {
  // Assimp makes up an albedo of 0.6 for a `usemtl` no .mtl defines; ldmbench keeps its
  // documented default (0.8 grey), and the .mtl's own colour where there is one.
  const std::string dir = test::make_temp_dir("ldm-import");
  write_file(dir, "red.mtl", "newmtl red\nKd 0.9 0.1 0.1\n");
  const std::string obj = write_file(dir, "two.obj", "mtllib red.mtl\nmtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                       "usemtl blue\nf 1 2 3\nusemtl red\nf 1 3 2\n");
  const Scene scene = load_scene(obj);
  ASSERT_EQ(scene.mesh.triangle_count(), 2u);
  std::map<std::string, glm::vec3> albedo;
  for (uint32_t m : scene.mesh.triangle_materials) albedo[scene.materials[m].name] = scene.materials[m].albedo;
  EXPECT_EQ(albedo.at("default"), glm::vec3(0.8f));
  EXPECT_EQ(albedo.at("red"), glm::vec3(0.9f, 0.1f, 0.1f));
  EXPECT_EQ(albedo.count("blue"), 0u);
  // A scene material of the undefined name is what the file meant: it is used.
  const std::string json = write_file(dir, "two.json", R"({"meshes": [{"file": "two.obj"}], "materials": {"blue": [0.1, 0.2, 0.7]}})");
  const Scene with_blue = load_scene(json);
  bool blue = false;
  for (uint32_t m : with_blue.mesh.triangle_materials)
    blue = blue || (with_blue.materials[m].name == "blue" && with_blue.materials[m].albedo == glm::vec3(0.1f, 0.2f, 0.7f));
  EXPECT_TRUE(blue);
}

TEST(ImportChecks, MalformedModelsAreRefusedNamingFileMeshAndNode) {
  REQUIRE_TEST_MODELS();
  // glTF-Sample-Models' stress cases as Assimp passes them on.
  const std::string infinite = (kModels / "glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb").string();
  expect_contains(user_error([&] { load_scene(infinite); }), {"BoxWithInfinites.glb", "mesh", "node", "not finite"});
  const std::string no_triangles = (kModels / "OBJ/testpoints.obj").string();
  expect_contains(user_error([&] { load_scene(no_triangles); }), {"testpoints.obj", "no triangles"});
}

TEST(ImportChecks, ConvertedDataIsChecked) {
  // The converter on hand-made models: each check names the file, the mesh and the node.
  auto model = [] {
    ImportedModel m;
    m.materials.push_back({"red", true, {0.8f, 0.1f, 0.1f}});
    ImportedMesh mesh;
    mesh.name = "tri";
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.face_sizes = {3};
    mesh.indices = {0, 1, 2};
    m.meshes.push_back(mesh);
    ImportedNode root;
    root.name = "root";
    root.meshes = {0};
    m.nodes.push_back(root);
    return m;
  };
  auto convert = [](const ImportedModel& m) {
    Scene scene;
    append_imported_model(scene, m, "model.glb", {}, "scene.json: /meshes/0/file");
    return scene;
  };
  EXPECT_EQ(convert(model()).mesh.triangle_count(), 1u);
  EXPECT_EQ(convert(model()).materials.at(0).albedo, glm::vec3(0.8f, 0.1f, 0.1f));

  ImportedModel index = model();
  index.meshes[0].indices[2] = 7;
  expect_contains(user_error([&] { convert(index); }),
                  {"scene.json: /meshes/0/file", "model.glb", "mesh 'tri'", "node 'root'", "vertex 7 of 3"});
  ImportedModel nan = model();
  nan.meshes[0].positions[1].x = NAN;
  expect_contains(user_error([&] { convert(nan); }), {"mesh 'tri'", "vertex 1 is not finite"});
  // Beyond the scene extent only through the node's transform.
  ImportedModel huge = model();
  huge.nodes[0].transform = glm::scale(glm::mat4(1.0f), glm::vec3(1e30f));
  expect_contains(user_error([&] { convert(huge); }), {"node 'root'", "beyond the representable scene extent"});
  ImportedModel flat = model();
  flat.meshes[0].positions[2] = {2, 0, 0};
  expect_contains(user_error([&] { convert(flat); }), {"model.glb", "all 1 triangles have zero area"});
  ImportedModel material = model();
  material.meshes[0].material = 3;
  expect_contains(user_error([&] { convert(material); }), {"mesh 'tri'", "material 3 of 1"});
  ImportedModel colour = model();
  colour.materials[0].albedo.y = INFINITY;
  expect_contains(user_error([&] { convert(colour); }), {"material 'red'", "non-finite"});
  ImportedModel placed = model();
  placed.nodes[0].meshes = {2};
  expect_contains(user_error([&] { convert(placed); }), {"node 'root'", "mesh 2 of 1"});
  ImportedModel orphan = model();
  orphan.nodes[0].parent = 0;
  expect_contains(user_error([&] { convert(orphan); }), {"node #0", "does not precede"});
  ImportedModel polygon = model();
  polygon.meshes[0].face_sizes = {2, 1};
  EXPECT_NO_THROW(convert(model()));
  expect_contains(user_error([&] { convert(polygon); }), {"no triangles"});  // a line and a point
  ImportedModel quad = model();
  quad.meshes[0].positions.push_back({1, 1, 0});
  quad.meshes[0].face_sizes = {4};
  quad.meshes[0].indices = {0, 1, 3, 2};
  expect_contains(user_error([&] { convert(quad); }), {"face 0 has 4 corners"});
  ImportedModel short_indices = model();
  short_indices.meshes[0].face_sizes = {3, 3};
  expect_contains(user_error([&] { convert(short_indices); }), {"face 1 runs past"});
  // A mirrored node keeps unit normals facing out of its mirrored triangles.
  ImportedModel mirrored = model();
  mirrored.meshes[0].normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mirrored.nodes[0].transform = glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, -1));
  const Scene m = convert(mirrored);
  for (const glm::vec3& n : m.mesh.normals) EXPECT_NEAR(n.z, -1.0f, 1e-6f);
}

TEST(ImportChecks, EncodingRoundTripsAndRefusesTruncatedBytes) {
  ImportedModel m;
  m.materials.push_back({"a", true, {0.1f, 0.2f, 0.3f}});
  ImportedMesh mesh;
  mesh.name = "m";
  mesh.positions = {{1, 2, 3}};
  mesh.normals = {{0, 1, 0}};
  mesh.face_sizes = {1};
  mesh.indices = {0};
  m.meshes.push_back(mesh);
  ImportedNode node;
  node.name = "n";
  node.transform[3] = glm::vec4(5, 6, 7, 1);
  node.meshes = {0};
  m.nodes.push_back(node);
  const std::string bytes = encode_imported_model(m);
  const ImportedModel back = decode_imported_model(bytes);
  EXPECT_EQ(back.materials[0].albedo, m.materials[0].albedo);
  EXPECT_EQ(back.meshes[0].positions, mesh.positions);
  EXPECT_EQ(back.nodes[0].transform, node.transform);
  for (size_t cut : {size_t(0), size_t(9), bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW(decode_imported_model(bytes.substr(0, cut)), std::runtime_error) << cut;
  EXPECT_THROW(decode_imported_model(bytes + "x"), std::runtime_error);
  // A count far beyond the bytes is refused before anything is allocated for it.
  std::string huge = bytes;
  const uint32_t lots = 0xffffffffu;
  std::memcpy(&huge[8], &lots, 4);
  EXPECT_THROW(decode_imported_model(huge), std::runtime_error);
}

TEST(ImportIsolation, ChildOutcomesAreTellApart) {
  IsolationLimits limits;
  limits.seconds = 5;
  const IsolatedOutcome returned = run_isolated([] { return std::string("result"); }, limits);
  EXPECT_EQ(returned.kind, IsolatedOutcome::Kind::Returned);
  EXPECT_EQ(returned.bytes, "result");
  const IsolatedOutcome threw = run_isolated([]() -> std::string { throw std::runtime_error("bad file"); }, limits);
  EXPECT_EQ(threw.kind, IsolatedOutcome::Kind::Threw);
  EXPECT_EQ(threw.message, "bad file");
  const IsolatedOutcome crashed = run_isolated([]() -> std::string {
    raise(SIGSEGV);
    return "unreachable";
  }, limits);
  EXPECT_EQ(crashed.kind, IsolatedOutcome::Kind::Crashed);
  EXPECT_EQ(crashed.signal, SIGSEGV);
  EXPECT_NE(describe_signal(SIGSEGV).find("SIGSEGV"), std::string::npos);
  limits.seconds = 0.5;
  const IsolatedOutcome hung = run_isolated([]() -> std::string {
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
  }, limits);
  EXPECT_EQ(hung.kind, IsolatedOutcome::Kind::TimedOut);
  // A large result crosses the pipe whole (more than its buffer).
  limits.seconds = 30;
  const IsolatedOutcome big = run_isolated([] { return std::string(5 << 20, 'x'); }, limits);
  EXPECT_EQ(big.kind, IsolatedOutcome::Kind::Returned);
  EXPECT_EQ(big.bytes.size(), size_t(5) << 20);
}

TEST(ImportIsolation, AFileThatExhaustsTheImportersMemoryIsARefusal) {
  REQUIRE_TEST_MODELS();
  // assimp-testmodels' own hostile file: an OFF claiming 353,535,235,358 vertices. In this
  // process Assimp would reserve without bound (it ran for minutes filling memory); in the
  // child, whose address space is limited, the allocation fails and the import is refused.
  const std::string file = (kModels / "invalid/OutOfMemory.off").string();
  const std::string message = user_error([&] { load_scene(file); });
  expect_contains(message, {"OutOfMemory.off", "Assimp"});
  // How it was refused, not how fast (no check here depends on the machine's speed; ctest's
  // timeout bounds a child that never stops): the allocation fails in the child's capped
  // address space. Under AddressSanitizer the cap holds too (it counts the shadow the parent
  // had mapped; uncapped, the child filled pages for 52-130 s), but ASan's operator new
  // reports the failed allocation and ends the child (its death status) instead of throwing.
#if defined(__SANITIZE_ADDRESS__)
  EXPECT_NE(message.find("crashed on it (exit status " + std::to_string(kSanitizerDeathStatus) + ")"), std::string::npos)
      << message;
#else
  EXPECT_NE(message.find("bad_alloc"), std::string::npos) << message;
#endif
  // The empty and malformed ones: refusals naming the file, never a crash of this process.
  for (const char* name : {"invalid/empty.ply", "invalid/empty.off", "invalid/empty.3ds", "invalid/malformed.obj"})
    expect_contains(user_error([&] { load_scene((kModels / name).string()); }), {fs::path(name).filename().string()});
}

// Inputs fuzz_import found (tests/fuzz/corpus/import/assimp-*): bytes Assimp aborts on (an
// ai_assert in its triangulation, Debian builds it with assertions) and bytes it loops on.
// In this process either would end ldmbench; isolated, each is a refusal naming the file.
std::string fuzz_input(const std::string& name) {
  const std::string bytes = test::read_text((fs::path(LDM_TEST_SOURCE_DIR) / "fuzz" / "corpus" / "import" / name).string());
  return bytes.empty() ? bytes : bytes.substr(1);  // the first byte picks the format
}

TEST(ImportIsolation, AFileAssimpCrashesOrHangsOnIsARefusalNamingTheFile) {
  const std::string dir = test::make_temp_dir("ldm-import");
  const std::string aborts = write_file(dir, "aborts.off", fuzz_input("assimp-aborts.off"));
  const std::string message = user_error([&] { load_scene(aborts); });
  expect_contains(message, {"aborts.off", "importer (Assimp", "crashed", "SIGABRT"});
  // The child that hangs is ended at its 1 s limit: the refusal says so (were it not ended,
  // the test would hang to ctest's timeout; no wall-clock bound here, which a slow machine
  // could fail).
  Scene scene;
  expect_contains(user_error([&] {
                    import_mesh_bytes_into(scene, fuzz_input("assimp-hangs.ply"), "ply", "hangs.ply", 1.0, "test");
                  }),
                  {"hangs.ply", "took longer than 1 s"});
}

TEST(MeshScene, DefaultsFollowTheScenesSize) {
  // A unit cube scaled to millimetres (the engine's unit): d_max, camera and light scale.
  const std::string dir = test::make_temp_dir("ldm-import");
  const std::string path = write_file(dir, "box.off", test::cube_off(400));
  const Scene scene = load_scene(path);
  EXPECT_EQ(scene.mesh.triangle_count(), 12u);
  const BoundingSphere sphere = scene.bounding_sphere();
  EXPECT_NEAR(sphere.radius, 200.0f * std::sqrt(3.0f), 1e-3f);
  EXPECT_NEAR(scene.ao.d_max, kDerivedDMaxFraction * sphere.radius, 1e-3f);
  EXPECT_NE(scene.sources.d_max.find("derived"), std::string::npos);
  EXPECT_NE(scene.sources.camera.find("derived"), std::string::npos);
  EXPECT_NE(scene.sources.light.find("derived"), std::string::npos);
  // The camera sees the whole sphere: its centre straight ahead, its rim inside the field.
  const glm::vec3 view = scene.camera.target - scene.camera.eye;
  EXPECT_NEAR(glm::length(glm::normalize(view) - glm::normalize(sphere.centre - scene.camera.eye)), 0.0f, 1e-4f);
  const float half_angle = std::asin(sphere.radius / glm::length(view)) * 180.0f / 3.14159265f;
  EXPECT_LT(half_angle, 0.5f * scene.camera.fov_y_deg);
  EXPECT_GT(half_angle, 0.4f * scene.camera.fov_y_deg);  // and fills it
  // The light's cone covers the sphere and lights its centre with 1 W/m^2.
  const glm::vec3 to_centre = sphere.centre - scene.light.position;
  const float reach = std::asin(sphere.radius / glm::length(to_centre)) * 180.0f / 3.14159265f;
  EXPECT_GE(scene.light.inner_angle_deg, 0.7f * reach);
  EXPECT_GE(scene.light.outer_angle_deg, reach);
  EXPECT_NEAR(scene.light.intensity.x / glm::dot(to_centre, to_centre), 1.0f, 1e-4f);
  EXPECT_NO_THROW(scene.validate());
  // A scene file with the mesh alone derives the same; its own keys win and say so.
  const std::string json = write_file(dir, "box.json", R"({"name": "my-box", "meshes": [{"file": "box.off"}],
      "ao": {"d_max": 25}})");
  const Scene from_file = load_scene(json);
  EXPECT_EQ(from_file.name, "my-box");
  EXPECT_EQ(from_file.ao.d_max, 25.0f);
  EXPECT_EQ(from_file.sources.d_max, "scene file");
  EXPECT_EQ(from_file.camera.eye, scene.camera.eye);
  EXPECT_NE(from_file.sources.camera.find("derived"), std::string::npos);
  // A generator's settings are the generator's.
  EXPECT_EQ(load_scene("cornell").sources.d_max, "generator cornell");
}

TEST(MeshScene, IdsUseTheScenesNameAndCollisionsAreRefused) {
  const std::string dir = test::make_temp_dir("ldm-import");
  const std::string named = write_file(dir, "scene.json", R"({"name": "my-room", "generator": {"type": "cornell"}})");
  const std::string unnamed = write_file(dir, "other.json", R"({"generator": {"type": "cornell"}})");
  EXPECT_EQ(scene_id_name(named), "my-room");
  EXPECT_EQ(load_scene(named).name, "my-room");
  EXPECT_EQ(scene_id_name(unnamed), "other");  // the file's name, never the generator's
  EXPECT_EQ(load_scene(unnamed).name, "other");
  EXPECT_EQ(scene_id_name("cornell"), "cornell");
  const std::string mesh = write_file(dir, "tri.stl", "solid t\nfacet normal 0 0 1\nouter loop\n"
                                                      "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                                      "endloop\nendfacet\nendsolid t\n");
  EXPECT_EQ(scene_id_name(mesh), "tri");
  EXPECT_EQ(load_scene(mesh).name, "tri");
}

}  // namespace
}  // namespace ldm
