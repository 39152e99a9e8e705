#pragma once
// Depth compositing of the texture image F_t across the processes of a
// distributed render (ParaView's pvbatch and pvserver under MPI), so that
// each process advects its own piece of the surface through the F_t of the
// whole picture: the picture is then the single process's, with no seams
// along the piece boundaries (docs/paraview.md has the design and a diagram).
//
// Each pixel of F_t goes to the process whose surface is nearest there, ties
// to the lower rank; where no process has a surface, rank 0's background.
// Two reductions over all processes, elementwise: the minimum of a 64-bit key
// per pixel (window depth above, rank below), then the sum of F_t where every
// process has zeroed the pixels it did not win (x + 0 = x: exact).

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "ibfvs/core/image/image.h"

namespace ibfvs {

/// One key per pixel: the window depth's bits (depth in [0, 1], 1 where this
/// process drew nothing) above, `rank` below; the elementwise minimum over
/// all processes names the nearest surface's process. Throws InputError for
/// a depth outside [0, 1] or a negative rank.
std::vector<std::uint64_t> composite_keys(const ImageF& depth, int rank);

/// Zeroes the pixels of `texture` (any channel count) whose minimum key names
/// another process; after summing the textures of all processes elementwise
/// each pixel is the winner's. Throws InputError when the sizes differ.
void keep_won_pixels(ImageF& texture, std::span<const std::uint64_t> min_keys, int rank);

/// The collective operations of the process group (MPI through ParaView's
/// vtkCommunicator in the plugin; a loop in the tests).
struct CompositeGroup {
  int rank = 0;
  int size = 1;
  std::function<void(std::span<std::uint64_t>)> min_all;  ///< in place, elementwise
  std::function<void(std::span<float>)> sum_all;          ///< in place, elementwise
};

/// Both steps and both reductions: on return each of `images` (F_t, and F
/// when the contrast statistics need it; the size of `depth`, any channel
/// count) holds the composited image on every process. Nothing happens for a
/// group of one.
void composite_nearest(std::span<ImageF* const> images, const ImageF& depth,
                       const CompositeGroup& group);

}  // namespace ibfvs
