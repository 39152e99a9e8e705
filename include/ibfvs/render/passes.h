#pragma once
// The passes of a frame, each owning its program and its uniforms; the grid
// and statistics passes their targets too. The IBFVS, resolve and display
// passes draw into the feedback images (feedback_images.h) and the frame's
// targets (frame_targets.h), each through its own framebuffer there.
// IbfvsRenderer (ibfvs_renderer.h) runs them in order:
//
//   GridPass   the noise grid G of the frame                     (eq. 8)
//   IbfvsPrograms  the IBFVS pass (or its G-buffer and resolve halves) and
//              the display pass, compiled for one set of features
//   StatsPass  the contrast statistics of the shown texture     (section 3.4)
//   HostPass   F and its depth into a host's framebuffer (ParaView)
//
// The caller binds each pass's images by the frame's plan (frame_plan.h)
// before running it.

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "ibfvs/core/texture/noise.h"
#include "ibfvs/gl/objects.h"
#include "ibfvs/render/pass_settings.h"
#include "ibfvs/render/shaders.h"

namespace ibfvs {

/// The grid pass: G_ij = w(v_g k + phi_ij) once per grid point (eq. 8),
/// into a texture the IBFVS pass samples bilinearly (eq. 7).
class GridPass {
 public:
  /// The grid's phases phi_ij, its columns and rows.
  explicit GridPass(const NoiseGrid& grid);
  /// The time profile w, a spike's width and the seed.
  void apply(const NoiseParams& noise) const;
  /// G of the frame at noise time v_g k, in the cells of `box` (x, y,
  /// columns, rows: the cells the surface can read).
  void run(float noise_time, glm::ivec4 box);
  [[nodiscard]] const gl::Texture2D& values() const { return grid_; }
  [[nodiscard]] const gl::Texture2D& phases() const { return phases_; }
  [[nodiscard]] glm::ivec2 size() const { return {grid_.width(), grid_.height()}; }

 private:
  gl::Texture2D phases_;
  gl::Texture2D grid_;
  gl::Framebuffer framebuffer_;
  gl::Program program_;
  gl::VertexArray empty_;
  int noise_time_ = -1, profile_ = -1, spike_width_ = -1, seed_ = -1;
};

/// What the IBFVS pass's programs take each frame (those that follow from
/// the settings are set by IbfvsPrograms::apply).
struct IbfvsFrame {
  glm::mat4 view{1.0f}, projection{1.0f};
  glm::mat4 advect_view_projection{1.0f};  ///< the view that projects r - v dt (eq. 13)
  float dt = 0.0f, noise_time = 0.0f;
  float field_mix = 0.0f;  ///< between the field's (and the surface's) two steps
  float drawn_mix = 0.0f;  ///< the mix the last frame drew a moving surface at
  float probe = 0.0f;      ///< world length of the probe step
  glm::vec2 texture_shift{0.0f}, noise_shift{0.0f};
  bool locked = false;
  glm::vec2 tap_depth{0.0f};       ///< the depth map this frame's taps are written with
  glm::vec2 last_tap_depth{0.0f};  ///< the map the last frame's taps were written with
};

/// The IBFVS pass's programs for one set of features (steps 2-7 of the
/// paper's algorithm): the pass in one piece, or, deferred
/// (shaders::deferred_pass), its first half (the mesh into a G-buffer) and
/// the resolve; and with a tap texture the display pass. Their textures are
/// bound by the caller, by the units' table.
class IbfvsPrograms {
 public:
  IbfvsPrograms(const shaders::ShaderFeatures& features, bool deferred);
  /// The uniforms that follow from the settings (shaders::settings_uniforms), into each.
  void apply(const std::vector<shaders::UniformValue>& uniforms) const;
  /// The frame's uniforms, into each.
  void set_frame(const IbfvsFrame& frame) const;
  /// The mesh pass (the first half where deferred).
  [[nodiscard]] const gl::Program& mesh() const { return mesh_; }
  /// The resolve, where deferred (else empty).
  [[nodiscard]] const gl::Program& resolve() const { return resolve_; }
  /// The display pass, with a tap texture and not deferred (else empty).
  [[nodiscard]] const gl::Program& display() const { return display_; }

 private:
  struct Uniforms {
    int view_projection, advect_view_projection, view, clip_to_depth, dt, noise_time, field_mix,
        locked, probe, texture_shift, noise_shift, tap_depth, new_tap_depth, drawn_mix;
  };
  static Uniforms locations(const gl::Program& p);
  static void set(const gl::Program& p, const Uniforms& u, const IbfvsFrame& frame);
  gl::Program mesh_;
  Uniforms u_{};
  gl::Program resolve_;
  Uniforms ru_{};
  gl::Program display_;
  int display_texture_shift_ = -1, display_tap_depth_ = -1;
};

/// The statistics pass: the mean and deviation of D over the surface, from
/// a sparse grid of its pixels that moves every frame, blended into a
/// running average (1 x 1: sum l, sum l^2, count) that the next frames'
/// contrast stage reads.
class StatsPass {
 public:
  StatsPass();
  /// No statistics (before the first frame).
  void clear();
  /// One pass over F_t and F (whose alpha holds D before the contrast
  /// stage), bound by the plan, of an image of `size`; `grey`: F_t holds
  /// grey values. `weight`: of this pass in the running average.
  void run(bool grey, glm::ivec2 size, int frame, float weight);
  [[nodiscard]] const gl::Texture2D& result() const { return stats_; }

 private:
  gl::Texture2D stats_;
  gl::Framebuffer framebuffer_;
  struct Program {
    gl::Program program;
    int image_size = -1, stats_size = -1, offset = -1;
  } programs_[2];  // [grey]
  gl::VertexArray empty_;
};

/// The host pass: F where the surface is, with the surface's depth (both
/// bound by the plan), into
/// the framebuffer bound now (a host's), over its viewport from `origin`.
class HostPass {
 public:
  HostPass();
  /// `interior`: only the pixels whose 3x3 neighbourhood but two corners is
  /// surface too. `box`: the pixels the surface can cover (the pass writes
  /// gl_FragDepth, so no depth test spares the rest). The caller saves and
  /// prepares the host's state.
  void draw(glm::ivec2 origin, bool interior, glm::ivec4 box);

 private:
  gl::Program program_;
  int origin_ = -1, interior_ = -1;
  gl::VertexArray empty_;
};

}  // namespace ibfvs
