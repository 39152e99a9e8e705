#include "ibfvs/render/ibfvs_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/texture/display.h"
#include "ibfvs/render/frame_plan.h"
#include "ibfvs/render/pass_settings.h"
#include "ibfvs/render/shaders.h"

namespace ibfvs {
namespace {

template <class T>
std::span<const std::byte> bytes_of(std::span<const T> v) {
  return std::as_bytes(v);
}

// The settings, checked before any pass is made from them.
const RenderSettings& checked(const RenderSettings& settings) {
  settings.validate();
  gl::check_image_size(settings.width, settings.height, "size");
  return settings;
}

}  // namespace

IbfvsRenderer::IbfvsRenderer(const RenderSettings& settings)
    : settings_(checked(settings)),
      grid_pass_(NoiseGrid(settings_.width, settings_.height, settings_.noise)),
      targets_(glm::ivec2(settings_.width, settings_.height)) {
  color_map_ = gl::Texture2D(256, 1, gl::Format::RGBA32F, true);
  use_layout(shaders::colour_background(settings_), false);
  phase_size_ = grid_pass_.size();
  empty_vao_ = gl::VertexArray::create();
  apply_settings();
  static_cast<void>(variant(features()));  // compile now: a shader error shows at construction
  reset();
}

void IbfvsRenderer::use_layout(bool colour, bool keep) {
  const FeedbackImages::Layout layout = FeedbackImages::layout_for(settings_, colour);
  const bool made = feedback_.size().x > 0;
  if (made && layout == feedback_.layout()) return;
  if (made && keep)
    feedback_.convert(layout, settings_.sharpen);
  else
    feedback_.allocate(glm::ivec2(settings_.width, settings_.height), layout);
  targets_.attach(feedback_);
}

void IbfvsRenderer::record_flow(bool on) {
  targets_.record_flow(on, feedback_);
}

shaders::ShaderFeatures IbfvsRenderer::features() const {
  shaders::ShaderFeatures f =
      shaders::features_for(settings_, feedback_.layout().colour, static_cast<bool>(surface_image_),
                            targets_.records_flow());
  f.moving = surface_.moving();
  return f;
}

IbfvsRenderer::Variant& IbfvsRenderer::variant(const shaders::ShaderFeatures& f) {
  const bool deferred = deferred_allowed_ && shaders::deferred_pass(f);
  const unsigned key = f.key() | (deferred ? 1u << 24u : 0u);
  auto it = variants_.find(key);
  if (it == variants_.end()) {  // made on first use
    it = variants_.emplace(key, Variant{IbfvsPrograms(f, deferred)}).first;
    if (deferred) targets_.make_gbuffer();
  }
  Variant& v = it->second;
  if (v.applied != settings_version_) {  // the settings changed since it was last used
    v.programs.apply(shaders::settings_uniforms(settings_, f, phase_size_, image_centre_));
    v.applied = settings_version_;
  }
  return v;
}

void IbfvsRenderer::apply_settings() {
  ++settings_version_;
  grid_pass_.apply(settings_.noise);
  std::vector<float> table(256 * 4);
  for (int i = 0; i < 256; ++i) {
    const glm::vec3 c = settings_.color_table.size() == 256
                            ? settings_.color_table[static_cast<std::size_t>(i)]
                            : color_map(settings_.color_map, static_cast<float>(i) / 255.0f);
    table[4 * i] = c.r, table[4 * i + 1] = c.g, table[4 * i + 2] = c.b, table[4 * i + 3] = 1.0f;
  }
  color_map_.upload_float(table, 4);
}

void IbfvsRenderer::update_settings(const RenderSettings& settings) {
  settings.validate();
  if (settings.width != settings_.width || settings.height != settings_.height ||
      settings.noise.scale != settings_.noise.scale || settings.noise.seed != settings_.noise.seed)
    throw InputError("renderer: size, noise scale and seed need a new renderer");
  settings_ = settings;
  // A grey texture turns colour once the settings ask for it and stays so
  // until reset(); F_t carries over into another layout.
  use_layout(feedback_.layout().colour || shaders::colour_background(settings_), true);
  apply_settings();
}

void IbfvsRenderer::reset() {
  gl::prepare_own_draw();
  // The layout of these settings, grey where they allow it again.
  use_layout(shaders::colour_background(settings_), false);
  for (int i = 0; i < 2; ++i) targets_.clear(i, feedback_, settings_.background);
  stats_pass_.clear();  // no statistics before the first frame
  feedback_.rewind();
  displayed_ = 0;
  frame_ = 0;
  has_previous_ = false;
}

void IbfvsRenderer::shift_image(glm::vec2 pixels) {
  texture_shift_ += pixels;
  noise_shift_ += pixels;
}

void IbfvsRenderer::present(int window_width, int window_height, int left) {
  gl::clear_window(window_width, window_height, glm::vec4(settings_.background, 1.0f));
  const int area = std::max(window_width - left, 1);
  const float scale = std::min(static_cast<float>(area) / settings_.width,
                               static_cast<float>(window_height) / settings_.height);
  const int w = static_cast<int>(std::lround(settings_.width * scale));
  const int h = static_cast<int>(std::lround(settings_.height * scale));
  const int x0 = left + (area - w) / 2, y0 = (window_height - h) / 2;
  targets_.display().blit_to_default(0, settings_.width, settings_.height, x0, y0, x0 + w, y0 + h);
}

void IbfvsRenderer::render_frame(const ViewState& view, float dt) {
  const glm::mat4 vp = view.projection * view.view;
  const int next = feedback_.now(), last = feedback_.last();
  gl::prepare_own_draw();  // a host's scissor box, masks or stencil test must not apply here
  targets_.clear(next, feedback_, settings_.background);
  surface_box_ = screen_box(vp);
  if (!surface_.empty()) {
    const float noise_time = settings_.noise.rate * static_cast<float>(frame_);
    const shaders::ShaderFeatures f = features();
    const IbfvsPrograms& v = variant(f).programs;
    // The frame's passes, in the plan's order, each where its `when` says
    // (frame_plan.h: pass_runs, which the page follows too). The statistics
    // change slowly: every kStatsEvery frames is enough, and on llvmpipe
    // each extra pass ends the frame's scene early.
    const PassFacts facts = pass_facts(f, static_cast<bool>(v.resolve()), frame_);
    for (const PlannedPass& pass : frame_plan()) {
      if (!pass_runs(pass.when, facts)) continue;
      if (pass.name == "grid") {  // G_ij of this frame
        bind_reads(pass, next, last);
        grid_pass_.run(noise_time, grid_box());
      } else if (pass.name == "ibfvs") {
        ibfvs_pass(v, view, dt, noise_time);
      } else if (pass.name == "resolve") {
        resolve_pass(v);
      } else if (pass.name == "display") {
        display_pass(v);
      } else if (pass.name == "stats") {
        if (defer_statistics_)
          statistics_due_ = true;
        else
          statistics_pass(next, frame_);
      }
    }
  }
  displayed_ = next;
  texture_shift_ = glm::vec2(0.0f);
  if (!locked_) {  // a locked F_t stays where it is; the output is shared
    feedback_.advance();
    previous_view_projection_ = vp;
    last_view_ = view;
    // This frame's surface is the one the next frame's texture comes from.
    surface_.frame_drawn(field_mix_);
  }
  has_previous_ = true;
  ++frame_;
}

void IbfvsRenderer::ibfvs_pass(const IbfvsPrograms& v, const ViewState& view, float dt,
                               float noise_time) {
  const glm::mat4 vp = view.projection * view.view;
  const bool use_previous = settings_.advect_view == AdvectView::Previous && has_previous_;
  const int next = feedback_.now(), last = feedback_.last();
  targets_.ibfvs(next).bind();
  gl::set_viewport(settings_.width, settings_.height);
  gl::set_running_average(0.0f);  // no blending (a host's may be on)
  gl::enable_depth_test(true);
  // A closed mesh hides its back faces behind its front ones: culling them
  // halves llvmpipe's triangle setup and changes no pixel.
  gl::set_face_culling(cull_);
  if (v.resolve()) targets_.gbuffer().bind();  // the first half of the deferred pass
  v.mesh().use();
  feedback_.set_tap_depth(next, tap_depth_map(view.projection));
  // A moving surface: where the last frame drew each vertex (the pair of
  // steps it drew and its mix; the current ones where no motion enters).
  float drawn_mix = field_mix_;
  if (surface_.moving()) {
    point_drawn_attributes();
    if (carries_surface() && has_previous_ && !locked_ && surface_.drawn_this_mesh())
      drawn_mix = surface_.drawn_mix();
  }
  IbfvsFrame frame;
  frame.view = view.view;
  frame.projection = view.projection;
  frame.advect_view_projection = locked_        ? lock_view_projection_
                                 : use_previous ? previous_view_projection_
                                                : vp;
  frame.dt = locked_ ? 0.0f : dt;
  frame.noise_time = noise_time;
  frame.field_mix = field_mix_;
  frame.drawn_mix = drawn_mix;
  frame.probe = probe_;
  frame.texture_shift = texture_shift_;
  frame.noise_shift = noise_shift_;
  frame.locked = locked_;
  frame.tap_depth = feedback_.tap_depth(next);
  frame.last_tap_depth = feedback_.tap_depth(last);
  v.set_frame(frame);
  bind_reads(planned_pass("ibfvs"), next, last);
  surface_.draw();
}

const gl::Texture2D* IbfvsRenderer::image(std::string_view name, int now, int last) const {
  static const std::map<std::string_view, const gl::Texture2D* (*)(const IbfvsRenderer&, int, int)>
      images = {
          {"phases", [](const IbfvsRenderer& r, int, int) { return &r.grid_pass_.phases(); }},
          {"grid", [](const IbfvsRenderer& r, int, int) { return &r.grid_pass_.values(); }},
          {"texture.last",
           [](const IbfvsRenderer& r, int, int l) { return &r.feedback_.texture(l); }},
          {"texture.now",
           [](const IbfvsRenderer& r, int n, int) { return &r.feedback_.texture(n); }},
          {"taps.last", [](const IbfvsRenderer& r, int, int l) { return &r.feedback_.taps(l); }},
          {"taps.now", [](const IbfvsRenderer& r, int n, int) { return &r.feedback_.taps(n); }},
          {"color_map", [](const IbfvsRenderer& r, int, int) { return &r.color_map_; }},
          {"surface_image", [](const IbfvsRenderer& r, int, int) { return &r.surface_image_; }},
          {"stats", [](const IbfvsRenderer& r, int, int) { return &r.stats_pass_.result(); }},
          {"gbuffer0",
           [](const IbfvsRenderer& r, int, int) { return &r.targets_.gbuffer_image(0); }},
          {"gbuffer1",
           [](const IbfvsRenderer& r, int, int) { return &r.targets_.gbuffer_image(1); }},
          {"seed", [](const IbfvsRenderer& r, int, int) { return &r.targets_.seed(); }},
          {"base", [](const IbfvsRenderer& r, int, int) { return &r.targets_.base(); }},
          {"output", [](const IbfvsRenderer& r, int, int) { return &r.targets_.output(); }},
          {"depth", [](const IbfvsRenderer& r, int, int) { return &r.targets_.depth(); }},
      };
  const auto it = images.find(name);
  if (it == images.end())
    throw GraphicsError("renderer: the frame plan names an image it does not have: " +
                        std::string(name));
  return it->second(*this, now, last);
}

void IbfvsRenderer::bind_reads(const PlannedPass& pass, int now, int last) const {
  for (const PlannedRead& read : pass.reads)
    if (const gl::Texture2D* t = image(read.image, now, last); *t) t->bind(read.unit);
}

void IbfvsRenderer::resolve_pass(const IbfvsPrograms& v) {
  targets_.resolve(feedback_.now()).bind();
  gl::set_face_culling(0);
  gl::test_depth_behind_surface(true);  // the surface's pixels, each once
  gl::scissor(true, surface_box_);
  v.resolve().use();
  bind_reads(planned_pass("resolve"), feedback_.now(), feedback_.last());
  gl::draw_attributeless_triangle(empty_vao_);
  gl::scissor(false);
  gl::test_depth_behind_surface(false);
}

void IbfvsRenderer::display_pass(const IbfvsPrograms& v) {
  targets_.display().bind();
  gl::set_face_culling(0);
  gl::test_depth_behind_surface(true);
  gl::scissor(true, surface_box_);  // the depth test rejects the rest, but per pixel
  v.display().use();                // its frame's uniforms: set with the IBFVS pass's
  bind_reads(planned_pass("display"), feedback_.now(), feedback_.last());
  gl::draw_attributeless_triangle(empty_vao_);
  gl::scissor(false);
  gl::test_depth_behind_surface(false);
}

glm::ivec4 IbfvsRenderer::screen_box(const glm::mat4& view_projection) const {
  const glm::ivec4 all(0, 0, settings_.width, settings_.height);
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? surface_.bounds().max.x : surface_.bounds().min.x,
                           (c & 2) ? surface_.bounds().max.y : surface_.bounds().min.y,
                           (c & 4) ? surface_.bounds().max.z : surface_.bounds().min.z);
    const glm::vec4 clip = view_projection * glm::vec4(corner, 1.0f);
    if (!(clip.w > 1e-6f)) return all;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    lo = glm::min(lo, ndc);
    hi = glm::max(hi, ndc);
  }
  const glm::vec2 size(settings_.width, settings_.height);
  // In pixels, clamped before the conversion (a corner near the eye's plane
  // lies far outside), with a pixel of margin: rasterisation takes pixel
  // centres, rounding the rest.
  const glm::vec2 from =
      glm::clamp(glm::floor((lo * 0.5f + 0.5f) * size) - 1.0f, glm::vec2(0.0f), size);
  const glm::vec2 to =
      glm::clamp(glm::ceil((hi * 0.5f + 0.5f) * size) + 1.0f, glm::vec2(0.0f), size);
  const glm::ivec2 a(from), b(to);
  return glm::ivec4(a, glm::max(b - a, glm::ivec2(0)));
}

glm::ivec4 IbfvsRenderer::grid_box() const {
  const glm::ivec4 all(0, 0, grid_pass_.size().x, grid_pass_.size().y);
  const auto cells = [&](int from, int size, float shift, int count) {
    // noise(x) reads the grid at (x - 0.5) / s + 0.5 cells, bilinearly; x is
    // a pixel centre inside the box, moved by the noise shift and by up to
    // the sharpening's reach across the flow.
    const float s = settings_.noise.scale;
    const float lo = static_cast<float>(from) + 0.5f - kSharpenReach - shift;
    const float hi = static_cast<float>(from + size) - 0.5f + kSharpenReach - shift;
    const float first = std::floor((lo - 0.5f) / s) - 1.0f;  // a cell of margin
    const float last = std::floor((hi - 0.5f) / s) + 2.0f;
    return first >= 0.0f && last < static_cast<float>(count)
               ? glm::ivec2(static_cast<int>(first), static_cast<int>(last - first) + 1)
               : glm::ivec2(-1);
  };
  if (surface_box_.z <= 0 || surface_box_.w <= 0) return glm::ivec4(0);  // nothing to read
  const glm::ivec2 x = cells(surface_box_.x, surface_box_.z, noise_shift_.x, all.z);
  const glm::ivec2 y = cells(surface_box_.y, surface_box_.w, noise_shift_.y, all.w);
  return x.x < 0 || y.x < 0 ? all : glm::ivec4(x.x, y.x, x.y, y.y);
}

void IbfvsRenderer::run_deferred_statistics() {
  if (!statistics_due_) return;
  statistics_due_ = false;
  const gl::SavedState saved;
  gl::prepare_own_draw();
  statistics_pass(displayed_, frame_ - 1);
}

void IbfvsRenderer::statistics_pass(int texture_index, int frame) {
  bind_reads(planned_pass("stats"), texture_index, 1 - texture_index);
  stats_pass_.run(!feedback_.layout().colour, glm::ivec2(settings_.width, settings_.height), frame,
                  kStatsWeight);
}

void IbfvsRenderer::lock() {
  if (locked_) return;
  locked_ = true;
  lock_view_projection_ = previous_view_projection_;  // the view that made F_t
}

void IbfvsRenderer::unlock() {
  locked_ = false;  // previous_view_projection_ is still the view that made F_t
}

void IbfvsRenderer::fill_texture_with_cell_colors(std::uint32_t seed) {
  use_layout(true, true);  // colours need a colour texture (until reset())
  const int w = settings_.width, h = settings_.height;
  const float s = settings_.noise.scale;
  const int columns = static_cast<int>(std::ceil(static_cast<float>(w) / s)) + 1;
  std::vector<float> rgba(static_cast<std::size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto cell = static_cast<std::uint64_t>(static_cast<int>(static_cast<float>(y) / s)) *
                            static_cast<std::uint64_t>(columns) +
                        static_cast<std::uint64_t>(static_cast<float>(x) / s);
      float* p = &rgba[(static_cast<std::size_t>(y) * w + x) * 4];
      for (int c = 0; c < 3; ++c)
        p[c] = hash_uniform(seed, 3 * cell + static_cast<std::uint64_t>(c));
      p[3] = kAnyDepth;
    }
  feedback_.upload_colours(rgba);
}

ImageU8 IbfvsRenderer::read_output() const {
  ImageU8 image;
  read_output(image);
  return image;
}

void IbfvsRenderer::read_output(ImageU8& image) const {
  targets_.read_output(image);
}

ImageF IbfvsRenderer::read_texture_raw() const {
  return feedback_.read_raw(settings_.sharpen);
}

ImageF IbfvsRenderer::read_texture() const {
  const ImageF raw = read_texture_raw();
  ImageF image(settings_.width, settings_.height, 4);
  for (std::size_t i = 0; i < image.pixels.size() / 4; ++i) {
    float* p = &image.pixels[4 * i];
    const float* r = &raw.pixels[kRawChannels * i];
    if (feedback_.layout().colour)
      std::copy_n(r, 3, p);
    else
      p[0] = p[1] = p[2] = r[0];
    p[3] = 1.0f;
  }
  return image;
}

ImageF IbfvsRenderer::read_flow() const {
  return targets_.read_flow();
}

ImageF IbfvsRenderer::read_depth() const {
  return targets_.read_depth();
}

std::vector<std::uint8_t> IbfvsRenderer::read_coverage() const {
  const ImageF depth = read_depth();
  std::vector<std::uint8_t> covered(depth.pixels.size());
  for (std::size_t i = 0; i < covered.size(); ++i) covered[i] = depth.pixels[i] < 1.0f ? 1 : 0;
  return covered;
}

void IbfvsRenderer::draw_over_output(const std::function<void()>& draw) {
  targets_.display().bind();
  gl::set_viewport(settings_.width, settings_.height);
  draw();
}

void IbfvsRenderer::draw_to_host(glm::ivec2 origin, bool interior) {
  const gl::SavedState saved;
  gl::prepare_host_draw();
  gl::set_viewport(origin, settings_.width, settings_.height);  // the host's, put back after
  bind_reads(planned_pass("host"), feedback_.last(), feedback_.now());
  host_pass_.draw(origin, interior, surface_box_);
}

void IbfvsRenderer::write_texture_raw(const ImageF& texture) {
  feedback_.upload_raw(texture, settings_.sharpen);
}

void IbfvsRenderer::take_texture(const ImageF& raw, const ViewState& view) {
  if (raw.channels != kRawChannels || raw.width < 1 || raw.height < 1)
    throw InputError("renderer: take_texture needs an image of " + std::to_string(kRawChannels) +
                     " channels");
  // Nearest texel, in the image's own coordinates: the texture coordinates
  // T(r - v dt) are in [0, 1]^2 whatever the size. The taps' depth is
  // encoded again from the eye depth under this renderer's map.
  const int w = settings_.width, h = settings_.height;
  ImageF resampled(w, h, kRawChannels);
  for (int y = 0; y < h; ++y) {
    const int sy = std::min(raw.height - 1, static_cast<int>((y + 0.5) * raw.height / h));
    for (int x = 0; x < w; ++x) {
      const int sx = std::min(raw.width - 1, static_cast<int>((x + 0.5) * raw.width / w));
      for (int c = 0; c < kRawChannels; ++c) resampled.at(x, y, c) = raw.at(sx, sy, c);
      resampled.at(x, y, 5) = -1.0f;
    }
  }
  feedback_.set_tap_depth(feedback_.last(), tap_depth_map(view.projection));
  feedback_.upload_raw(resampled, settings_.sharpen);
  previous_view_projection_ = view.projection * view.view;
  last_view_ = view;
  has_previous_ = true;
}

ImageF IbfvsRenderer::read_output_raw() const {
  return targets_.read_output_raw();
}

void IbfvsRenderer::write_output_raw(const ImageF& output) {
  targets_.write_output_raw(output);
}

void IbfvsRenderer::set_probe_length(float world) {
  if (!(world > 0.0f) || !std::isfinite(world))
    throw InputError("renderer: the probe length must be a positive number");
  probe_ = world;
}

void IbfvsRenderer::finish() {
  gl::finish();
}

}  // namespace ibfvs
