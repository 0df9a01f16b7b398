#pragma once
// Move-only owners of OpenGL objects, so that every buffer, texture and program is freed
// exactly once and a failing configuration in a sweep leaks nothing into the next one.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "harness/gl/gl_api.h"

namespace ldm {

template <void (*Delete)(GLuint)>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlHandle& operator=(GlHandle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) Delete(id_);
    id_ = 0;
  }
  // Gives up the object without deleting it (another owner frees it).
  GLuint release() { return std::exchange(id_, 0); }

 private:
  GLuint id_ = 0;
};

void delete_gl_buffer(GLuint id);
void delete_gl_texture(GLuint id);
void delete_gl_framebuffer(GLuint id);
void delete_gl_vertex_array(GLuint id);
void delete_gl_program(GLuint id);
void delete_gl_query(GLuint id);

// An immutable-size buffer (glNamedBufferStorage) that remembers its size and a name for
// memory reports.
class GlBuffer {
 public:
  GlBuffer() = default;
  GlBuffer(std::string name, uint64_t bytes, const void* data = nullptr,
           GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
  ~GlBuffer() { drop(); }
  GlBuffer(GlBuffer&& other) noexcept;
  GlBuffer& operator=(GlBuffer&& other) noexcept;
  GLuint id() const { return handle_.id(); }
  uint64_t bytes() const { return bytes_; }
  const std::string& name() const { return name_; }
  explicit operator bool() const { return bool(handle_); }

  void clear_to_zero();
  void clear_to_uint(uint32_t value);
  void upload(const void* data, uint64_t bytes, uint64_t offset = 0);
  void download(void* out, uint64_t bytes, uint64_t offset = 0) const;
  template <typename T>
  std::vector<T> download_all() const {
    std::vector<T> out(bytes_ / sizeof(T));
    download(out.data(), out.size() * sizeof(T));
    return out;
  }
  void bind_storage(GLuint binding) const;
  void bind_atomic_counter(GLuint binding) const;
  // Whether this buffer shares a lender's storage (GlBufferLoanScope).
  bool borrowed() const { return borrowed_; }

 private:
  void drop();  // frees the storage, or hands a borrowed one back
  GlHandle<delete_gl_buffer> handle_;
  uint64_t bytes_ = 0;
  std::string name_;
  bool borrowed_ = false;
};

// Storage lending, for the counting replay (harness/measuring/measurement_session.cpp): a
// second instance of a structure or pass, prepared and run once after the measured frames,
// takes the measured instance's buffers (already allocated at their settled size and
// touched) instead of allocating and first-touching new ones. Buffers allocated while a
// GlBufferOwnerScope is alive are tagged with its owner (an opaque pointer); while a
// GlBufferLoanScope for that owner is alive, a buffer allocated without initial data takes,
// instead of new storage, a live buffer of the owner with the same name, size and flags that
// is not lent yet. The borrower shares that storage (what it writes, the lender then holds)
// and never frees it. Outside these scopes (every measured frame) nothing changes.
class GlBufferOwnerScope {
 public:
  explicit GlBufferOwnerScope(const void* owner);
  ~GlBufferOwnerScope();
  GlBufferOwnerScope(const GlBufferOwnerScope&) = delete;
  GlBufferOwnerScope& operator=(const GlBufferOwnerScope&) = delete;

 private:
  const void* previous_;
};

class GlBufferLoanScope {
 public:
  explicit GlBufferLoanScope(const void* lender);
  ~GlBufferLoanScope();
  GlBufferLoanScope(const GlBufferLoanScope&) = delete;
  GlBufferLoanScope& operator=(const GlBufferLoanScope&) = delete;
  // Buffers lent (and bytes) since the scope began.
  uint64_t buffers_lent() const;
  uint64_t bytes_lent() const;

 private:
  const void* previous_;
  uint64_t buffers_at_start_, bytes_at_start_;
};

class GlTexture2D {
 public:
  GlTexture2D() = default;
  GlTexture2D(GLenum internal_format, int width, int height);
  GLuint id() const { return handle_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  GLenum internal_format() const { return format_; }
  // Bytes of level 0 (the formats the harness allocates; others throw GpuError).
  uint64_t bytes() const;
  // Reads the whole level 0 as floats with `channels` components (GL_RED..GL_RGBA).
  std::vector<float> read_floats(int channels) const;

 private:
  GlHandle<delete_gl_texture> handle_;
  int width_ = 0, height_ = 0;
  GLenum format_ = 0;
};

class GlFramebuffer {
 public:
  GlFramebuffer();
  GLuint id() const { return handle_.id(); }
  void attach_color(int index, const GlTexture2D& texture);
  void attach_depth(const GlTexture2D& texture);
  // A framebuffer with no attachments rasterizes a width x height viewport; fragment
  // shaders write only to storage buffers (the LDM construction passes).
  void set_default_size(int width, int height);
  void check_complete(const char* what) const;

 private:
  GlHandle<delete_gl_framebuffer> handle_;
};

class GlVertexArray {
 public:
  GlVertexArray();
  GLuint id() const { return handle_.id(); }

 private:
  GlHandle<delete_gl_vertex_array> handle_;
};

class GlProgram {
 public:
  GlProgram() = default;
  explicit GlProgram(GLuint id) : handle_(id) {}
  GLuint id() const { return handle_.id(); }
  explicit operator bool() const { return bool(handle_); }
  void use() const;
  GLint uniform(const char* name) const;  // -1 when the uniform is unused or absent
  void set(const char* name, int value) const;
  void set(const char* name, unsigned value) const;
  void set(const char* name, float value) const;
  void set(const char* name, float x, float y, float z) const;
  void set_mat4(const char* name, const float* column_major) const;

 private:
  GlHandle<delete_gl_program> handle_;
};

// Throws GpuError naming `where` if the GL error flag is set.
void check_gl(const char* where);

}  // namespace ldm
