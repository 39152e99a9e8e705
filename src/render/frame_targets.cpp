#include "ibfvs/render/frame_targets.h"

#include "ibfvs/core/support/error.h"
#include "ibfvs/render/frame_plan.h"

namespace ibfvs {

FrameTargets::FrameTargets(glm::ivec2 size)
    : size_(size),
      output_(size.x, size.y, gl::Format::RGBA8, false),
      depth_(size.x, size.y, gl::Format::Depth24, false),
      display_(gl::Framebuffer::create()) {
  display_.attach_color(0, output_);
  display_.attach_depth(depth_);
  display_.finish(1);
}

void FrameTargets::attach(const FeedbackImages& feedback) {
  taps_ = feedback.layout().taps;
  const auto own = [&](gl::Format f) {
    return taps_ ? gl::Texture2D(size_.x, size_.y, f, false) : gl::Texture2D();
  };
  base_ = own(gl::Format::RGBA8);
  seed_ = own(gl::Format::RGBA16F);
  for (int i = 0; i < 2; ++i) {
    gl::Framebuffer& f = ibfvs_[i];
    f = gl::Framebuffer::create();
    f.attach_color(0, feedback.texture(i));
    f.attach_color(1, taps_ ? base_ : output_);
    if (taps_) {
      f.attach_color(2, feedback.taps(i));
      f.attach_color(3, seed_);
    }
    if (record_flow_) f.attach_color(flow_attachment(), flow_);
    f.attach_depth(depth_);
    f.finish(record_flow_ ? flow_attachment() + 1 : flow_attachment());
    // The deferred pass's second half writes F itself, without the seed.
    gl::Framebuffer& r = resolve_[i];
    r = gl::Framebuffer();
    if (!taps_) continue;
    r = gl::Framebuffer::create();
    r.attach_color(0, feedback.texture(i));
    r.attach_color(1, output_);
    r.attach_color(2, feedback.taps(i));
    if (record_flow_) r.attach_color(3, flow_);
    r.attach_depth(depth_);
    r.finish(record_flow_ ? 4 : 3);
  }
}

void FrameTargets::record_flow(bool on, const FeedbackImages& feedback) {
  if (on == record_flow_) return;
  record_flow_ = on;
  if (on && !flow_) flow_ = gl::Texture2D(size_.x, size_.y, gl::Format::RG16F, false);
  attach(feedback);
  if (on) ibfvs_[feedback.last()].clear_color(flow_attachment(), glm::vec4(0.0f));
}

void FrameTargets::make_gbuffer() {
  if (gbuffer_framebuffer_) return;
  gbuffer_framebuffer_ = gl::Framebuffer::create();
  for (int i = 0; i < 2; ++i) {
    gbuffer_[i] = gl::Texture2D(size_.x, size_.y, gl::Format::RGBA32F, false);
    gbuffer_framebuffer_.attach_color(static_cast<unsigned>(i), gbuffer_[i]);
  }
  gbuffer_framebuffer_.attach_depth(depth_);
  gbuffer_framebuffer_.finish(2);
}

void FrameTargets::clear(int i, const FeedbackImages& feedback, glm::vec3 background) {
  const glm::vec3& b = background;
  gl::Framebuffer& f = ibfvs_[i];
  f.clear_color(0, feedback.layout().colour ? glm::vec4(b, frame::kNoDepth)
                                            : glm::vec4(b.r, frame::kNoDepth, 0, 0));
  display_.clear_color(0, glm::vec4(b, 1.0f));
  if (taps_) f.clear_color(2, glm::vec4(0.5f, 0.0f, 0.5f, 0.5f));  // no depth, no direction
  if (record_flow_) f.clear_color(flow_attachment(), glm::vec4(0.0f));
  f.clear_depth();  // the depth buffer is shared by every framebuffer
}

void FrameTargets::read_output(ImageU8& image) const {
  image.width = size_.x;
  image.height = size_.y;
  image.channels = 4;
  image.pixels.resize(static_cast<std::size_t>(image.width) * image.height * 4);
  display_.read_rgba8(0, image.width, image.height, image.pixels);
  // The alpha channel holds the contrast stage's statistics input: F is opaque.
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
}

ImageF FrameTargets::read_output_raw() const {
  ImageF image(size_.x, size_.y, 4);
  output_.read_float(image.pixels, 4);
  return image;
}

void FrameTargets::write_output_raw(const ImageF& output) {
  if (output.width != size_.x || output.height != size_.y || output.channels != 4)
    throw InputError("renderer: write_output_raw needs a " + std::to_string(size_.x) + "x" +
                     std::to_string(size_.y) + " RGBA image");
  output_.upload_float(output.pixels, 4);
}

ImageF FrameTargets::read_flow() const {
  if (!record_flow_) throw InputError("renderer: read_flow needs record_flow(true) first");
  ImageF image(size_.x, size_.y, 2);
  flow_.read_float(image.pixels, 2);
  return image;
}

ImageF FrameTargets::read_depth() const {
  ImageF image(size_.x, size_.y, 1);
  display_.read_depth(image.width, image.height, image.pixels);
  return image;
}

}  // namespace ibfvs
