// Distributed rendering without a cluster: two renderers, each with half of a
// mesh (two processes' pieces), composite F_t after every frame
// (core/image/composite.h) and must then show the single renderer's picture, seam
// included; without compositing they do not. draw_to_host puts the pieces
// into one host framebuffer by depth, as ParaView's compositing does.

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <unordered_map>
#include <utility>

#include <gtest/gtest.h>

#include "gl_fixture.h"
#include "ibfvs/core/image/composite.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/objects.h"
#include "ibfvs/render/ibfvs_renderer.h"

namespace ibfvs {
namespace {

class CompositeGLTest : public test::GlTest {};

struct Piece {
  TriMesh mesh;
  std::vector<glm::vec3> field;
};

// The triangles whose centroid lies on one side of the plane x = 0, with
// their own vertices (a process's piece: boundary vertices on both).
Piece half(const TriMesh& whole, const std::vector<glm::vec3>& field, bool left) {
  Piece p;
  std::unordered_map<std::uint32_t, std::uint32_t> index;
  for (const Triangle& t : whole.triangles) {
    const float cx =
        (whole.positions[t[0]].x + whole.positions[t[1]].x + whole.positions[t[2]].x) / 3.0f;
    if ((cx < 0.0f) != left) continue;
    Triangle out{};
    for (int k = 0; k < 3; ++k) {
      auto [it, fresh] = index.emplace(t[k], static_cast<std::uint32_t>(p.mesh.positions.size()));
      if (fresh) {
        p.mesh.positions.push_back(whole.positions[t[k]]);
        p.mesh.normals.push_back(whole.normals[t[k]]);
        p.field.push_back(field[t[k]]);
      }
      out[k] = it->second;
    }
    p.mesh.triangles.push_back(out);
  }
  return p;
}

// Two processes' collectives, run in one: each step sees both ranks' data
// (F_t, and F for the contrast statistics, which then run on the result).
void composite_pair(IbfvsRenderer& a, IbfvsRenderer& b) {
  const std::array<ImageF, 2> depth{a.read_depth(), b.read_depth()};
  std::array<std::vector<std::uint64_t>, 2> keys{composite_keys(depth[0], 0),
                                                 composite_keys(depth[1], 1)};
  for (std::size_t i = 0; i < keys[0].size(); ++i)
    keys[0][i] = keys[1][i] = std::min(keys[0][i], keys[1][i]);
  const auto both = [&](ImageF ta, ImageF tb) {
    keep_won_pixels(ta, keys[0], 0);
    keep_won_pixels(tb, keys[1], 1);
    for (std::size_t i = 0; i < ta.pixels.size(); ++i) ta.pixels[i] += tb.pixels[i];
    return ta;
  };
  const ImageF texture = both(a.read_texture_raw(), b.read_texture_raw());
  a.write_texture_raw(texture);
  b.write_texture_raw(texture);
  ASSERT_EQ(a.statistics_due(), b.statistics_due());
  if (a.statistics_due()) {
    const ImageF output = both(a.read_output_raw(), b.read_output_raw());
    a.write_output_raw(output);
    b.write_output_raw(output);
    a.run_deferred_statistics();
    b.run_deferred_statistics();
  }
}

struct Setup {
  PreparedScene scene;
  Camera camera;
};

Setup torus() {
  Scene s;
  s.mesh = "torus";
  s.width = 160;
  s.height = 120;
  apply_setting(s, "camera", "30,35,0");
  PreparedScene p = prepare_scene(s);
  Camera camera(mesh_bounds(*p.mesh), p.camera, 160.0f / 120.0f);
  return {std::move(p), camera};
}

// A host framebuffer (colour and depth) the renderers draw into.
struct Host {
  gl::Texture2D colour, depth;
  gl::Framebuffer fb;
  Host(int w, int h)
      : colour(w, h, gl::Format::RGBA8, false),
        depth(w, h, gl::Format::Depth24, false),
        fb(gl::Framebuffer::create()) {
    fb.attach_color(0, colour);
    fb.attach_depth(depth);
    fb.finish(1);
    fb.clear_color(0, glm::vec4(1.0f, 0.0f, 1.0f, 1.0f));  // magenta: the host's background
    fb.clear_depth();
  }
  std::vector<std::uint8_t> read(int w, int h) const {
    std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h * 4);
    fb.read_rgba8(0, w, h, out);
    return out;
  }
};

// Pixels whose colour differs by more than `tolerance` in some channel.
std::size_t differing(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
                      int tolerance = 2) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); i += 4)
    for (std::size_t c = 0; c < 3; ++c)
      if (std::abs(int(a[i + c]) - int(b[i + c])) > tolerance) {
        ++n;
        break;
      }
  return n;
}

std::vector<std::uint8_t> run(bool composite, std::vector<std::uint8_t>* single_out) {
  const Setup s = torus();
  const PreparedScene& p = s.scene;
  EXPECT_GT(p.settings.contrast, 0.0f);  // the default look: statistics composited too
  EXPECT_GT(p.settings.filter_length, 0.0f);
  const int w = p.width, h = p.height;
  const Piece left = half(*p.mesh, p.field, true), right = half(*p.mesh, p.field, false);
  EXPECT_GT(left.mesh.triangles.size(), 100u);
  EXPECT_GT(right.mesh.triangles.size(), 100u);
  IbfvsRenderer single(p.settings), a(p.settings), b(p.settings);
  single.set_mesh(*p.mesh, p.field);
  a.set_mesh(left.mesh, left.field);
  b.set_mesh(right.mesh, right.field);
  const float probe = 1e-3f * mesh_bounds(*p.mesh).diagonal();
  single.set_probe_length(probe);
  a.set_probe_length(probe);
  b.set_probe_length(probe);
  a.defer_statistics(composite);
  b.defer_statistics(composite);
  const ViewState view{s.camera.view(), s.camera.projection()};
  for (int k = 0; k < 40; ++k) {
    single.render_frame(view, p.dt);
    a.render_frame(view, p.dt);
    b.render_frame(view, p.dt);
    if (composite) composite_pair(a, b);
  }
  Host whole(w, h), pieces(w, h);
  whole.fb.bind();
  gl::set_viewport(w, h);
  single.draw_to_host({0, 0});
  pieces.fb.bind();
  a.draw_to_host({0, 0});
  b.draw_to_host({0, 0});
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (single_out) *single_out = whole.read(w, h);
  return pieces.read(w, h);
}

TEST_F(CompositeGLTest, TwoPiecesCompositedShowTheSingleRenderersPicture) {
  std::vector<std::uint8_t> single;
  const std::vector<std::uint8_t> pieces = run(true, &single);
  // The host's background where there is no surface, and the torus covers a good part.
  std::size_t background = 0;
  for (std::size_t i = 0; i < single.size(); i += 4)
    background += single[i] == 255 && single[i + 1] == 0 && single[i + 2] == 255;
  EXPECT_GT(background, single.size() / 4 / 5);
  EXPECT_LT(background, single.size() / 4 * 4 / 5);
  // Equal up to rounding (llvmpipe: identical): no seam where the pieces meet.
  EXPECT_LE(differing(single, pieces), single.size() / 4 / 1000);
}

TEST_F(CompositeGLTest, WithoutCompositingTheSeamShows) {
  std::vector<std::uint8_t> single;
  const std::vector<std::uint8_t> pieces = run(false, &single);
  // Each piece advects from its own F_t: along the boundary the other
  // piece's pixels count as background, fresh noise appears there.
  EXPECT_GT(differing(single, pieces), single.size() / 4 / 200);
}

// ParaView antialiases its picture with FXAA after the opaque geometry; the
// mapper then draws the texture again, only inside the silhouettes. The host's
// colour stands for FXAA's result: replaced inside, kept at the silhouettes
// and off the surface, and the host's depth (the texture's own) lets it pass.
TEST_F(CompositeGLTest, DrawingAgainInsideTheSilhouettesKeepsTheirAntialiasing) {
  const auto s = torus();  // (Setup is also gtest's name)
  const PreparedScene& p = s.scene;
  const int w = p.width, h = p.height;
  IbfvsRenderer r(p.settings);
  r.set_mesh(*p.mesh, p.field);
  const ViewState view{s.camera.view(), s.camera.projection()};
  for (int k = 0; k < 10; ++k) r.render_frame(view, p.dt);
  Host host(w, h);
  host.fb.bind();
  gl::set_viewport(w, h);
  r.draw_to_host({0, 0});
  const std::vector<std::uint8_t> first = host.read(w, h);
  host.fb.clear_color(0, glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));  // "FXAA's" picture: green
  host.fb.bind();
  r.draw_to_host({0, 0}, true);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const std::vector<std::uint8_t> again = host.read(w, h);
  const ImageF depth = r.read_depth();
  // Surface at (x, y), clamped to the image as the shader's reads are.
  const auto surface = [&](int x, int y) {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return depth.pixels[std::size_t(y) * w + x] < 1.0f;
  };
  std::size_t inside = 0, rim = 0, wrong = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = (std::size_t(y) * w + x) * 4;
      const bool green = again[i] == 0 && again[i + 1] == 255 && again[i + 2] == 0;
      // Its 3x3 neighbourhood but two corners (the shader's two gathers).
      bool interior = true;
      for (const auto& [dx, dy] :
           {std::pair{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, 1}})
        interior = interior && surface(x + dx, y + dy);
      if (interior) {
        ++inside;
        wrong += std::abs(int(again[i]) - int(first[i])) > 1 ||
                 std::abs(int(again[i + 1]) - int(first[i + 1])) > 1;
      } else {
        rim += surface(x, y);
        wrong += !green;
      }
    }
  EXPECT_GT(inside, std::size_t(w) * h / 5);
  EXPECT_GT(rim, 100u);
  EXPECT_EQ(wrong, 0u);
}

TEST(CompositeTest, KeysPickTheNearestSurfaceAndTheLowerRankOnTies) {
  ImageF d0(3, 1, 1), d1(3, 1, 1);
  d0.pixels = {0.25f, 1.0f, 0.5f};
  d1.pixels = {0.75f, 1.0f, 0.5f};
  auto k0 = composite_keys(d0, 0);
  const auto k1 = composite_keys(d1, 1);
  for (std::size_t i = 0; i < 3; ++i) k0[i] = std::min(k0[i], k1[i]);
  ImageF t0(3, 1, 2, 7.0f), t1(3, 1, 2, 9.0f);
  keep_won_pixels(t0, k0, 0);
  keep_won_pixels(t1, k0, 1);
  EXPECT_EQ(t0.pixels, (std::vector<float>{7, 7, 7, 7, 7, 7}));  // nearest; nobody; a tie
  EXPECT_EQ(t1.pixels, (std::vector<float>{0, 0, 0, 0, 0, 0}));
  ImageF bad(1, 1, 1, 2.0f);
  EXPECT_THROW(composite_keys(bad, 0), InputError);
  EXPECT_THROW(keep_won_pixels(t0, std::span<const std::uint64_t>(k0).first(2), 0), InputError);
}

TEST(CompositeTest, AGroupOfOneLeavesTheTextureAlone) {
  ImageF t(2, 2, 2, 3.0f), d(2, 2, 1, 0.5f);
  CompositeGroup one;
  one.min_all = [](std::span<std::uint64_t>) { FAIL() << "no reduction in a group of one"; };
  one.sum_all = [](std::span<float>) { FAIL() << "no reduction in a group of one"; };
  ImageF* images[] = {&t};
  composite_nearest(images, d, one);
  EXPECT_EQ(t.pixels, std::vector<float>(8, 3.0f));
}

}  // namespace
}  // namespace ibfvs
