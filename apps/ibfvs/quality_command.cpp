#include "ibfvs/quality_command.h"

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <CLI/CLI.hpp>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/image/image_analysis.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/render/quality.h"
#include "ibfvs/render_command.h"

namespace ibfvs::app {

void add_quality_options(CLI::App& command, SceneOptions& scene, QualityOptions& options) {
  add_scene_options(command, scene);
  command.add_option("--warmup", options.warmup, "Frames before measuring")
      ->check(CLI::Range(1, 100000));
  command.add_option("--png", options.png,
                     "Measure this picture instead (another tool's, of a flow turning about the "
                     "view axis): alignment and contrast where it differs from its corner pixel");
  command
      .add_option("--centre", options.centre,
                  "X,Y: the rotation's centre in the picture in pixels from the top left "
                  "(default: the middle)")
      ->delimiter(',')
      ->expected(2);
  command.add_option("--direction", options.direction,
                     "With --png: the true flow direction per pixel of the same view, "
                     "direction-coded (red, green: 0.5 + 0.5 x, y of the unit direction, y up; "
                     "blue 255 where defined), instead of a rotation");
  command.add_flag("--shown", options.shown,
                   "Measure the picture as shown (beta, shading, background of the scene) "
                   "instead of the texture alone (beta 1, red background)");
}

namespace {

// The picture's luminance and its surface: where the direction picture
// defines a direction, or (no direction picture) where it differs from its
// corner pixel.
int measure_picture(const QualityOptions& o) {
  const ImageU8 picture = read_png(o.png);  // rows bottom-up
  const int w = picture.width, h = picture.height;
  ImageU8 direction;
  if (!o.direction.empty()) {
    direction = read_png(o.direction);
    if (direction.width != w || direction.height != h || direction.channels < 3)
      throw InputError(o.direction + ": must be an RGB picture of " + std::to_string(w) + "x" +
                       std::to_string(h) + " pixels, as " + o.png);
  }
  ImageF rgb(w, h, 3);
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(w) * h);
  const auto px = [&](std::size_t i, int c) {
    return picture.pixels[i * picture.channels + std::min(c, picture.channels - 1)];
  };
  for (std::size_t i = 0; i < mask.size(); ++i) {
    bool background = true;
    for (int c = 0; c < 3; ++c) background = background && px(i, c) == px(0, c);
    for (int c = 0; c < 3; ++c) rgb.pixels[3 * i + c] = static_cast<float>(px(i, c)) / 255.0f;
    mask[i] = direction.pixels.empty()
                  ? (background ? 0 : 1)
                  : (direction.pixels[i * direction.channels + 2] >= 128 ? 1 : 0);
  }
  const ImageF image = luminance(rgb);
  std::function<glm::vec2(float, float)> flow;
  std::string what;
  if (!direction.pixels.empty()) {
    flow = [&](float x, float y) {
      const std::size_t i =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      const std::uint8_t* d = &direction.pixels[i * direction.channels];
      return glm::vec2(d[0] / 127.5f - 1.0f, d[1] / 127.5f - 1.0f);
    };
    what = "the flow of " + o.direction;
  } else {
    // Bottom-up rows: y up from the bottom; the centre is given from the top.
    const float cx = o.centre.empty() ? 0.5f * static_cast<float>(w) : o.centre[0];
    const float cy =
        o.centre.empty() ? 0.5f * static_cast<float>(h) : static_cast<float>(h) - o.centre[1];
    flow = [w, cx, cy](float x, float y) {
      const glm::vec2 d(x - cx, y - cy);
      // Too close to the centre the direction is ill-defined.
      return glm::length(d) < 0.04f * static_cast<float>(w) ? glm::vec2(0) : glm::vec2(-d.y, d.x);
    };
    char text[96];
    std::snprintf(text, sizeof text, "a flow turning about (%.1f, %.1f)", cx,
                  static_cast<float>(h) - cy);
    what = text;
  }
  std::size_t covered = 0;
  for (const std::uint8_t m : mask) covered += m;
  std::printf("%s, %dx%d, %s:\n", o.png.c_str(), w, h, what.c_str());
  std::printf("  surface covers            %.1f%% of the image\n",
              100.0 * static_cast<double>(covered) / static_cast<double>(mask.size()));
  std::printf("  alignment A               %.3f   (0.5 isotropic, 1 perfect streaks)\n",
              flow_alignment(image, mask, flow, 4));
  std::printf("  streak width W            %.2f px (across the flow; 0.8 thin lines)\n",
              streak_width(image, mask, flow, 4));
  std::printf("  grain along Z             %.3f   (along the lines against across; LIC 0.1)\n",
              grain_along(image, mask, flow, 4));
  std::printf("  RMS contrast              %.3f\n", rms_contrast(image, mask));
  return 0;
}

}  // namespace

int run_quality(const SceneOptions& scene_options, const QualityOptions& options) {
  if (!options.png.empty()) return measure_picture(options);
  const Scene scene = scene_from_command_line(scene_options);
  PreparedScene prepared = prepare_scene(scene);
  for (const std::string& w : prepared.warnings)
    std::fprintf(stderr, "ibfvs: warning: %s\n", w.c_str());
  const std::string name = prepared.mesh_name;
  gl::HeadlessContext context;
  const QualityReport r = measure_quality(std::move(prepared), options.warmup, options.shown);
  context.throw_if_errors();
  std::printf("%s, %dx%d, measured after %d frames (%s, still camera):\n", name.c_str(), r.width,
              r.height, r.warmup,
              options.shown ? "as shown" : "the texture alone: beta 1, red background");
  std::printf("  surface covers            %.1f%% of the image\n", 100.0 * r.coverage);
  std::printf("  alignment A               %.3f   (0.5 isotropic, 1 perfect streaks)\n",
              r.alignment);
  std::printf("  streak width W            %.2f px (across the flow; 0.8 thin lines)\n",
              r.streak_width);
  std::printf("  grain along Z             %.3f   (along the lines against across; LIC 0.1)\n",
              r.grain);
  if (!options.shown)
    std::printf("  red inflow                %.2f%%  of the surface pixels\n",
                100.0 * r.red_inflow);
  std::printf("  pattern speed / flow      %.2f (lag 8), %.2f (lag 16)   (1 moves with the flow)\n",
              r.lag8.ratio, r.lag16.ratio);
  std::printf("  correlation lag 16        %.3f along the flow, %.3f in place\n", r.lag16.at_flow,
              r.lag16.still);
  std::printf("  carried frame to frame    %.3f   (correlation along the flow; 1: no flicker)\n",
              r.carried);
  std::printf("  RMS contrast              %.3f, varying %.2f%% over 17 frames\n", r.contrast,
              100.0 * r.contrast_spread);
  std::printf("  frame time                %.2f ms (with read-back)\n", r.frame_ms);
  return 0;
}

}  // namespace ibfvs::app
