#pragma once
// Limits checked before allocating: what a mesh, an image or a grid would
// need, against what this machine has, so that a request that cannot fit is
// refused with an estimate instead of an out-of-memory kill.

#include <cstddef>
#include <cstdint>
#include <string>

namespace ibfvs {

/// The widest and tallest image a setting may ask for; what a render can
/// have is less: the GL implementation's largest image (gl::check_image_size)
/// and the memory (image_bytes).
constexpr int kMaxImageSide = 1 << 20;

/// This machine's physical memory in bytes (0 when it cannot be told).
/// IBFVS_MEMORY_LIMIT (bytes, or with a K/M/G suffix) lowers it, for tests
/// and for sharing a machine.
std::uint64_t memory_limit();

/// "1.5 GiB", "180 MiB", "12 KiB".
std::string format_bytes(double bytes);

/// Throws InputError "WHAT would need about N GiB of memory (...); this
/// machine has M GiB" when `bytes` exceed memory_limit().
void check_memory(double bytes, const std::string& what);

/// Peak memory of a mesh of `triangles` triangles through loading,
/// subdivision and rendering: measured on the cow (docs/reliability.md),
/// about 110 bytes per triangle.
double mesh_bytes(double triangles);

/// Triangles after `levels` Loop subdivisions (each makes four of one).
double subdivided_triangles(std::size_t triangles, int levels);

/// Memory of a render of width x height: the GPU targets (colour, depth,
/// the two texture buffers, flow) and the frame read back and encoded.
double image_bytes(int width, int height);

}  // namespace ibfvs
