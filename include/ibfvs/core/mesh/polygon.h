#pragma once
// Polygons as triangles: a file's quadrilaterals and faces of five points
// or more (OpenFOAM's cut cells, a polyhedral mesh's faces), split the way
// every reader and host of ibfvs splits them (the VTK readers, ParaView's
// mapper, the PyVista layer).
//
// How a polygon splits depends on where its points are: a quadrilateral
// along its shorter diagonal, a larger polygon as a fan where it is convex
// and by ear clipping where it is not. Each of those tests has a tie (two
// diagonals of equal length, a corner that is straight), and as a mesh
// moves, the rounding of its moved points carries nearly tied polygons
// across it: a turning fan's nearly straight corners did, and a few of its
// polygons split into other triangles at some steps, which then played as
// surfaces of their own (the texture left standing in the image). So a
// split is decided once for a set of cells and kept (SplitMemory): a later
// state with the same cells, wherever its points have moved, gets the same
// triangles.

#include <array>
#include <concepts>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

class ByteReader;
class ByteWriter;

/// The polygon through `points[ids[0]], points[ids[1]], ...` as triangles
/// of the same winding (ids.size() - 2 of them): a fan from its first point
/// where it is strictly convex (seen along its mean normal, every corner
/// turning by more than 1e-4 of its edges), else ear clipping in the order
/// of its points (each ear the first one found from the last; a straight
/// corner is never an ear's tip, so that no triangle has three points on a
/// line). A polygon that is not simple (no ear left) is fanned from there
/// on, and so is one of over 1,024 points (ear clipping's time grows as the
/// cube). Indices must be within `points`.
std::vector<Triangle> triangulate_polygon(std::span<const std::uint32_t> ids,
                                          std::span<const glm::vec3> points);

/// A quadrilateral's two triangles: along its shorter diagonal, as VTK's
/// triangle filter splits it, but along the one from its second point where
/// the two are within a thousandth of each other (as VTK does for equal
/// ones). Indices must be within `points`.
std::array<Triangle, 2> split_quad(std::span<const std::uint32_t, 4> ids,
                                   std::span<const glm::vec3> points);

/// Polygons the way VTK's cell arrays hold them: polygon c has the points
/// ids[offsets[c]] .. ids[offsets[c + 1] - 1] (offsets: one more than there
/// are polygons, starting at 0, never decreasing, the last ids.size()).
/// Index: VTK's 32- or 64-bit storage, numpy's int64.
template <std::signed_integral Index>
struct PolygonList {
  std::span<const Index> offsets;
  std::span<const Index> ids;
  [[nodiscard]] std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

/// Every polygon's triangles, in order, with the polygon each comes from.
struct PolygonSplit {
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> polygon;  ///< per triangle: the index of its polygon
  /// Triangles left out: a repeated point, or no area (three points on a
  /// line, as remove_degenerate_triangles finds them) at the points split.
  std::size_t dropped = 0;
};

/// Splits each polygon: a triangle as it is, a quadrilateral by split_quad,
/// a larger one by triangulate_polygon; fewer than three points give none,
/// and degenerate triangles are dropped (PolygonSplit::dropped). A polygon
/// with a point that is not in `points` (negative or past the end) is
/// fanned without reading them: validate_mesh then names the point. Throws
/// InputError for offsets that are not as PolygonList says.
template <std::signed_integral Index>
PolygonSplit split_polygons(const PolygonList<Index>& polygons, std::span<const glm::vec3> points);

/// The splits of the polygon lists seen so far, kept while they fit in a
/// budget: a list of the very same polygons (offsets and ids, compared in
/// full) on as many points gets the split it got the first time, wherever
/// its points have moved since (the head of this file says why). The
/// least recently used splits go first. Not thread-safe: its user holds one
/// lock around it (the VTK readers hold VTK's).
class SplitMemory {
 public:
  /// `budget`: the bytes of polygons and triangles it keeps; 0: a sixteenth
  /// of memory_limit(), at most 1 GiB.
  explicit SplitMemory(std::uint64_t budget = 0);
  ~SplitMemory();
  SplitMemory(const SplitMemory&) = delete;
  SplitMemory& operator=(const SplitMemory&) = delete;

  /// The split of `polygons` on `points`: the one these polygons got the
  /// first time they came on as many points (while it is kept), else
  /// split_polygons's on these points, kept from now on.
  template <std::signed_integral Index>
  std::shared_ptr<const PolygonSplit> split(const PolygonList<Index>& polygons,
                                            std::span<const glm::vec3> points);

  /// How many splits it keeps, and their bytes.
  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] std::uint64_t bytes() const { return bytes_; }
  /// How many splits it has made so far (a mark for put_since).
  [[nodiscard]] std::uint64_t made() const { return made_; }
  /// The splits made after mark `since` (and still kept), for another
  /// process: a reading child hands its new splits back to the parent.
  void put_since(ByteWriter& out, std::uint64_t since) const;
  /// Keeps the splits put_since wrote (those it has already stay as they
  /// are). Throws InputError on a short or inconsistent record.
  void take(ByteReader& in);

 private:
  struct Entry;
  void keep(std::unique_ptr<Entry> entry);
  std::vector<std::unique_ptr<Entry>> entries_;
  std::uint64_t budget_ = 0, bytes_ = 0, made_ = 0, clock_ = 0;
};

}  // namespace ibfvs
