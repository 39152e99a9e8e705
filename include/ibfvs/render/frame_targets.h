#pragma once
// What the passes of a frame draw into, beyond F_t (feedback_images.h),
// and each pass's framebuffer over those images:
//
//   ibfvs(i)   the IBFVS pass: F_t[i], F (or, with a tap texture, the
//              base and the taps[i] and seed the display pass reads), the
//              recorded flow where asked, the depth
//   gbuffer()  the deferred pass's first half: t(x), depths, shading
//   resolve(i) the deferred pass's second half: F_t[i], F, taps[i], the flow
//   display()  the display pass: F and the depth; read back and presented
//
// F is shared: the IBFVS pass writes it without a tap texture, the resolve
// or the display pass with one, and the statistics and host passes read
// it. The grid and statistics passes own their targets (passes.h).
// IbfvsRenderer owns one. Needs a current OpenGL 4.5 context.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/image/image.h"
#include "ibfvs/gl/objects.h"
#include "ibfvs/render/feedback_images.h"

namespace ibfvs {

class FrameTargets {
 public:
  FrameTargets() = default;
  /// F and the depth of images of `size`, and the display pass's framebuffer.
  explicit FrameTargets(glm::ivec2 size);
  /// The IBFVS and resolve passes' framebuffers over `feedback`'s images,
  /// after it allocated them (a new layout), with a base and a seed where
  /// it has taps.
  void attach(const FeedbackImages& feedback);
  /// Records every pixel's displacement from the next frame on (a fourth or
  /// fifth attachment), or stops; cleared to 0.
  void record_flow(bool on, const FeedbackImages& feedback);
  [[nodiscard]] bool records_flow() const { return record_flow_; }
  /// The G-buffer, made the first time a deferred variant is.
  void make_gbuffer();

  [[nodiscard]] const gl::Framebuffer& ibfvs(int i) const { return ibfvs_[i]; }
  [[nodiscard]] const gl::Framebuffer& gbuffer() const { return gbuffer_framebuffer_; }
  [[nodiscard]] const gl::Framebuffer& resolve(int i) const { return resolve_[i]; }
  [[nodiscard]] const gl::Framebuffer& display() const { return display_; }

  /// Before the frame that draws F_t[i]: F_t[i] and F in the background
  /// (F_t's depth kNoDepth), taps[i] without depth or direction, the flow 0,
  /// the depth far.
  void clear(int i, const FeedbackImages& feedback, glm::vec3 background);

  [[nodiscard]] const gl::Texture2D& output() const { return output_; }
  [[nodiscard]] const gl::Texture2D& depth() const { return depth_; }
  [[nodiscard]] const gl::Texture2D& base() const { return base_; }
  [[nodiscard]] const gl::Texture2D& seed() const { return seed_; }
  [[nodiscard]] const gl::Texture2D& gbuffer_image(int i) const { return gbuffer_[i]; }

  /// F, RGBA8, opaque, rows bottom-up, into `image` (its memory reused).
  void read_output(ImageU8& image) const;
  /// F as stored, RGBA float (alpha: D before the contrast stage).
  [[nodiscard]] ImageF read_output_raw() const;
  void write_output_raw(const ImageF& output);
  /// The recorded displacement, pixels, two channels.
  [[nodiscard]] ImageF read_flow() const;
  /// Window depth in [0, 1], one channel; 1 off the surface.
  [[nodiscard]] ImageF read_depth() const;

 private:
  glm::ivec2 size_{0};
  gl::Texture2D output_;  // F
  gl::Texture2D depth_;   // a texture: the host and resolve passes read it
  gl::Framebuffer display_;
  // With a tap texture the IBFVS pass leaves the display pass ((1 - beta)
  // F_s, beta) and the seed (the filter's first tap, t(x)'s depth, the
  // displacement).
  gl::Texture2D base_;
  gl::Texture2D seed_;
  gl::Texture2D flow_;  // displacement of the last frame, pixels (when recorded)
  bool record_flow_ = false;
  bool taps_ = false;  // the feedback attached has taps
  [[nodiscard]] unsigned flow_attachment() const { return taps_ ? 4u : 2u; }
  gl::Texture2D gbuffer_[2];
  gl::Framebuffer gbuffer_framebuffer_;
  gl::Framebuffer ibfvs_[2];
  gl::Framebuffer resolve_[2];  // with a tap texture
};

}  // namespace ibfvs
