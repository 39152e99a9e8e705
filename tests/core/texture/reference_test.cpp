#include <cmath>

#include <gtest/gtest.h>

#include "ibfvs/core/texture/reference.h"

namespace ibfvs {
namespace {

// A map that covers the pixels inside [x0, x1) x [y0, y1) and moves them by `shift`.
BackwardMap translation_map(int w, int h, glm::vec2 shift, int x0, int x1, int y0, int y1) {
  BackwardMap m;
  m.width = w;
  m.height = h;
  m.covered.assign(static_cast<std::size_t>(w) * h, 0);
  m.source.assign(static_cast<std::size_t>(w) * h, glm::vec2(0));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      m.covered[i] = x >= x0 && x < x1 && y >= y0 && y < y1;
      m.source[i] = glm::vec2(x + 0.5f, y + 0.5f) - shift;
    }
  return m;
}

TEST(Reference, StillFieldConvergesToTheNoise) {
  NoiseParams p;
  p.rate = 0.0f;
  ReferenceIbfvs ref(32, 32, 0.5f, p);
  const BackwardMap map = translation_map(32, 32, {0, 0}, 0, 32, 0, 32);
  const float alpha = 0.2f;
  for (int k = 0; k < 80; ++k) ref.step(map, k, alpha);
  const NoiseGrid g(32, 32, p);
  for (int y = 0; y < 32; y += 5)
    for (int x = 0; x < 32; x += 3)
      EXPECT_NEAR(ref.texture().at(x, y), g.sample(x + 0.5f, y + 0.5f, 0), 1e-4f);
}

TEST(Reference, BackgroundOutsideTheSurface) {
  NoiseParams p;
  ReferenceIbfvs ref(32, 32, 0.25f, p);
  const BackwardMap map = translation_map(32, 32, {1.5f, 0.5f}, 8, 24, 8, 24);
  for (int k = 0; k < 30; ++k) ref.step(map, k, 0.1f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      if (!map.covered[static_cast<std::size_t>(y) * 32 + x]) {
        EXPECT_EQ(ref.texture().at(x, y), 0.25f);
      }
}

TEST(Reference, IntegerTranslationMovesTheTexture) {
  // alpha = 0: pure transport (equation 4); a shift by whole pixels is exact.
  NoiseParams p;
  ReferenceIbfvs ref(16, 16, 0.5f, p);
  const BackwardMap fill = translation_map(16, 16, {0, 0}, 0, 16, 0, 16);
  for (int k = 0; k < 5; ++k) ref.step(fill, k, 0.7f);
  const ImageF before = ref.texture();
  ref.step(translation_map(16, 16, {2, 0}, 0, 16, 0, 16), 5, 0.0f);
  for (int y = 0; y < 16; ++y)
    for (int x = 2; x < 16; ++x) EXPECT_EQ(ref.texture().at(x, y), before.at(x - 2, y));
}

}  // namespace
}  // namespace ibfvs
