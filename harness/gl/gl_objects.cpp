#include "harness/gl/gl_objects.h"

#include <map>

#include <cstdio>
#include <string>

#include "harness/util/error.h"

namespace ldm {

void delete_gl_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_gl_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_gl_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_gl_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_gl_program(GLuint id) { glDeleteProgram(id); }
void delete_gl_query(GLuint id) { glDeleteQueries(1, &id); }

void check_gl(const char* where) {
  GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  std::string codes;
  while (error != GL_NO_ERROR) {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, " 0x%04x", error);
    codes += buffer;
    error = glGetError();
  }
  if (codes.find("0x0505") != std::string::npos)
    throw GpuError(std::string(where) + ": the device is out of memory (GL_OUT_OF_MEMORY)");
  throw GpuError(std::string(where) + ": GL error" + codes);
}

namespace {

struct Lendable {
  const void* owner;
  std::string name;
  uint64_t bytes;
  GLbitfield flags;
  bool lent = false;
};
// Buffers allocated inside a GlBufferOwnerScope, by GL name, while their owner holds them.
std::map<GLuint, Lendable>& lendable_buffers() {
  static std::map<GLuint, Lendable> buffers;
  return buffers;
}
const void* g_buffer_owner = nullptr;
const void* g_buffer_lender = nullptr;
uint64_t g_buffers_lent = 0, g_bytes_lent = 0;

}  // namespace

GlBufferOwnerScope::GlBufferOwnerScope(const void* owner) : previous_(g_buffer_owner) {
  g_buffer_owner = owner;
}
GlBufferOwnerScope::~GlBufferOwnerScope() { g_buffer_owner = previous_; }

GlBufferLoanScope::GlBufferLoanScope(const void* lender)
    : previous_(g_buffer_lender), buffers_at_start_(g_buffers_lent), bytes_at_start_(g_bytes_lent) {
  g_buffer_lender = lender;
}
GlBufferLoanScope::~GlBufferLoanScope() { g_buffer_lender = previous_; }
uint64_t GlBufferLoanScope::buffers_lent() const { return g_buffers_lent - buffers_at_start_; }
uint64_t GlBufferLoanScope::bytes_lent() const { return g_bytes_lent - bytes_at_start_; }

GlBuffer::GlBuffer(GlBuffer&& other) noexcept
    : handle_(std::move(other.handle_)),
      bytes_(other.bytes_),
      name_(std::move(other.name_)),
      borrowed_(std::exchange(other.borrowed_, false)) {}

GlBuffer& GlBuffer::operator=(GlBuffer&& other) noexcept {
  if (this != &other) {
    drop();
    handle_ = std::move(other.handle_);
    bytes_ = other.bytes_;
    name_ = std::move(other.name_);
    borrowed_ = std::exchange(other.borrowed_, false);
  }
  return *this;
}

void GlBuffer::drop() {
  const GLuint id = handle_.id();
  if (!id) return;
  auto& lendable = lendable_buffers();
  const auto it = lendable.find(id);
  if (borrowed_) {  // the lender frees it
    if (it != lendable.end()) it->second.lent = false;
    handle_.release();
    borrowed_ = false;
    return;
  }
  if (it != lendable.end()) lendable.erase(it);
  handle_.reset();
}

GlBuffer::GlBuffer(std::string name, uint64_t bytes, const void* data, GLbitfield flags)
    : bytes_(bytes), name_(std::move(name)) {
  if (g_buffer_lender && !data) {
    for (auto& [id, buffer] : lendable_buffers())
      if (buffer.owner == g_buffer_lender && !buffer.lent && buffer.bytes == bytes &&
          buffer.flags == flags && buffer.name == name_) {
        buffer.lent = true;
        handle_ = GlHandle<delete_gl_buffer>(id);
        borrowed_ = true;
        ++g_buffers_lent;
        g_bytes_lent += bytes;
        return;
      }
  }
  GLuint id = 0;
  glCreateBuffers(1, &id);
  handle_ = GlHandle<delete_gl_buffer>(id);
  // A zero-byte storage is invalid; keep one word so that bindings stay legal.
  glNamedBufferStorage(id, GLsizeiptr(bytes ? bytes : 4), data, flags);
  check_gl(("allocating buffer '" + name_ + "'").c_str());
  if (g_buffer_owner) lendable_buffers()[id] = Lendable{g_buffer_owner, name_, bytes, flags};
}

void GlBuffer::clear_to_zero() { clear_to_uint(0u); }

void GlBuffer::clear_to_uint(uint32_t value) {
  glClearNamedBufferData(id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
}

void GlBuffer::upload(const void* data, uint64_t bytes, uint64_t offset) {
  glNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

void GlBuffer::download(void* out, uint64_t bytes, uint64_t offset) const {
  if (bytes == 0) return;
  glGetNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), out);
  check_gl(("reading back buffer '" + name_ + "'").c_str());
}

void GlBuffer::bind_storage(GLuint binding) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id());
}

void GlBuffer::bind_atomic_counter(GLuint binding) const {
  glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, binding, id());
}

GlTexture2D::GlTexture2D(GLenum internal_format, int width, int height)
    : width_(width), height_(height), format_(internal_format) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  handle_ = GlHandle<delete_gl_texture>(id);
  glTextureStorage2D(id, 1, internal_format, width, height);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  check_gl("allocating texture");
}

uint64_t GlTexture2D::bytes() const {
  uint64_t texel = 0;
  switch (format_) {
    case GL_RGBA32F: texel = 16; break;
    case GL_RG32F: texel = 8; break;
    case GL_R32F: case GL_R32UI: case GL_DEPTH_COMPONENT32F: case GL_RGBA8: texel = 4; break;
    default: throw GpuError("GlTexture2D::bytes: texel size of format " + std::to_string(format_) +
                            " unknown");
  }
  return texel * uint64_t(width_) * uint64_t(height_);
}

std::vector<float> GlTexture2D::read_floats(int channels) const {
  static const GLenum formats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  std::vector<float> out(size_t(width_) * size_t(height_) * size_t(channels));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(id(), 0, formats[channels - 1], GL_FLOAT, GLsizei(out.size() * sizeof(float)),
                    out.data());
  check_gl("reading back texture");
  return out;
}

GlFramebuffer::GlFramebuffer() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  handle_ = GlHandle<delete_gl_framebuffer>(id);
}

void GlFramebuffer::attach_color(int index, const GlTexture2D& texture) {
  glNamedFramebufferTexture(id(), GLenum(GL_COLOR_ATTACHMENT0 + index), texture.id(), 0);
}

void GlFramebuffer::attach_depth(const GlTexture2D& texture) {
  glNamedFramebufferTexture(id(), GL_DEPTH_ATTACHMENT, texture.id(), 0);
}

void GlFramebuffer::set_default_size(int width, int height) {
  glNamedFramebufferParameteri(id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
  glNamedFramebufferParameteri(id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
}

void GlFramebuffer::check_complete(const char* what) const {
  GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char buffer[128];
    std::snprintf(buffer, sizeof buffer, "%s: framebuffer incomplete (0x%04x)", what, status);
    throw GpuError(buffer);
  }
}

GlVertexArray::GlVertexArray() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  handle_ = GlHandle<delete_gl_vertex_array>(id);
}

void GlProgram::use() const { glUseProgram(id()); }
GLint GlProgram::uniform(const char* name) const { return glGetUniformLocation(id(), name); }
void GlProgram::set(const char* name, int value) const {
  glProgramUniform1i(id(), uniform(name), value);
}
void GlProgram::set(const char* name, unsigned value) const {
  glProgramUniform1ui(id(), uniform(name), value);
}
void GlProgram::set(const char* name, float value) const {
  glProgramUniform1f(id(), uniform(name), value);
}
void GlProgram::set(const char* name, float x, float y, float z) const {
  glProgramUniform3f(id(), uniform(name), x, y, z);
}
void GlProgram::set_mat4(const char* name, const float* column_major) const {
  glProgramUniformMatrix4fv(id(), uniform(name), 1, GL_FALSE, column_major);
}

}  // namespace ldm
