#pragma once
// The images one frame hands the next (the paper's step 6): F_t with each
// pixel's eye depth, as a ping-pong pair (a frame reads the last one and
// draws the other), and beside a grey F_t the display filter's taps
// (shaders::tap_texture), each pair member with the depth map its taps were
// written with. How they are stored follows the settings' features
// (Layout); read_raw and upload_raw give and take them in one form that
// does not depend on it (kRawChannels), which carries F_t across a change
// of layout, to a renderer of another size and through a distributed
// render's compositing. IbfvsRenderer owns one; FrameTargets
// (frame_targets.h) attaches it to the passes' framebuffers. Needs a
// current OpenGL 4.5 context.

#include <span>

#include <glm/vec2.hpp>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/scene/render_settings.h"
#include "ibfvs/gl/objects.h"

namespace ibfvs {

class FeedbackImages {
 public:
  /// The raw form's channels: grey value, eye depth, the direction of the
  /// streaks at the pixel (x, y: unit, or 0 without the display filter),
  /// the value the filter's taps read, and the taps' depth as stored (-1:
  /// none, upload_raw encodes the eye depth); or RGB, eye depth, 0, 0, -1.
  /// The depth is frame::kNoDepth off the surface.
  static constexpr int kRawChannels = 6;

  /// How F_t is stored.
  struct Layout {
    bool colour = true;  ///< RGB, else one grey value
    int channels = 4;    ///< stored: 2 (grey value, depth) or 4
    bool taps = false;   ///< a tap texture beside it
    bool operator==(const Layout&) const = default;
  };
  /// The layout for these settings, with F_t in colour or grey. Grey is
  /// value and depth, with the displacement where the display filter
  /// follows it (half the bytes of colour for the paper's look); with
  /// sharpening the direction goes with the taps, 8 bits a channel.
  [[nodiscard]] static Layout layout_for(const RenderSettings& settings, bool colour);

  FeedbackImages() = default;
  /// Storage of `layout` for images of `size`: content undefined until a
  /// frame's targets are cleared or upload_raw fills it; last() stays.
  void allocate(glm::ivec2 size, const Layout& layout);
  /// The same F_t in another layout (grey spreads to RGB; colour to grey is
  /// not asked for): read, allocated again and written back.
  void convert(const Layout& layout, float sharpen);
  [[nodiscard]] const Layout& layout() const { return layout_; }
  [[nodiscard]] glm::ivec2 size() const { return size_; }

  /// The pair member that holds F_t of the last frame, and the one the
  /// frame being drawn writes.
  [[nodiscard]] int last() const { return last_; }
  [[nodiscard]] int now() const { return 1 - last_; }
  /// The frame drew `now()`: it is the last from here.
  void advance() { last_ = 1 - last_; }
  /// The pair's first member is the last (a restart).
  void rewind() { last_ = 0; }

  [[nodiscard]] const gl::Texture2D& texture(int i) const { return texture_[i]; }
  /// Empty without a tap texture.
  [[nodiscard]] const gl::Texture2D& taps(int i) const { return taps_[i]; }
  /// The depth map (core/texture/display.h: tap_depth_map) taps(i) was
  /// written with.
  [[nodiscard]] glm::vec2 tap_depth(int i) const { return tap_depth_[i]; }
  void set_tap_depth(int i, glm::vec2 map) { tap_depth_[i] = map; }

  /// The last F_t in the raw form; `sharpen`: the settings' (the taps' values
  /// are stored spread by it).
  [[nodiscard]] ImageF read_raw(float sharpen) const;
  /// The raw form (of this size) into the last F_t and its taps.
  void upload_raw(const ImageF& raw, float sharpen);
  /// RGBA (RGB and eye depth) into the last F_t of a colour layout.
  void upload_colours(std::span<const float> rgba);

 private:
  glm::ivec2 size_{0};
  Layout layout_;
  gl::Texture2D texture_[2];
  gl::Texture2D taps_[2];
  glm::vec2 tap_depth_[2]{};
  int last_ = 0;
};

}  // namespace ibfvs
