#include "harness/scene/imported_model.h"

#include <cstring>
#include <stdexcept>

namespace ldm {
namespace {

constexpr char kMagic[8] = {'L', 'D', 'M', 'M', 'O', 'D', 'L', '1'};

class Writer {
 public:
  // An empty vector's data() may be null, which memcpy and append must not be given.
  void raw(const void* data, size_t size) {
    if (size > 0) out_.append(static_cast<const char*>(data), size);
  }
  void u32(uint32_t v) { raw(&v, sizeof v); }
  void i32(int32_t v) { raw(&v, sizeof v); }
  void f32(float v) { raw(&v, sizeof v); }
  void text(const std::string& s) {
    u32(uint32_t(s.size()));
    raw(s.data(), s.size());
  }
  template <class T>
  void array(const std::vector<T>& v) {
    u32(uint32_t(v.size()));
    raw(v.data(), v.size() * sizeof(T));
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : data_(bytes.data()), left_(bytes.size()) {}
  void raw(void* out, size_t size) {
    if (size > left_) throw std::runtime_error("the imported model's encoding is truncated");
    if (size == 0) return;  // out may be an empty vector's null data()
    std::memcpy(out, data_, size);
    data_ += size;
    left_ -= size;
  }
  uint32_t u32() {
    uint32_t v;
    raw(&v, sizeof v);
    return v;
  }
  int32_t i32() {
    int32_t v;
    raw(&v, sizeof v);
    return v;
  }
  float f32() {
    float v;
    raw(&v, sizeof v);
    return v;
  }
  // A count of elements of `size` bytes each, checked against the bytes left before anything
  // is allocated for it.
  size_t count(size_t size) {
    const uint32_t n = u32();
    if (size > 0 && n > left_ / size)
      throw std::runtime_error("the imported model's encoding claims more elements than it holds");
    return n;
  }
  std::string text() {
    std::string s(count(1), '\0');
    raw(s.data(), s.size());
    return s;
  }
  template <class T>
  std::vector<T> array() {
    std::vector<T> v(count(sizeof(T)));
    raw(v.data(), v.size() * sizeof(T));
    return v;
  }
  bool done() const { return left_ == 0; }

 private:
  const char* data_;
  size_t left_;
};

}  // namespace

std::string encode_imported_model(const ImportedModel& model) {
  Writer w;
  w.raw(kMagic, sizeof kMagic);
  w.u32(uint32_t(model.materials.size()));
  for (const auto& m : model.materials) {
    w.text(m.name);
    w.u32(m.has_albedo ? 1u : 0u);
    for (int k = 0; k < 3; ++k) w.f32(m.albedo[k]);
  }
  w.u32(uint32_t(model.meshes.size()));
  for (const auto& mesh : model.meshes) {
    w.text(mesh.name);
    w.u32(mesh.material);
    w.array(mesh.positions);
    w.array(mesh.normals);
    w.array(mesh.face_sizes);
    w.array(mesh.indices);
  }
  w.u32(uint32_t(model.nodes.size()));
  for (const auto& node : model.nodes) {
    w.text(node.name);
    w.i32(node.parent);
    w.raw(&node.transform[0][0], sizeof(float) * 16);
    w.array(node.meshes);
  }
  return w.take();
}

ImportedModel decode_imported_model(const std::string& bytes) {
  Reader r(bytes);
  char magic[sizeof kMagic];
  r.raw(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw std::runtime_error("the imported model's encoding has the wrong header");
  ImportedModel model;
  // The smallest encoding of each element bounds its count (a material: name length,
  // flag and colour; a mesh: name length, material and four array lengths; a node: name
  // length, parent, matrix and mesh count).
  model.materials.resize(r.count(4 + 4 + 12));
  for (auto& m : model.materials) {
    m.name = r.text();
    m.has_albedo = r.u32() != 0;
    for (int k = 0; k < 3; ++k) m.albedo[k] = r.f32();
  }
  model.meshes.resize(r.count(4 + 4 + 16));
  for (auto& mesh : model.meshes) {
    mesh.name = r.text();
    mesh.material = r.u32();
    mesh.positions = r.array<glm::vec3>();
    mesh.normals = r.array<glm::vec3>();
    mesh.face_sizes = r.array<uint32_t>();
    mesh.indices = r.array<uint32_t>();
  }
  model.nodes.resize(r.count(4 + 4 + 64 + 4));
  for (auto& node : model.nodes) {
    node.name = r.text();
    node.parent = r.i32();
    r.raw(&node.transform[0][0], sizeof(float) * 16);
    node.meshes = r.array<uint32_t>();
  }
  if (!r.done()) throw std::runtime_error("the imported model's encoding has trailing bytes");
  return model;
}

}  // namespace ldm
