#include "ibfvs/gl/objects.h"

#include <array>

#include <algorithm>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/limits.h"
#include "ibfvs/gl/context.h"

namespace ibfvs::gl {

void delete_buffer(unsigned id) {
  glDeleteBuffers(1, &id);
}
void delete_vertex_array(unsigned id) {
  glDeleteVertexArrays(1, &id);
}
void delete_texture(unsigned id) {
  glDeleteTextures(1, &id);
}
void delete_renderbuffer(unsigned id) {
  glDeleteRenderbuffers(1, &id);
}
void delete_framebuffer(unsigned id) {
  glDeleteFramebuffers(1, &id);
}
void delete_program(unsigned id) {
  glDeleteProgram(id);
}

namespace {

struct FormatInfo {
  GLenum internal;
  GLenum format;
};

FormatInfo info(Format f) {
  switch (f) {
    case Format::RGBA8:
      return {GL_RGBA8, GL_RGBA};
    case Format::RGBA16F:
      return {GL_RGBA16F, GL_RGBA};
    case Format::R16F:
      return {GL_R16F, GL_RED};
    case Format::RG16F:
      return {GL_RG16F, GL_RG};
    case Format::RGBA32F:
      return {GL_RGBA32F, GL_RGBA};
    case Format::R32F:
      return {GL_R32F, GL_RED};
    case Format::Depth24:
      return {GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT};
  }
  return {GL_RGBA8, GL_RGBA};
}

GLenum channel_format(int channels) {
  switch (channels) {
    case 1:
      return GL_RED;
    case 2:
      return GL_RG;
    case 4:
      return GL_RGBA;
    default:
      throw GraphicsError("texture transfer: 1, 2 or 4 channels, not " + std::to_string(channels));
  }
}

// Pixel transfers between client memory and GL, whatever a host left bound
// (ParaView's VTK may leave a pixel buffer object bound, or row lengths and
// skips set): plain tightly packed rows for the transfer, the host's
// settings back afterwards.
class PixelTransfer {
 public:
  explicit PixelTransfer(bool pack) : pack_(pack) {
    glGetIntegerv(buffer_binding(), &buffer_);
    for (std::size_t i = 0; i < names().size(); ++i) glGetIntegerv(names()[i], &values_[i]);
    glBindBuffer(target(), 0);
    for (std::size_t i = 0; i < names().size(); ++i)
      glPixelStorei(names()[i], names()[i] == alignment() ? 4 : 0);
  }
  ~PixelTransfer() {
    glBindBuffer(target(), static_cast<GLuint>(buffer_));
    for (std::size_t i = 0; i < names().size(); ++i) glPixelStorei(names()[i], values_[i]);
  }
  PixelTransfer(const PixelTransfer&) = delete;
  PixelTransfer& operator=(const PixelTransfer&) = delete;

 private:
  GLenum target() const { return pack_ ? GL_PIXEL_PACK_BUFFER : GL_PIXEL_UNPACK_BUFFER; }
  GLenum buffer_binding() const {
    return pack_ ? GL_PIXEL_PACK_BUFFER_BINDING : GL_PIXEL_UNPACK_BUFFER_BINDING;
  }
  GLenum alignment() const { return pack_ ? GL_PACK_ALIGNMENT : GL_UNPACK_ALIGNMENT; }
  const std::array<GLenum, 5>& names() const {
    static const std::array<GLenum, 5> pack = {GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH,
                                               GL_PACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS,
                                               GL_PACK_IMAGE_HEIGHT};
    static const std::array<GLenum, 5> unpack = {GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH,
                                                 GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS,
                                                 GL_UNPACK_IMAGE_HEIGHT};
    return pack_ ? pack : unpack;
  }
  bool pack_;
  GLint buffer_ = 0;
  std::array<GLint, 5> values_{};
};

// The capabilities ibfvs's passes switch, which SavedState saves and puts
// back: a host's (ParaView's) may have any of them on. The clip distances are
// VTK's clipping planes (6).
constexpr std::array<GLenum, 12> kCapabilities = {
    GL_DEPTH_TEST,     GL_CULL_FACE,           GL_BLEND,          GL_SCISSOR_TEST,
    GL_STENCIL_TEST,   GL_POLYGON_OFFSET_FILL, GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE1,
    GL_CLIP_DISTANCE2, GL_CLIP_DISTANCE3,      GL_CLIP_DISTANCE4, GL_CLIP_DISTANCE5};

void set_capability(GLenum capability, bool on) {
  if (on)
    glEnable(capability);
  else
    glDisable(capability);
}

// Off for every capability but depth testing and culling, which each pass sets.
void disable_host_capabilities() {
  for (const GLenum c : kCapabilities)
    if (c != GL_DEPTH_TEST && c != GL_CULL_FACE) glDisable(c);
}

}  // namespace

Buffer::Buffer(std::span<const std::byte> bytes, bool dynamic) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  static_cast<Object&>(*this) = Object(id);
  size_ = bytes.size();
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes.size()), bytes.data(),
                       dynamic ? GL_DYNAMIC_STORAGE_BIT : 0);
}

void Buffer::update(std::size_t offset, std::span<const std::byte> bytes) {
  glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes.size()),
                       bytes.data());
}

VertexArray VertexArray::create() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  return VertexArray(id);
}

void VertexArray::attribute(unsigned location, const Buffer& buffer, unsigned binding,
                            int components, std::size_t offset, std::size_t stride) {
  glVertexArrayVertexBuffer(id(), binding, buffer.id(), static_cast<GLintptr>(offset),
                            static_cast<GLsizei>(stride));
  glVertexArrayAttribFormat(id(), location, components, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(id(), location, binding);
  glEnableVertexArrayAttrib(id(), location);
}

void VertexArray::attribute_packed_snorm(unsigned location, const Buffer& buffer, unsigned binding,
                                         std::size_t offset, std::size_t stride) {
  glVertexArrayVertexBuffer(id(), binding, buffer.id(), static_cast<GLintptr>(offset),
                            static_cast<GLsizei>(stride));
  glVertexArrayAttribFormat(id(), location, 4, GL_INT_2_10_10_10_REV, GL_TRUE, 0);
  glVertexArrayAttribBinding(id(), location, binding);
  glEnableVertexArrayAttrib(id(), location);
}

void VertexArray::index_buffer(const Buffer& buffer) {
  glVertexArrayElementBuffer(id(), buffer.id());
}
void VertexArray::bind() const {
  glBindVertexArray(id());
}

int max_image_size() {
  GLint texture = 0, renderbuffer = 0, viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  return std::min({texture, renderbuffer, viewport[0], viewport[1]});
}

void check_image_size(int width, int height, const std::string& key) {
  const int most = max_image_size();
  if (width <= most && height <= most) return;
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  throw SettingError(key, std::to_string(width) + "x" + std::to_string(height) +
                              " is larger than this GL implementation's largest image, " +
                              std::to_string(most) + "x" + std::to_string(most) + " (" +
                              (renderer ? renderer : "?") + "); it would need about " +
                              format_bytes(image_bytes(width, height)) + " of memory");
}

Texture2D::Texture2D(int width, int height, Format format, bool linear)
    : width_(width), height_(height), format_(format) {
  if (width > max_image_size() || height > max_image_size())
    throw GraphicsError("texture of " + std::to_string(width) + "x" + std::to_string(height) +
                        " pixels: larger than this GL implementation's largest, " +
                        std::to_string(max_image_size()));
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  static_cast<Object&>(*this) = Object(id);
  glTextureStorage2D(id, 1, info(format).internal, width, height);
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, filter);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, filter);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void Texture2D::set_repeat(bool repeat) {
  const GLint mode = repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  glTextureParameteri(id(), GL_TEXTURE_WRAP_S, mode);
  glTextureParameteri(id(), GL_TEXTURE_WRAP_T, mode);
}

void Texture2D::upload_float(std::span<const float> data, int channels) {
  const std::size_t need = static_cast<std::size_t>(width_) * height_ * channels;
  if (data.size() < need) throw GraphicsError("texture upload: not enough data");
  const PixelTransfer transfer(false);
  glTextureSubImage2D(id(), 0, 0, 0, width_, height_, channel_format(channels), GL_FLOAT,
                      data.data());
}

void Texture2D::bind(unsigned unit) const {
  glBindTextureUnit(unit, id());
}

void Texture2D::read_float(std::span<float> out, int channels) const {
  const std::size_t need = static_cast<std::size_t>(width_) * height_ * channels;
  if (out.size() < need) throw GraphicsError("texture read: buffer too small");
  const PixelTransfer transfer(true);
  glGetTextureImage(id(), 0, channel_format(channels), GL_FLOAT,
                    static_cast<GLsizei>(need * sizeof(float)), out.data());
}

Renderbuffer::Renderbuffer(int width, int height, Format format) {
  if (width > max_image_size() || height > max_image_size())
    throw GraphicsError("renderbuffer of " + std::to_string(width) + "x" + std::to_string(height) +
                        " pixels: larger than this GL implementation's largest, " +
                        std::to_string(max_image_size()));
  GLuint id = 0;
  glCreateRenderbuffers(1, &id);
  static_cast<Object&>(*this) = Object(id);
  glNamedRenderbufferStorage(id, info(format).internal, width, height);
}

Framebuffer Framebuffer::create() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  return Framebuffer(id);
}

void Framebuffer::attach_color(unsigned index, const Texture2D& texture) {
  glNamedFramebufferTexture(id(), GL_COLOR_ATTACHMENT0 + index, texture.id(), 0);
}

void Framebuffer::attach_depth(const Renderbuffer& depth) {
  glNamedFramebufferRenderbuffer(id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
}

void Framebuffer::attach_depth(const Texture2D& depth) {
  glNamedFramebufferTexture(id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
}

void Framebuffer::finish(unsigned color_count) {
  std::vector<GLenum> buffers(color_count);
  for (unsigned i = 0; i < color_count; ++i) buffers[i] = GL_COLOR_ATTACHMENT0 + i;
  glNamedFramebufferDrawBuffers(id(), static_cast<GLsizei>(color_count), buffers.data());
  const GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GraphicsError("framebuffer incomplete (status 0x" + std::to_string(status) + ")");
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, id());
}

void Framebuffer::clear_color(unsigned index, const glm::vec4& rgba) {
  glClearNamedFramebufferfv(id(), GL_COLOR, static_cast<GLint>(index), glm::value_ptr(rgba));
}

void Framebuffer::clear_depth(float depth) {
  glClearNamedFramebufferfv(id(), GL_DEPTH, 0, &depth);
}

void Framebuffer::read_rgba8(unsigned index, int width, int height,
                             std::span<std::uint8_t> out) const {
  const std::size_t need = static_cast<std::size_t>(width) * height * 4;
  if (out.size() < need) throw GraphicsError("framebuffer read: buffer too small");
  glNamedFramebufferReadBuffer(id(), GL_COLOR_ATTACHMENT0 + index);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, id());
  const PixelTransfer transfer(true);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
}

void Framebuffer::blit_to_default(unsigned index, int width, int height, int x0, int y0, int x1,
                                  int y1) const {
  glNamedFramebufferReadBuffer(id(), GL_COLOR_ATTACHMENT0 + index);
  glBlitNamedFramebuffer(id(), 0, 0, 0, width, height, x0, y0, x1, y1, GL_COLOR_BUFFER_BIT,
                         GL_LINEAR);
}

void Framebuffer::read_depth(int width, int height, std::span<float> out) const {
  const std::size_t need = static_cast<std::size_t>(width) * height;
  if (out.size() < need) throw GraphicsError("framebuffer depth read: buffer too small");
  glBindFramebuffer(GL_READ_FRAMEBUFFER, id());
  const PixelTransfer transfer(true);
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, out.data());
}

namespace {

GLuint compile(GLenum type, const std::string& source) {
  const GLuint shader = glCreateShader(type);
  const char* src = source.c_str();
  glShaderSource(shader, 1, &src, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
    glGetShaderInfoLog(shader, len, nullptr, log.data());
    glDeleteShader(shader);
    // KHR_debug may report the same failure; the exception carries it.
    (void)take_recorded_gl_errors();
    throw GraphicsError(std::string(type == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                        " shader does not compile: " + log);
  }
  return shader;
}

}  // namespace

Program::Program(const std::string& vertex_source, const std::string& fragment_source) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex_source);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  const GLuint program = glCreateProgram();
  static_cast<Object&>(*this) = Object(program);
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDetachShader(program, vs);
  glDetachShader(program, fs);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
    glGetProgramInfoLog(program, len, nullptr, log.data());
    (void)take_recorded_gl_errors();
    throw GraphicsError("shader program does not link: " + log);
  }
}

void Program::use() const {
  glUseProgram(id());
}
int Program::location(const char* name) const {
  return glGetUniformLocation(id(), name);
}
void Program::set(int loc, std::span<const float> values) const {
  glProgramUniform1fv(id(), loc, static_cast<GLsizei>(values.size()), values.data());
}

void Program::set(int loc, float v) const {
  glProgramUniform1f(id(), loc, v);
}
void Program::set(int loc, int v) const {
  glProgramUniform1i(id(), loc, v);
}
void Program::set(int loc, std::uint32_t v) const {
  glProgramUniform1ui(id(), loc, v);
}
void Program::set(int loc, const glm::vec2& v) const {
  glProgramUniform2fv(id(), loc, 1, glm::value_ptr(v));
}
void Program::set(int loc, const glm::ivec2& v) const {
  glProgramUniform2iv(id(), loc, 1, glm::value_ptr(v));
}
void Program::set(int loc, const glm::vec3& v) const {
  glProgramUniform3fv(id(), loc, 1, glm::value_ptr(v));
}
void Program::set(int loc, const glm::mat4& v) const {
  glProgramUniformMatrix4fv(id(), loc, 1, GL_FALSE, glm::value_ptr(v));
}

void clear_window(int width, int height, const glm::vec4& rgba) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glClearColor(rgba.r, rgba.g, rgba.b, rgba.a);
  glClear(GL_COLOR_BUFFER_BIT);
}

void set_viewport(int width, int height) {
  glViewport(0, 0, width, height);
}
void set_viewport(glm::ivec2 origin, int width, int height) {
  glViewport(origin.x, origin.y, width, height);
}
glm::ivec2 viewport_origin() {
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, viewport);
  return {viewport[0], viewport[1]};
}
void set_face_culling(int orientation) {
  if (orientation == 0) {
    glDisable(GL_CULL_FACE);
    return;
  }
  glEnable(GL_CULL_FACE);
  glCullFace(orientation > 0 ? GL_BACK : GL_FRONT);
}

void set_running_average(float weight) {
  if (weight > 0.0f) {
    glEnable(GL_BLEND);
    glBlendColor(0.0f, 0.0f, 0.0f, weight);
    glBlendFunc(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
  } else {
    glDisable(GL_BLEND);
  }
}

void enable_depth_test(bool on) {
  if (on) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
}
void test_depth_behind_surface(bool on) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(on ? GL_GREATER : GL_LESS);
  glDepthMask(on ? GL_FALSE : GL_TRUE);
}

void draw_over(bool on) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(on ? GL_LEQUAL : GL_LESS);
  glDepthMask(on ? GL_FALSE : GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, on ? GL_FALSE : GL_TRUE);
  if (on) glDisable(GL_CULL_FACE);
}

void scissor(bool on, const glm::ivec4& box) {
  set_capability(GL_SCISSOR_TEST, on);
  if (on) glScissor(box.x, box.y, box.z, box.w);
}

void draw_attributeless_triangle(const VertexArray& vao) {
  vao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void draw_triangles(std::size_t index_count, bool index32) {
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count),
                 index32 ? GL_UNSIGNED_INT : GL_UNSIGNED_SHORT, nullptr);
}
void prepare_own_draw() {
  // Blending off above all: a host's (ParaView's) would blend the noise
  // grid pass, which writes no alpha, into nothing.
  disable_host_capabilities();
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void prepare_host_draw() {
  prepare_own_draw();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);
}

void finish() {
  glFinish();
}

SavedState::SavedState() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_SCISSOR_BOX, scissor_box_);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
  for (int u = 0; u < kSavedUnits; ++u) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + u));
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &unit_textures_[u]);
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
  glGetIntegerv(GL_CULL_FACE_MODE, &cull_face_mode_);
  glGetIntegerv(GL_FRONT_FACE, &front_face_);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask_);
  for (std::size_t i = 0; i < kCapabilities.size(); ++i)
    if (glIsEnabled(kCapabilities[i]) == GL_TRUE) capabilities_ |= 1u << i;
  glGetIntegerv(GL_BLEND_SRC_RGB, &blend_func_[0]);
  glGetIntegerv(GL_BLEND_DST_RGB, &blend_func_[1]);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_func_[2]);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_func_[3]);
  glGetFloatv(GL_BLEND_COLOR, blend_color_);
}

SavedState::~SavedState() {
  // A name bound before may have been deleted since (by the host, or by us
  // when it was ours): binding it again would be an error, 0 is not.
  const auto alive = [](int name, GLboolean (*is)(GLuint)) {
    return name != 0 && is(static_cast<GLuint>(name)) ? static_cast<GLuint>(name) : 0u;
  };
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, alive(draw_framebuffer_, glIsFramebuffer));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, alive(read_framebuffer_, glIsFramebuffer));
  glUseProgram(alive(program_, glIsProgram));
  glBindVertexArray(alive(vertex_array_, glIsVertexArray));
  for (int u = 0; u < kSavedUnits; ++u) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + u));
    glBindTexture(GL_TEXTURE_2D, alive(unit_textures_[u], glIsTexture));
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glBindTexture(GL_TEXTURE_2D, alive(texture_, glIsTexture));
  glDepthFunc(static_cast<GLenum>(depth_func_));
  glCullFace(static_cast<GLenum>(cull_face_mode_));
  glFrontFace(static_cast<GLenum>(front_face_));
  glDepthMask(depth_mask_);
  glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
  for (std::size_t i = 0; i < kCapabilities.size(); ++i)
    set_capability(kCapabilities[i], (capabilities_ & (1u << i)) != 0);
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glScissor(scissor_box_[0], scissor_box_[1], scissor_box_[2], scissor_box_[3]);
  glBlendFuncSeparate(static_cast<GLenum>(blend_func_[0]), static_cast<GLenum>(blend_func_[1]),
                      static_cast<GLenum>(blend_func_[2]), static_cast<GLenum>(blend_func_[3]));
  glBlendColor(blend_color_[0], blend_color_[1], blend_color_[2], blend_color_[3]);
}

}  // namespace ibfvs::gl
