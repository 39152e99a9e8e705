#include "ibfvs/core/image/image_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

ImageF luminance(const ImageF& rgb) {
  if (rgb.channels < 3) throw InputError("luminance: needs an RGB image");
  ImageF out(rgb.width, rgb.height, 1);
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    const float* p = &rgb.pixels[i * static_cast<std::size_t>(rgb.channels)];
    out.pixels[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
  }
  return out;
}

ImageF gaussian_blur(const ImageF& image, float sigma) {
  constexpr int r = 2;
  float k[2 * r + 1];
  float sum = 0.0f;
  for (int i = -r; i <= r; ++i) sum += k[i + r] = std::exp(-0.5f * i * i / (sigma * sigma));
  for (float& v : k) v /= sum;
  const auto pass = [&](const ImageF& src, int dx, int dy) {
    ImageF dst = src;
    for (int y = 0; y < src.height; ++y)
      for (int x = 0; x < src.width; ++x)
        for (int c = 0; c < src.channels; ++c) {
          float acc = 0.0f;
          for (int i = -r; i <= r; ++i) {
            const int xx = std::clamp(x + i * dx, 0, src.width - 1);
            const int yy = std::clamp(y + i * dy, 0, src.height - 1);
            acc += k[i + r] * src.at(xx, yy, c);
          }
          dst.at(x, y, c) = acc;
        }
    return dst;
  };
  return pass(pass(image, 1, 0), 0, 1);
}

namespace {

// The masked pixels at least `margin` pixels (Chebyshev) from any unmasked one.
std::vector<std::uint8_t> eroded(const std::vector<std::uint8_t>& mask, int w, int h, int margin) {
  std::vector<std::uint8_t> inner = mask;
  for (int step = 0; step < margin + 1; ++step) {
    std::vector<std::uint8_t> next = inner;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!inner[y * w + x]) continue;
        for (int dy = -1; dy <= 1 && next[y * w + x]; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= w || yy >= h || !inner[yy * w + xx]) {
              next[y * w + x] = 0;
              break;
            }
          }
      }
    inner.swap(next);
  }
  return inner;
}

// Calls visit(x, y, centre, unit) for each pixel of `inner` whose flow at
// its centre is not zero, with that centre and the flow's unit direction.
template <typename Visit>
void for_each_flow_pixel(const std::vector<std::uint8_t>& inner, int w, int h,
                         const std::function<glm::vec2(float, float)>& flow, Visit&& visit) {
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!inner[static_cast<std::size_t>(y) * w + x]) continue;
      const glm::vec2 centre(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const glm::vec2 f = flow(centre.x, centre.y);
      const float len = glm::length(f);
      if (!(len > 0.0f)) continue;
      visit(x, y, centre, f / len);
    }
}

}  // namespace

double flow_alignment(const ImageF& image, const std::vector<std::uint8_t>& mask,
                      const std::function<glm::vec2(float, float)>& flow, int margin) {
  const int w = image.width, h = image.height;
  const std::vector<std::uint8_t> inner = eroded(mask, w, h, margin);
  const ImageF blurred = gaussian_blur(image, 1.0f);
  double along = 0.0, total = 0.0;
  for (int y = 1; y < h - 1; ++y)
    for (int x = 1; x < w - 1; ++x) {
      if (!inner[y * w + x]) continue;
      const auto p = [&](int dx, int dy) { return blurred.at(x + dx, y + dy, 0); };
      const float gx = (p(1, -1) + 2 * p(1, 0) + p(1, 1)) - (p(-1, -1) + 2 * p(-1, 0) + p(-1, 1));
      const float gy = (p(-1, 1) + 2 * p(0, 1) + p(1, 1)) - (p(-1, -1) + 2 * p(0, -1) + p(1, -1));
      glm::vec2 f = flow(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const float len = glm::length(f);
      if (!(len > 0.0f)) continue;
      f /= len;
      const glm::vec2 n(-f.y, f.x);
      const double gn = gx * n.x + gy * n.y;
      along += gn * gn;
      total += static_cast<double>(gx) * gx + static_cast<double>(gy) * gy;
    }
  return total > 0.0 ? along / total : std::numeric_limits<double>::quiet_NaN();
}

double streak_width(const ImageF& image, const std::vector<std::uint8_t>& mask,
                    const std::function<glm::vec2(float, float)>& flow, int margin) {
  const int w = image.width, h = image.height;
  if (mask.size() != static_cast<std::size_t>(w) * h)
    throw InputError("streak_width: the mask must match the image");
  const std::vector<std::uint8_t> inner = eroded(mask, w, h, margin);
  // Band-pass: a Gaussian of 0.7 pixels minus the mean over 9 x 9 pixels
  // (summed-area table), on the first channel.
  const ImageF fine = gaussian_blur(image.select_channels(0, 1), 0.7f);
  std::vector<double> sat(static_cast<std::size_t>(w + 1) * (h + 1), 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      sat[(y + 1) * (w + 1) + x + 1] = image.at(x, y, 0) + sat[y * (w + 1) + x + 1] +
                                       sat[(y + 1) * (w + 1) + x] - sat[y * (w + 1) + x];
  ImageF band(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int x0 = std::max(x - 4, 0), x1 = std::min(x + 5, w);
      const int y0 = std::max(y - 4, 0), y1 = std::min(y + 5, h);
      const double box = sat[y1 * (w + 1) + x1] - sat[y0 * (w + 1) + x1] - sat[y1 * (w + 1) + x0] +
                         sat[y0 * (w + 1) + x0];
      band.at(x, y) = fine.at(x, y) - static_cast<float>(box / ((x1 - x0) * (y1 - y0)));
    }
  struct Sample {
    float x, y, nx, ny, value;
  };
  std::vector<Sample> samples;
  for_each_flow_pixel(inner, w, h, flow, [&](int x, int y, glm::vec2 c, glm::vec2 u) {
    samples.push_back({c.x, c.y, -u.y, u.x, band.at(x, y)});
  });
  if (samples.size() < 16) return std::numeric_limits<double>::quiet_NaN();
  // The correlation of the band-passed picture with itself shifted s pixels
  // along each pixel's normal to the flow; W is where it falls below 0.5.
  const auto correlation = [&](float s) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
    for (const Sample& p : samples) {
      const float qx = p.x + s * p.nx, qy = p.y + s * p.ny;
      const int xi = static_cast<int>(std::floor(qx)), yi = static_cast<int>(std::floor(qy));
      if (xi < 0 || yi < 0 || xi >= w || yi >= h || !mask[static_cast<std::size_t>(yi) * w + xi])
        continue;
      const double a = p.value, b = sample_bilinear(band, qx, qy, 0);
      sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, n += 1;
    }
    if (n < 2) return 0.0;
    const double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
    return va > 0 && vb > 0 ? (sab / n - (sa / n) * (sb / n)) / std::sqrt(va * vb) : 0.0;
  };
  constexpr float kStep = 0.05f;
  double last = 1.0;
  for (int k = 1; k <= 200; ++k) {
    const double c = correlation(kStep * static_cast<float>(k));
    if (c < 0.5) return kStep * (k - 1 + (last - 0.5) / (last - c));
    last = c;
  }
  return kStep * 200;
}

double grain_along(const ImageF& image, const std::vector<std::uint8_t>& mask,
                   const std::function<glm::vec2(float, float)>& flow, int margin) {
  const int w = image.width, h = image.height;
  if (mask.size() != static_cast<std::size_t>(w) * h)
    throw InputError("grain_along: the mask must match the image");
  const std::vector<std::uint8_t> inner = eroded(mask, w, h, std::max(margin, 2));
  double along = 0.0, across = 0.0;
  std::size_t n = 0;
  for_each_flow_pixel(inner, w, h, flow, [&](int x, int y, glm::vec2 c, glm::vec2 u) {
    const auto second = [&](glm::vec2 d) {
      return 2.0 * image.at(x, y, 0) - sample_bilinear(image, c.x + d.x, c.y + d.y, 0) -
             sample_bilinear(image, c.x - d.x, c.y - d.y, 0);
    };
    const double a = second(u), b = second(glm::vec2(-u.y, u.x));
    along += a * a;
    across += b * b;
    ++n;
  });
  if (n < 16 || !(across > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return along / across;
}

namespace {

double channel_mean(const ImageF& image, int x, int y) {
  const int n = std::min(image.channels, 3);
  double sum = 0.0;
  for (int c = 0; c < n; ++c) sum += image.at(x, y, c);
  return sum / n;
}

double bilinear_mean(const ImageF& image, float x, float y) {
  const int n = std::min(image.channels, 3);
  double sum = 0.0;
  for (int c = 0; c < n; ++c) sum += sample_bilinear(image, x, y, c);
  return sum / n;
}

}  // namespace

PatternMotion pattern_motion(const ImageF& before, const ImageF& after, const ImageF& flow,
                             const std::vector<std::uint8_t>& mask, int lag) {
  const int w = after.width, h = after.height;
  if (before.width != w || before.height != h || flow.width != w || flow.height != h ||
      flow.channels != 2 || mask.size() != static_cast<std::size_t>(w) * h || lag < 1)
    throw InputError("pattern_motion: images, flow (2 channels) and mask must match, lag >= 1");
  const auto masked = [&](float x, float y) {
    const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
    return xi >= 0 && yi >= 0 && xi < w && yi < h && mask[static_cast<std::size_t>(yi) * w + xi];
  };
  PatternMotion result;
  result.best = -2.0;
  for (int step = 0; step <= 30; ++step) {
    const double r = 0.05 * step;
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
    for (int y = 0; y < h; y += 2)
      for (int x = 0; x < w; x += 2) {
        if (!mask[static_cast<std::size_t>(y) * w + x]) continue;
        float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
        bool on = true;
        for (int k = 0; k < lag && on; ++k) {
          const float dx = sample_bilinear(flow, px, py, 0), dy = sample_bilinear(flow, px, py, 1);
          px -= static_cast<float>(r) * dx;
          py -= static_cast<float>(r) * dy;
          on = masked(px, py);
        }
        if (!on) continue;
        const double a = channel_mean(after, x, y), b = bilinear_mean(before, px, py);
        sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, n += 1;
      }
    double c = 0.0;
    if (n > 1) {
      const double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
      c = va > 0 && vb > 0 ? (sab / n - (sa / n) * (sb / n)) / std::sqrt(va * vb) : 0.0;
    }
    if (step == 0) result.still = c;
    if (step == 20) {
      result.at_flow = c;
      result.pixels = static_cast<std::size_t>(n);
    }
    if (c > result.best) {
      result.best = c;
      result.ratio = r;
    }
  }
  return result;
}

double rms_contrast(const ImageF& image, const std::vector<std::uint8_t>& mask) {
  double s = 0, ss = 0, n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (!mask[static_cast<std::size_t>(y) * image.width + x]) continue;
      const double v = channel_mean(image, x, y);
      s += v, ss += v * v, n += 1;
    }
  if (n < 2) return 0.0;
  return std::sqrt(std::max(ss / n - (s / n) * (s / n), 0.0));
}

double red_tinted_fraction(const ImageF& image, const std::vector<std::uint8_t>& mask,
                           float threshold) {
  if (image.channels < 3) throw InputError("red_tinted_fraction: needs an RGB image");
  double tinted = 0, n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (!mask[static_cast<std::size_t>(y) * image.width + x]) continue;
      n += 1;
      if (image.at(x, y, 0) - 0.5f * (image.at(x, y, 1) + image.at(x, y, 2)) > threshold)
        tinted += 1;
    }
  return n > 0 ? tinted / n : 0.0;
}

}  // namespace ibfvs
