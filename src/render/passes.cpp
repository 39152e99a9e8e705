#include "ibfvs/render/passes.h"

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "ibfvs/core/texture/display.h"
#include "ibfvs/render/shaders.h"

namespace ibfvs {
namespace {

void set_uniform(const gl::Program& p, const shaders::UniformValue& u) {
  const int location = p.location(u.name.c_str());
  const auto f = [&](std::size_t i) { return static_cast<float>(u.values[i]); };
  const auto n = [&](std::size_t i) { return static_cast<int>(u.values[i]); };
  using T = shaders::UniformValue::Type;
  if (u.array) {
    std::vector<float> values(u.values.begin(), u.values.end());
    p.set(location, std::span<const float>(values));
  } else if (u.type == T::Uint) {
    p.set(location, static_cast<std::uint32_t>(u.values[0]));
  } else if (u.type == T::Int) {
    if (u.values.size() == 1)
      p.set(location, n(0));
    else
      p.set(location, glm::ivec2(n(0), n(1)));
  } else if (u.values.size() == 1) {
    p.set(location, f(0));
  } else if (u.values.size() == 2) {
    p.set(location, glm::vec2(f(0), f(1)));
  } else {
    p.set(location, glm::vec3(f(0), f(1), f(2)));
  }
}

}  // namespace

IbfvsPrograms::IbfvsPrograms(const shaders::ShaderFeatures& f, bool deferred) {
  if (deferred) {
    mesh_ = gl::Program(shaders::ibfvs_vertex_source(f), shaders::gbuffer_fragment_source(f));
    resolve_ = gl::Program(shaders::display_vertex_source(), shaders::resolve_fragment_source(f));
    ru_ = locations(resolve_);
  } else {
    mesh_ = gl::Program(shaders::ibfvs_vertex_source(f), shaders::ibfvs_fragment_source(f));
  }
  u_ = locations(mesh_);
  if (shaders::tap_texture(f) && !deferred) {
    display_ = gl::Program(shaders::display_vertex_source(), shaders::display_fragment_source(f));
    display_texture_shift_ = display_.location("u_texture_shift");
    display_tap_depth_ = display_.location("u_tap_depth");
  }
}

IbfvsPrograms::Uniforms IbfvsPrograms::locations(const gl::Program& p) {
  Uniforms u{};
  u.view_projection = p.location("u_view_projection");
  u.advect_view_projection = p.location("u_advect_view_projection");
  u.view = p.location("u_view");
  u.clip_to_depth = p.location("u_clip_to_depth");
  u.dt = p.location("u_dt");
  u.noise_time = p.location("u_noise_time");
  u.field_mix = p.location("u_field_mix");
  u.locked = p.location("u_locked");
  u.probe = p.location("u_probe");
  u.texture_shift = p.location("u_texture_shift");
  u.noise_shift = p.location("u_noise_shift");
  u.tap_depth = p.location("u_tap_depth");
  u.new_tap_depth = p.location("u_new_tap_depth");
  u.drawn_mix = p.location("u_drawn_mix");
  return u;
}

void IbfvsPrograms::apply(const std::vector<shaders::UniformValue>& uniforms) const {
  for (const shaders::UniformValue& u : uniforms) {
    set_uniform(mesh_, u);
    if (resolve_) set_uniform(resolve_, u);
    if (display_) set_uniform(display_, u);
  }
}

void IbfvsPrograms::set(const gl::Program& p, const Uniforms& u, const IbfvsFrame& frame) {
  p.set(u.view_projection, frame.projection * frame.view);
  p.set(u.advect_view_projection, frame.advect_view_projection);
  p.set(u.view, frame.view);
  // Eye depth d = -z_eye from clip (z, w): w = -z_eye in perspective
  // (P[2][3] = -1, P[3][3] = 0); z = P[2][2] z_eye + P[3][2] with w = 1 in
  // orthographic projection.
  const glm::mat4& pr = frame.projection;
  p.set(u.clip_to_depth, pr[3][3] == 0.0f ? glm::vec2(0.0f, 1.0f)
                                          : glm::vec2(-1.0f / pr[2][2], pr[3][2] / pr[2][2]));
  p.set(u.dt, frame.dt);
  p.set(u.probe, frame.probe);
  p.set(u.field_mix, frame.field_mix);
  p.set(u.drawn_mix, frame.drawn_mix);
  p.set(u.texture_shift, frame.texture_shift);
  p.set(u.noise_shift, frame.noise_shift);
  p.set(u.locked, frame.locked ? 1 : 0);
  p.set(u.noise_time, frame.noise_time);
  // The map of the frame being drawn; -1 without the tap texture: GL ignores it.
  p.set(u.tap_depth, frame.tap_depth);
}

void IbfvsPrograms::set_frame(const IbfvsFrame& frame) const {
  set(mesh_, u_, frame);
  if (resolve_) {
    set(resolve_, ru_, frame);
    // It reads the last frame's taps, stored under that frame's map.
    resolve_.set(ru_.tap_depth, frame.last_tap_depth);
    resolve_.set(ru_.new_tap_depth, frame.tap_depth);
  }
  if (display_) {
    display_.set(display_texture_shift_, frame.texture_shift);
    // The taps it reads are the last frame's, stored under that frame's map.
    display_.set(display_tap_depth_, frame.last_tap_depth);
  }
}

GridPass::GridPass(const NoiseGrid& grid)
    : phases_(grid.columns(), grid.rows(), gl::Format::R32F, false),
      // G_ij, sampled bilinearly: equation 7.
      grid_(grid.columns(), grid.rows(), gl::Format::R32F, true),
      framebuffer_(gl::Framebuffer::create()),
      program_(shaders::grid_vertex_source(), shaders::grid_fragment_source()),
      empty_(gl::VertexArray::create()) {
  phases_.upload_float(grid.phases(), 1);
  grid_.set_repeat(true);
  framebuffer_.attach_color(0, grid_);
  framebuffer_.finish(1);
  noise_time_ = program_.location("u_noise_time");
  profile_ = program_.location("u_profile");
  spike_width_ = program_.location("u_spike_width");
  seed_ = program_.location("u_seed");
}

void GridPass::apply(const NoiseParams& noise) const {
  program_.set(profile_, static_cast<int>(noise.profile));
  program_.set(spike_width_, noise.spike_width);
  program_.set(seed_, noise.seed);
}

void GridPass::run(float noise_time, glm::ivec4 box) {
  framebuffer_.bind();
  gl::set_viewport(grid_.width(), grid_.height());
  gl::enable_depth_test(false);
  gl::set_face_culling(0);
  program_.use();
  program_.set(noise_time_, noise_time);
  // Only the cells the surface can read: the whole grid is a full-screen
  // pass of two hashes per cell (in ParaView, 5 ms of the motorbike's 90;
  // the box saves 3 of them).
  gl::scissor(true, box);
  gl::draw_attributeless_triangle(empty_);
  gl::scissor(false);
}

StatsPass::StatsPass()
    : stats_(1, 1, gl::Format::RGBA32F, false),
      framebuffer_(gl::Framebuffer::create()),
      empty_(gl::VertexArray::create()) {
  framebuffer_.attach_color(0, stats_);
  framebuffer_.finish(1);
  for (const int grey : {0, 1}) {
    Program& p = programs_[grey];
    p.program =
        gl::Program(shaders::grid_vertex_source(), shaders::stats_fragment_source(grey == 1));
    p.image_size = p.program.location("u_image_size");
    p.stats_size = p.program.location("u_stats_size");
    p.offset = p.program.location("u_offset");
  }
}

void StatsPass::clear() {
  framebuffer_.clear_color(0, glm::vec4(0.0f));
}

void StatsPass::run(bool grey, glm::ivec2 size, int frame, float weight) {
  const Program& p = programs_[grey ? 1 : 0];
  framebuffer_.bind();
  gl::set_viewport(stats_.width(), stats_.height());
  gl::enable_depth_test(false);
  gl::set_face_culling(0);
  p.program.use();
  p.program.set(p.image_size, glm::vec2(size));
  p.program.set(p.stats_size, display_stats_size(size.x, size.y));
  // Golden-ratio steps: the grid visits other pixels every frame.
  const auto f = static_cast<float>(frame);
  p.program.set(p.offset,
                glm::vec2(std::fmod(f * 0.6180340f, 1.0f), std::fmod(f * 0.3819660f, 1.0f)));
  gl::set_running_average(weight);
  gl::draw_attributeless_triangle(empty_);
  gl::set_running_average(0.0f);
}

HostPass::HostPass()
    : program_(shaders::grid_vertex_source(), shaders::host_fragment_source()),
      empty_(gl::VertexArray::create()) {
  origin_ = program_.location("u_origin");
  interior_ = program_.location("u_interior");
}

void HostPass::draw(glm::ivec2 origin, bool interior, glm::ivec4 box) {
  program_.use();
  program_.set(origin_, origin);
  program_.set(interior_, interior ? 1 : 0);
  gl::scissor(true, box + glm::ivec4(origin, 0, 0));
  gl::draw_attributeless_triangle(empty_);
}

}  // namespace ibfvs
