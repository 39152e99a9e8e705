#pragma once
// Images on the CPU: what the renderer reads back and what PNG files hold.
// Rows are stored bottom-up, as OpenGL reads them; PNG writing flips.

#include <cstdint>
#include <filesystem>
#include <vector>

namespace ibfvs {

/// 8-bit image, `channels` interleaved (1, 3 or 4), rows bottom-up.
struct ImageU8 {
  ImageU8() = default;
  /// A zeroed image of the given size.
  ImageU8(int w, int h, int c)
      : width(w), height(h), channels(c), pixels(static_cast<std::size_t>(w) * h * c) {}
  int width = 0;
  int height = 0;
  int channels = 4;
  std::vector<std::uint8_t> pixels;
  [[nodiscard]] std::uint8_t at(int x, int y, int c) const {
    return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c];
  }
};

/// Float image, `channels` interleaved, rows bottom-up.
struct ImageF {
  ImageF() = default;
  /// An image of the given size filled with `value`.
  ImageF(int w, int h, int c, float value = 0.0f)
      : width(w), height(h), channels(c), pixels(static_cast<std::size_t>(w) * h * c, value) {}
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<float> pixels;
  [[nodiscard]] float at(int x, int y, int c = 0) const {
    return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c];
  }
  float& at(int x, int y, int c = 0) {
    return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c];
  }
  /// Channels [first, first + count) as an image of their own.
  [[nodiscard]] ImageF select_channels(int first, int count) const;
};

/// Writes a PNG (8 bits per channel). Throws InputError naming the path.
void write_png(const ImageU8& image, const std::filesystem::path& path);

/// Writes a float image as a 16-bit PNG, values clamped to [0, 1]
/// (the raw texture F_t, without 8-bit rounding).
void write_png16(const ImageF& image, const std::filesystem::path& path);

/// Reads an 8-bit PNG (grey, RGB or RGBA) into bottom-up rows. Throws InputError.
ImageU8 read_png(const std::filesystem::path& path);

/// An RGBA image (even width and height, rows bottom-up) as the I420 bytes a
/// video encoder takes, in `out` (resized): the Y plane, then U and V at
/// half resolution, rows top-down; BT.601 limited range (as ffmpeg's default
/// conversion, in 8-bit fixed point), each chroma sample from the mean of
/// its 2x2 block. Throws InputError on odd sizes.
void to_yuv420(const ImageU8& rgba, std::vector<std::uint8_t>& out);

/// One channel of an 8-bit image as floats in [0, 1].
ImageF to_float_channel(const ImageU8& image, int channel);

/// Bilinear sample of channel c at (x, y) in pixels, texel centres at +0.5,
/// clamped at the edges (a GL_LINEAR texture with CLAMP_TO_EDGE).
float sample_bilinear(const ImageF& image, float x, float y, int c);

}  // namespace ibfvs
