#pragma once
// Move-only RAII wrappers of the OpenGL objects ibfvs uses (in the manner of
// Magnum's GL library): copy deleted, move noexcept, release() hands the name
// over, a default-constructed object owns nothing. All use direct state access
// (OpenGL 4.5), so creating or filling an object never disturbs bindings.
// Names are plain unsigned ints here so that this header needs no GL loader.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace ibfvs::gl {

/// Owns one GL name; `Deleter` frees it. Base of every wrapper below.
template <void (*Deleter)(unsigned)>
class Object {
 public:
  Object() = default;
  explicit Object(unsigned id) : id_(id) {}
  ~Object() { reset(); }
  Object(Object&& o) noexcept : id_(std::exchange(o.id_, 0u)) {}
  Object& operator=(Object&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0u);
    }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;

  [[nodiscard]] unsigned id() const { return id_; }
  [[nodiscard]] explicit operator bool() const { return id_ != 0; }
  /// Gives up ownership; the caller must delete the name.
  unsigned release() { return std::exchange(id_, 0u); }

 protected:
  void reset() {
    if (id_) Deleter(id_);
    id_ = 0;
  }

 private:
  unsigned id_ = 0;
};

void delete_buffer(unsigned id);
void delete_vertex_array(unsigned id);
void delete_texture(unsigned id);
void delete_renderbuffer(unsigned id);
void delete_framebuffer(unsigned id);
void delete_program(unsigned id);

/// Immutable-storage buffer (glNamedBufferStorage).
class Buffer : public Object<delete_buffer> {
 public:
  Buffer() = default;
  /// Creates a buffer holding `bytes`; `dynamic` allows later update().
  Buffer(std::span<const std::byte> bytes, bool dynamic = false);
  void update(std::size_t offset, std::span<const std::byte> bytes);
  [[nodiscard]] std::size_t size() const { return size_; }

 private:
  std::size_t size_ = 0;
};

/// Vertex array object describing float attributes in one or more buffers.
class VertexArray : public Object<delete_vertex_array> {
 public:
  using Object::Object;
  static VertexArray create();
  /// Attribute `location` reads `components` floats at `offset` in `buffer`,
  /// `stride` bytes per vertex, through binding point `binding`.
  void attribute(unsigned location, const Buffer& buffer, unsigned binding, int components,
                 std::size_t offset, std::size_t stride);
  /// Same with normalised signed 10-10-10-2 data (GL_INT_2_10_10_10_REV).
  void attribute_packed_snorm(unsigned location, const Buffer& buffer, unsigned binding,
                              std::size_t offset, std::size_t stride);
  void index_buffer(const Buffer& buffer);
  void bind() const;
};

/// Pixel formats used by ibfvs.
enum class Format {
  RGBA8,    ///< output images
  RGBA16F,  ///< the texture image F_t (16-bit float per channel)
  R16F,     ///< one 16-bit float channel
  RG16F,    ///< F_t while it is grey (value, depth); the image-space flow
  RGBA32F,  ///< exact read-back in tests
  R32F,     ///< noise phases
  Depth24,  ///< depth (a renderbuffer, or a texture read with texelFetch)
};

/// 2D texture with immutable storage, linear filtering, clamped edges.
class Texture2D : public Object<delete_texture> {
 public:
  Texture2D() = default;
  Texture2D(int width, int height, Format format, bool linear = true);
  /// Uploads float data (channels matching the format: 1, 2 or 4) for the whole texture.
  void upload_float(std::span<const float> data, int channels);
  void bind(unsigned unit) const;
  /// Repeat (true) or clamp to the edge (false, the default) outside [0, 1].
  void set_repeat(bool repeat);
  /// Reads the whole texture as floats, `channels` per pixel (1, 2 or 4), rows bottom-up.
  void read_float(std::span<float> out, int channels) const;
  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  [[nodiscard]] Format format() const { return format_; }

 private:
  int width_ = 0, height_ = 0;
  Format format_ = Format::RGBA8;
};

/// The largest width and height of an image the current context can render
/// to and sample: the least of GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE
/// and GL_MAX_VIEWPORT_DIMS.
int max_image_size();

/// Throws SettingError(key, ...) when width x height is more than
/// max_image_size(), naming the limit, the renderer and the memory it would
/// need, before anything is allocated.
void check_image_size(int width, int height, const std::string& key);

/// Renderbuffer (used for depth).
class Renderbuffer : public Object<delete_renderbuffer> {
 public:
  Renderbuffer() = default;
  Renderbuffer(int width, int height, Format format);
};

/// Framebuffer object with colour attachments and a depth attachment.
class Framebuffer : public Object<delete_framebuffer> {
 public:
  using Object::Object;
  static Framebuffer create();
  void attach_color(unsigned index, const Texture2D& texture);
  void attach_depth(const Renderbuffer& depth);
  /// A depth texture (Format::Depth24), for passes that read the depth later.
  void attach_depth(const Texture2D& depth);
  /// Enables colour attachments 0..count-1 as draw buffers; throws GraphicsError if incomplete.
  void finish(unsigned color_count);
  void bind() const;
  void clear_color(unsigned index, const glm::vec4& rgba);
  void clear_depth(float depth = 1.0f);
  /// Reads colour attachment `index` as RGBA8, rows bottom-up.
  void read_rgba8(unsigned index, int width, int height, std::span<std::uint8_t> out) const;
  /// Reads the depth attachment as floats in [0, 1] (1: nothing drawn), rows bottom-up.
  void read_depth(int width, int height, std::span<float> out) const;
  /// Copies colour attachment `index` (width x height) into the rectangle
  /// (x0, y0)-(x1, y1) of the default framebuffer (the window), linearly filtered.
  void blit_to_default(unsigned index, int width, int height, int x0, int y0, int x1, int y1) const;
};

/// Linked shader program, with uniform setters by name (locations cached by GL).
class Program : public Object<delete_program> {
 public:
  Program() = default;
  /// Compiles and links; throws GraphicsError with the info log.
  Program(const std::string& vertex_source, const std::string& fragment_source);
  void use() const;
  [[nodiscard]] int location(const char* name) const;
  void set(int location, float v) const;
  void set(int location, std::span<const float> values) const;  ///< a float array
  void set(int location, int v) const;
  void set(int location, std::uint32_t v) const;
  void set(int location, const glm::vec2& v) const;
  void set(int location, const glm::ivec2& v) const;
  void set(int location, const glm::vec3& v) const;
  void set(int location, const glm::mat4& v) const;
};

/// Global render state for the IBFVS passes.
void set_viewport(int width, int height);
/// The viewport at `origin` (its lower left corner in the bound framebuffer).
void set_viewport(glm::ivec2 origin, int width, int height);
/// The current viewport's lower left corner (where a host draws this view
/// in its framebuffer: a tile of its window).
[[nodiscard]] glm::ivec2 viewport_origin();
/// Binds the default framebuffer (the window), sets the viewport to all of it
/// and clears it to `rgba`.
void clear_window(int width, int height, const glm::vec4& rgba);
void enable_depth_test(bool on);
/// on: draws pass only where something nearer than the far plane was drawn
/// (a triangle on the far plane, depth test GREATER), the depth left as it
/// is; off: back to enable_depth_test(true) and depth writes.
void test_depth_behind_surface(bool on);
/// on: draws over what is there where nothing nearer was drawn (depth test
/// LEQUAL, no depth writes), its colour only (the alpha channel stays), no
/// face culling; off: back to enable_depth_test(true), depth and alpha writes.
void draw_over(bool on);
/// Draws only inside `box` (x, y, width, height in pixels), or everywhere.
void scissor(bool on, const glm::ivec4& box = glm::ivec4(0));
/// weight > 0: draws blend as weight * new + (1 - weight) * old (a running
/// average); 0: blending off.
void set_running_average(float weight);
/// 0: draw every face; +1: cull clockwise (back) faces; -1: cull counter-clockwise ones.
void set_face_culling(int orientation);
void draw_triangles(std::size_t index_count, bool index32);
/// One triangle of three vertices with no attributes (the shader places them
/// from gl_VertexID), for full-viewport passes; `vao` is any vertex array.
void draw_attributeless_triangle(const VertexArray& vao);
/// State for ibfvs's own passes into its own framebuffers whatever a host
/// left: no scissor or stencil test, all colour channels and depth written.
/// SavedState puts the host's back.
void prepare_own_draw();
/// State for drawing into a host's framebuffer (the one bound, its viewport):
/// depth test LEQUAL with depth writes, all colour channels, no blending,
/// culling or scissor. SavedState puts the host's back.
void prepare_host_draw();
void finish();

/// Saves the bindings and state a host application may rely on (draw and
/// read framebuffers, viewport, program, vertex array, the 2D textures of
/// units 0-4 and the active one, depth function and writes, colour mask,
/// culling, blending, scissor, stencil, polygon offset, clip distances) and
/// restores them when it goes out of
/// scope: drawing inside somebody else's context (ParaView's) leaves it as
/// it was.
class SavedState {
 public:
  SavedState();
  ~SavedState();
  SavedState(const SavedState&) = delete;
  SavedState& operator=(const SavedState&) = delete;

 private:
  int draw_framebuffer_ = 0, read_framebuffer_ = 0, program_ = 0, vertex_array_ = 0;
  int texture_ = 0, viewport_[4] = {0, 0, 0, 0}, scissor_box_[4] = {0, 0, 0, 0};
  static constexpr int kSavedUnits = 8;  // units 0-7, which ibfvs binds
  int active_texture_ = 0, unit_textures_[kSavedUnits] = {};
  int depth_func_ = 0, cull_face_mode_ = 0, front_face_ = 0;
  unsigned char depth_mask_ = 1, color_mask_[4] = {1, 1, 1, 1};
  unsigned capabilities_ = 0;  // bit i: kCapabilities[i] (objects.cpp) was on
  int blend_func_[4] = {1, 0, 1, 0};
  float blend_color_[4] = {0, 0, 0, 0};
};

}  // namespace ibfvs::gl
