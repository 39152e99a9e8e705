#pragma once
// The IBFVS texture synthesis on OpenGL 4.5 (paper sections 3.2-3.3,
// equations 10-13). A frame runs these passes, each compiled with only the
// features in use (shaders.h; their samplers' units: texture_units.h), each
// an object that owns its program and uniforms (passes.h), drawing into the
// images that one frame hands the next (feedback_images.h: F_t, the taps)
// and into the frame's targets, through each pass's framebuffer
// (frame_targets.h: F, the depth, the G-buffer); the renderer runs them in
// order:
//
//   grid      G_ij = w(v_g k + phi_ij) once per grid point        (eq. 8)
//   IBFVS     the mesh drawn once; per pixel:                       (steps 2-7)
//               t = T(r - v dt), homogeneous per vertex, divided per pixel (eq. 13)
//               F_t'(x) = (1 - alpha) F_t(t(x)) + alpha G(x; k)     (eq. 10)
//                 with fresh noise where t(x) is not on the same surface in
//                 the last frame (its depth is stored with F_t)
//               F(x) = beta D(F_t')(x) + (1 - beta) F_s(x)          (eq. 11)
//             or, deferred (pass_settings.h: deferred_pass), in two halves:
//             the mesh writes t(x), depths and shading into two images
//             (G-buffer), and a full-screen resolve over the surface's
//             pixels does the rest: on a CPU rasteriser most fragments of
//             small triangles never reach the costly half
//   display   with a tap texture (pass_settings.h: tap_texture): D, the
//             filter along the flow and the contrast stage (section 3.4),
//             and F, once per pixel of the surface; else D runs in the
//             IBFVS pass. D is for display only: the feedback loop stays
//             the paper's
//   swap      F_t and F_t' (ping-pong)                              (step 6)
//   stats     every kStatsEvery frames, with contrast: the mean and
//             deviation of D over the surface, blended into a running
//             average the next frames' contrast stage reads
//   host      draw_to_host: F and its depth into a host's framebuffer
//
// The depth test keeps only the nearest surface per pixel, so gamma = alpha
// exactly on the projected surface and 0 on the background (eq. 12) without
// the paper's reversed-z noise rectangle. Beyond the 2003 implementation:
// texture coordinates on the GPU (moving camera costs nothing), evaluated
// exactly per fragment so large triangles in perspective do not bend the warp
// (section 3.9), F_t in 16-bit float, and an option to advect with the
// previous frame's transform (section 3.7), which takes a moving surface's
// points where the last frame drew them too: t = T_{k-1}(r_{k-1} - v dt),
// so the texture follows the camera's motion and the surface's alike
// (set_surface_steps; replace_mesh for a surface whose triangles change).

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/geometry/rigid_motion.h"
#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/render_settings.h"
#include "ibfvs/core/texture/noise.h"
#include "ibfvs/core/texture/reference.h"
#include "ibfvs/gl/objects.h"
#include "ibfvs/render/feedback_images.h"
#include "ibfvs/render/frame_plan.h"
#include "ibfvs/render/frame_targets.h"
#include "ibfvs/render/passes.h"
#include "ibfvs/render/shaders.h"
#include "ibfvs/render/surface_buffers.h"

namespace ibfvs {

/// The IBFVS engine. Needs a current OpenGL 4.5 context for its whole life.
class IbfvsRenderer {
 public:
  // The frame's constants (frame_plan.h).
  static constexpr int kStatsEvery = frame::kStatsEvery;
  static constexpr float kStatsWeight = frame::kStatsWeight;
  static constexpr float kNoDepth = frame::kNoDepth;
  static constexpr float kAnyDepth = frame::kAnyDepth;

  explicit IbfvsRenderer(const RenderSettings& settings);

  /// Uploads positions, normals and the per-vertex field `field` (one vector
  /// per vertex, already projected or not). Resets the texture.
  void set_mesh(const TriMesh& mesh, std::span<const glm::vec3> field);
  /// Another surface (other triangles or another vertex count: a topology
  /// change, adaptive refinement, an unrelated mesh), keeping the texture:
  /// F_t stays where it is in the image and the flow takes it on (the
  /// image-space path). Same arguments as set_mesh.
  void replace_mesh(const TriMesh& mesh, std::span<const glm::vec3> field);
  /// The same vertices with other triangles (a step whose cells split
  /// otherwise, a host's own triangles of the same points:
  /// points_correspond): the texture stays, and so does the pair of steps
  /// the last frame drew, so that set_surface_steps's motion still carries
  /// it. Positions and fields as they were; `mesh` gives the triangles (its
  /// positions tell a closed surface's orientation).
  void set_triangles(const TriMesh& mesh);
  /// The surface moves (the same triangles: a moving or deforming mesh,
  /// rigid-body motion): its positions and normals at the current and the
  /// next time step, interpolated with set_field_mix as the field is. The
  /// advection of F_t then includes the surface's own motion between two
  /// frames as it includes the camera's (with AdvectView::Previous): each
  /// pixel's texture comes from where the last frame drew its surface point,
  /// moved back along the flow. Keeps the texture. One vector per vertex each.
  /// `motion`: each vertex's screw from the one step to the other
  /// (fit_surface_motion), along which the points move in between (a rigid
  /// part stays rigid); empty: along chords.
  void set_surface_steps(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                         std::span<const glm::vec3> next_positions,
                         std::span<const glm::vec3> next_normals, const SurfaceMotion& motion = {});
  /// Whether set_surface_steps made the surface move (until set_mesh or replace_mesh).
  [[nodiscard]] bool moving() const { return surface_.moving(); }
  /// Replaces the field (same vertex count); keeps the texture.
  void set_field(std::span<const glm::vec3> field);
  /// An unsteady field: two time steps, interpolated linearly on the GPU with
  /// set_field_mix (paper section 1: "it can handle ... unsteady flow").
  void set_field_steps(std::span<const glm::vec3> current, std::span<const glm::vec3> next);
  /// Position between the two steps, in [0, 1] (of the field, and of the
  /// surface where it moves).
  void set_field_mix(float mix);
  /// An image that stands in for the surface colour (paper 3.3 step 7: "a
  /// geographical map"), mapped by longitude and latitude of the direction
  /// from `centre` (equirectangular: x from -180 to 180 degrees east, y from
  /// -90 to 90 north, rows bottom-up as ImageU8 stores them). An empty image
  /// turns it off.
  void set_surface_image(const ImageU8& image, const glm::vec3& centre);
  /// Per-vertex scalars for colouring (`color`) and for modulating beta
  /// (`beta`); either may be empty (zeros). Sizes must match the mesh.
  void set_scalars(std::span<const float> color, std::span<const float> beta);
  /// Changes alpha, beta, noise profile/rate, colours and advect view. The
  /// image size and noise scale/seed need a new renderer.
  void update_settings(const RenderSettings& settings);

  /// F_t := B everywhere, frame counter 0 (algorithm steps 1-2).
  void reset();
  /// F_t := a random colour per noise cell (s x s pixels), for the
  /// topological decomposition of section 4.1 (figure 7, with alpha = 0).
  void fill_texture_with_cell_colors(std::uint32_t seed);
  /// Section 3.7: stop updating F_t and the texture coordinates; later frames
  /// map the last texture onto the surface as it was seen when locking, so
  /// the camera can move and the pattern stays on the surface (parts not
  /// visible then show whatever the image held there: one view only).
  void lock();
  /// Resumes the animation from the locked texture.
  void unlock();
  [[nodiscard]] bool locked() const { return locked_; }
  /// The view-projection that maps the surface onto the current F_t (the lock
  /// view when locked): texture coordinates for exporting F_t.
  [[nodiscard]] const glm::mat4& texture_view_projection() const {
    return locked_ ? lock_view_projection_ : previous_view_projection_;
  }
  /// Section 3.7's option for dragging: the next frame takes F_t shifted by
  /// `pixels` (x right, y up) and the noise G moves with it, so the pattern
  /// follows the mouse pointer.
  void shift_image(glm::vec2 pixels);
  /// One frame with displacement dt (world units per frame).
  void render_frame(const ViewState& view, float dt);

  [[nodiscard]] int frame() const { return frame_; }
  /// Channels F_t is stored in: 1 while it can only be grey, else 4.
  [[nodiscard]] int texture_channels() const { return feedback_.layout().colour ? 4 : 1; }
  [[nodiscard]] const RenderSettings& settings() const { return settings_; }
  /// The composed image F, RGBA8, rows bottom-up.
  [[nodiscard]] ImageU8 read_output() const;
  /// The same into `image`, reusing its memory (a video's frames, every frame).
  void read_output(ImageU8& image) const;
  /// The texture image F_t, RGBA float (values as stored in 16-bit float; a
  /// one-channel F_t is spread to grey RGB with alpha 1).
  [[nodiscard]] ImageF read_texture() const;
  /// F_t as stored, kRawChannels channels: grey value, eye depth, the
  /// direction of the streaks at the pixel in its frame (x, y, kept when
  /// the display filter is on, which follows it: the flow's own image-space
  /// direction, without the surface's or the camera's motion; unit, or 8
  /// bits a component with the tap texture; else 0) and the value the filter's
  /// taps read (sharpened, or the value), and the tap texture's depth as
  /// stored (-1 without one: write_texture_raw then stores the eye depth);
  /// or RGB, eye depth, 0, 0 and -1. The depth is kNoDepth off the surface.
  /// write_texture_raw takes the same.
  [[nodiscard]] ImageF read_texture_raw() const;
  static constexpr int kRawChannels = FeedbackImages::kRawChannels;
  /// Records every pixel's displacement from now on (for measurements: it
  /// costs a fourth attachment), or stops.
  void record_flow(bool on);
  /// The last frame's displacement of every pixel in pixels (x right, y up),
  /// two channels; 0 off the surface and while locked. Needs record_flow(true).
  [[nodiscard]] ImageF read_flow() const;
  /// Window depth of the last frame, one channel in [0, 1]; 1 where the
  /// surface does not cover the pixel (the projected surface Omega' of eq. 12).
  [[nodiscard]] ImageF read_depth() const;
  /// 1 where the surface covers the pixel in the last frame, else 0 (rows bottom-up).
  [[nodiscard]] std::vector<std::uint8_t> read_coverage() const;
  /// Draws the last output F into the window's framebuffer, scaled to fit the
  /// part of a window of that size right of `left` pixels (a side panel) with
  /// its aspect kept, the rest in the background colour.
  void present(int window_width, int window_height, int left = 0);
  /// Runs `draw` with F and the last frame's depth bound as the framebuffer
  /// over the whole image (an overlay drawn over the frame: it shows in
  /// read_output and present, not in F_t).
  void draw_over_output(const std::function<void()>& draw);
  /// Draws the last frame into the framebuffer bound now (a host's, such as
  /// ParaView's) over the image's size at `origin` (the viewport set to
  /// it, whatever the host's was): F where the surface is, with the surface's depth, so that the
  /// host's other objects hide it and it hides them as their own would; the
  /// rest of the host's picture stays. Leaves the host's state as it was.
  /// `interior` draws only the pixels whose 3x3 neighbourhood but two corners
  /// is surface too: the texture again over a host's image-space
  /// antialiasing (FXAA), which blurs its lines, leaving the host's
  /// smoothing of the silhouettes.
  void draw_to_host(glm::ivec2 origin, bool interior = false);
  /// Replaces F_t (as read_texture_raw gives it: same size and channels), for
  /// the depth compositing of a distributed render (core/image/composite.h).
  void write_texture_raw(const ImageF& texture);
  /// F as stored, RGBA float: the alpha channel holds D before the contrast
  /// stage, which the contrast statistics read.
  [[nodiscard]] ImageF read_output_raw() const;
  /// Replaces F (as read_output_raw gives it), for the same compositing.
  void write_output_raw(const ImageF& output);
  /// A distributed render composites F_t and F after each frame; the
  /// contrast statistics must then read the composited images: with `on`,
  /// render_frame leaves its statistics pass for run_deferred_statistics().
  void defer_statistics(bool on) { defer_statistics_ = on; }
  /// Whether the IBFVS pass may run split in two where the features allow
  /// (shaders::deferred_pass; the default): the same F_t, F within the
  /// rounding of the single pass's seed. Off: the single pass, as the
  /// browser page runs it (tests compare the two).
  void allow_deferred_pass(bool on) { deferred_allowed_ = on; }
  /// The camera the last frame was drawn with (identity before the first).
  [[nodiscard]] const ViewState& last_view() const { return last_view_; }
  /// Takes over the texture of another renderer of the same scene (a new
  /// size, a new noise grid): `raw` as its read_texture_raw gives it, of any
  /// size (resampled to this one, nearest texel), last drawn with `view`.
  /// The next frame advects from it as from this renderer's own last frame.
  void take_texture(const ImageF& raw, const ViewState& view);
  /// The statistics pass render_frame left (nothing when none is due).
  void run_deferred_statistics();
  /// True when render_frame left a statistics pass (contrast on, every
  /// kStatsEvery frames): F must then be composited too.
  [[nodiscard]] bool statistics_due() const { return statistics_due_; }
  /// World length of the probe step that projects a vector's direction
  /// (set_mesh sets 1/1000 of the mesh's diagonal); pieces of one mesh on
  /// several processes take the whole mesh's, so that they advect alike.
  void set_probe_length(float world);
  /// Blocks until the GPU has finished every submitted frame.
  void finish();

 private:
  // One compiled program per combination of features in use (see
  // shaders::ShaderFeatures), made on first use; settings_version_ tells
  // which ones still need the current settings as uniforms.
  struct Variant {
    IbfvsPrograms programs;
    std::uint64_t applied = 0;  // settings_version_ last set
  };
  void statistics_pass(int texture_index, int frame);  // for the contrast stage of the next frame
  bool defer_statistics_ = false;
  bool deferred_allowed_ = true;
  bool statistics_due_ = false;
  // The IBFVS pass (or its deferred first half) into F_t and F.
  void ibfvs_pass(const IbfvsPrograms& v, const ViewState& view, float dt, float noise_time);
  // The image of the frame plan named `name` (frame_plan.h) in a frame that
  // draws F_t into its pair member `now` from `last`; binds a pass's images.
  [[nodiscard]] const gl::Texture2D* image(std::string_view name, int now, int last) const;
  void bind_reads(const PlannedPass& pass, int now, int last) const;
  void display_pass(const IbfvsPrograms& v);
  void resolve_pass(const IbfvsPrograms& v);  // the deferred pass's second half
  // The pixels the mesh can cover in this view: its bounding box projected
  // (x, y, width, height), or the whole image where a corner is behind the eye.
  [[nodiscard]] glm::ivec4 screen_box(const glm::mat4& view_projection) const;
  // The grid values the IBFVS pass can read inside surface_box_ (its noise
  // and the sharpening's, with bilinear footprints), in grid cells; the
  // whole grid where they wrap around its edges.
  [[nodiscard]] glm::ivec4 grid_box() const;
  // screen_box of the last frame: the grid (grid_box), display and host passes
  // draw inside it.
  glm::ivec4 surface_box_{0};
  [[nodiscard]] shaders::ShaderFeatures features() const;
  // The variant for features `f` (features()), compiled and up to date.
  Variant& variant(const shaders::ShaderFeatures& f);
  void apply_settings();  // after settings_ changed
  // F_t in colour or grey, in the layout these settings give it
  // (FeedbackImages::layout_for: fewer channels are cheaper to sample on
  // llvmpipe), its content kept (`keep`) or not, and the passes'
  // framebuffers over it. Nothing where it has that layout already.
  void use_layout(bool colour, bool keep);

  RenderSettings settings_;
  // The passes that stand on their own (passes.h), made from the settings.
  GridPass grid_pass_;
  StatsPass stats_pass_;
  HostPass host_pass_;
  std::unordered_map<unsigned, Variant> variants_;  // by ShaderFeatures::key()
  std::uint64_t settings_version_ = 0;
  glm::ivec2 phase_size_{0};
  glm::vec3 image_centre_{0.0f};
  float field_mix_ = 0.0f;
  // The images a frame hands the next: F_t's ping-pong and the taps
  // (feedback_images.h); and what the passes draw into, with each pass's
  // framebuffer (frame_targets.h).
  FeedbackImages feedback_;
  FrameTargets targets_;
  gl::VertexArray empty_vao_;  // for the attributeless resolve and display passes
  // The surface: its points (two steps where it moves), the pair the last
  // frame drew, the field, the scalars, the triangles (surface_buffers.h).
  SurfaceBuffers surface_;
  void upload_mesh(const TriMesh& mesh, std::span<const glm::vec3> field);
  void point_drawn_attributes();  // attributes 7, 8, 11, 12 at the pair the last frame drew
  // Whether a moving surface's own motion carries the texture: advecting in
  // the last frame's view, with a field relative to the surface.
  [[nodiscard]] bool carries_surface() const {
    return ibfvs::carries_surface(settings_.advect_view, settings_.field_frame);
  }
  gl::Texture2D color_map_;  // 256 x 1 RGBA float
  gl::Texture2D surface_image_;
  float probe_ = 1e-3f;            // 1/1000 of the mesh's bounding-box diagonal
  int cull_ = 0;                   // closed_orientation of the mesh: its back faces are never seen
  glm::vec2 texture_shift_{0.0f};  // pixels, for the next frame only
  glm::vec2 noise_shift_{0.0f};    // pixels, accumulated
  int displayed_ = 0;              // the pair member of F_t the last F was drawn with
  int frame_ = 0;
  bool has_previous_ = false;
  bool locked_ = false;
  glm::mat4 lock_view_projection_{1.0f};
  glm::mat4 previous_view_projection_{1.0f};
  ViewState last_view_;
};

}  // namespace ibfvs
