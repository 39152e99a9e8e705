#include "ibfvs/core/support/limits.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <unistd.h>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

std::uint64_t memory_limit() {
  if (const char* text = std::getenv("IBFVS_MEMORY_LIMIT"); text && *text) {
    char* end = nullptr;
    double v = std::strtod(text, &end);
    switch (end && *end ? *end : ' ') {
      case 'K':
      case 'k':
        v *= 1024.0;
        break;
      case 'M':
      case 'm':
        v *= 1024.0 * 1024.0;
        break;
      case 'G':
      case 'g':
        v *= 1024.0 * 1024.0 * 1024.0;
        break;
      default:
        break;
    }
    if (v > 0) return static_cast<std::uint64_t>(v);
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 0;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
}

std::string format_bytes(double bytes) {
  static const char* kUnits[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int unit = 0;
  while (bytes >= 1024.0 && unit < 6) bytes /= 1024.0, ++unit;
  char text[32];
  std::snprintf(text, sizeof text, bytes < 10 && unit > 0 ? "%.1f %s" : "%.0f %s", bytes,
                kUnits[unit]);
  return text;
}

void check_memory(double bytes, const std::string& what) {
  const std::uint64_t limit = memory_limit();
  if (limit == 0 || bytes <= static_cast<double>(limit)) return;
  throw InputError(what + " would need about " + format_bytes(bytes) +
                   " of memory; this machine has " + format_bytes(static_cast<double>(limit)));
}

double mesh_bytes(double triangles) {
  return 110.0 * triangles;
}

double subdivided_triangles(std::size_t triangles, int levels) {
  return static_cast<double>(triangles) * std::pow(4.0, levels);
}

double image_bytes(int width, int height) {
  // GPU: colour RGBA8 4, depth 4, two texture buffers RGBA16F 16, flow RG16F
  // 4; CPU: the frame read back 4 and its YUV 1.5 (llvmpipe's GPU memory is
  // the same memory).
  return static_cast<double>(width) * static_cast<double>(height) * 33.5;
}

}  // namespace ibfvs
