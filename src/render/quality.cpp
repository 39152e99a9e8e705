#include "ibfvs/render/quality.h"

#include <chrono>
#include <cmath>
#include <vector>

#include "ibfvs/render/session.h"

namespace ibfvs {
namespace {

ImageF to_float(const ImageU8& image) {
  ImageF out(image.width, image.height, 3);
  for (std::size_t i = 0; i < out.pixels.size() / 3; ++i)
    for (int c = 0; c < 3; ++c)
      out.pixels[3 * i + c] = static_cast<float>(image.pixels[i * image.channels + c]) / 255.0f;
  return out;
}

}  // namespace

QualityReport measure_quality(PreparedScene scene, int warmup, bool shown) {
  if (!shown) {
    scene.settings.beta = 1.0f;
    scene.settings.background = glm::vec3(1.0f, 0.0f, 0.0f);
    scene.settings.use_beta = false;
  }
  scene.scene.orbit = 0.0f;
  scene.lock_at = Scene::kLockNever;
  QualityReport report;
  report.width = scene.width;
  report.height = scene.height;
  report.warmup = warmup;
  Session session(std::move(scene));
  const IbfvsRenderer& renderer = session.renderer();
  session.record_flow(true);
  for (int k = 0; k < warmup; ++k) session.advance();

  constexpr int kMeasured = 17;
  std::vector<ImageF> frames;
  std::vector<double> contrasts;
  ImageF flow;
  std::vector<std::uint8_t> mask;
  double seconds = 0.0;
  for (int k = 0; k < kMeasured; ++k) {
    const auto start = std::chrono::steady_clock::now();
    session.advance();
    frames.push_back(to_float(renderer.read_output()));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (k == 0) {
      flow = renderer.read_flow();
      mask = renderer.read_coverage();
    }
    contrasts.push_back(rms_contrast(frames.back(), mask));
  }
  report.frame_ms = 1e3 * seconds / kMeasured;
  std::size_t covered = 0;
  for (const std::uint8_t m : mask) covered += m;
  report.coverage = static_cast<double>(covered) / static_cast<double>(mask.size());

  const ImageF& last = frames.back();
  const ImageF grey = luminance(last);
  const auto direction = [&](float x, float y) {
    const int xi = static_cast<int>(x), yi = static_cast<int>(y);
    return glm::vec2(flow.at(xi, yi, 0), flow.at(xi, yi, 1));
  };
  // The texture alone (beta 1): its first channel (the grey texture's
  // channels are equal); as shown: the luminance.
  report.alignment = flow_alignment(shown ? grey : last, mask, direction, 4);
  report.streak_width = streak_width(shown ? grey : last, mask, direction, 4);
  report.grain = grain_along(shown ? grey : last, mask, direction, 4);
  report.red_inflow = shown ? std::nan("") : red_tinted_fraction(last, mask);
  report.lag8 = pattern_motion(frames[kMeasured - 9], last, flow, mask, 8);
  report.lag16 = pattern_motion(frames[0], last, flow, mask, 16);
  report.carried = pattern_motion(frames[kMeasured - 2], last, flow, mask, 1).at_flow;
  double sum = 0, squares = 0;
  for (const double c : contrasts) sum += c, squares += c * c;
  report.contrast = sum / kMeasured;
  const double spread =
      std::sqrt(std::max(squares / kMeasured - report.contrast * report.contrast, 0.0));
  report.contrast_spread = report.contrast > 0 ? spread / report.contrast : 0.0;
  return report;
}

}  // namespace ibfvs
