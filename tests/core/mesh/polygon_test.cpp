// Polygons as triangles (core/mesh/polygon.h): the split of one polygon,
// of a list of them, and the memory that keeps a list's split for the next
// state of the same cells.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>

#include "helpers.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/mesh/polygon.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/isolation.h"

namespace ibfvs {
namespace {

// Twice the area of a triangle of `points`, seen along +Z.
float twice_area(const Triangle& t, const std::vector<glm::vec3>& points) {
  return glm::cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]).z;
}

// The triangles of a polygon depend on its points' order, not on where it
// is: a turned copy gives the same; a star (not convex) is covered exactly.
TEST(Polygon, TrianglesFollowThePointsNotThePlace) {
  std::vector<glm::vec3> star;
  for (int k = 0; k < 10; ++k) {
    const float a = 0.6283185f * static_cast<float>(k), r = k % 2 ? 0.4f : 1.0f;
    star.push_back({r * std::cos(a), r * std::sin(a), 0.0f});
  }
  const std::vector<std::uint32_t> ids{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const std::vector<Triangle> first = triangulate_polygon(ids, star);
  ASSERT_EQ(first.size(), 8u);
  float area = 0.0f, truth = 0.0f;
  for (const Triangle& t : first) {
    const float z = glm::cross(star[t[1]] - star[t[0]], star[t[2]] - star[t[0]]).z;
    EXPECT_GT(z, 0.0f);
    area += 0.5f * z;
  }
  for (std::size_t k = 0; k < star.size(); ++k)
    truth += 0.5f * glm::cross(star[k], star[(k + 1) % star.size()]).z;
  EXPECT_NEAR(area, truth, 1e-5f);
  for (float turn = 0.05f; turn < 6.3f; turn += 0.37f) {
    std::vector<glm::vec3> turned;
    for (const glm::vec3& p : star)
      turned.push_back({std::cos(turn) * p.x - std::sin(turn) * p.y,
                        std::sin(turn) * p.x + std::cos(turn) * p.y, 3.0f + p.x});
    EXPECT_EQ(triangulate_polygon(ids, turned), first) << turn;
  }
  // A regular hexagon is a fan from its first point; fewer than 3 points give none.
  std::vector<glm::vec3> hexagon;
  for (int k = 0; k < 6; ++k)
    hexagon.push_back({std::cos(1.0471976f * k), std::sin(1.0471976f * k), 0.0f});
  EXPECT_EQ(triangulate_polygon(std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}, hexagon),
            (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}));
  EXPECT_TRUE(triangulate_polygon(std::vector<std::uint32_t>{0, 1}, hexagon).empty());
  // A star of 4,000 points (no solver's face): fanned, in bounded time.
  std::vector<glm::vec3> big;
  std::vector<std::uint32_t> all;
  for (std::uint32_t k = 0; k < 4000; ++k) {
    const float a = 0.0015707963f * static_cast<float>(k), r = k % 2 ? 0.9f : 1.0f;
    big.push_back({r * std::cos(a), r * std::sin(a), 0.0f});
    all.push_back(k);
  }
  EXPECT_EQ(triangulate_polygon(all, big).size(), 3998u);
}

// A convex polygon with points on its edges (a cell whose neighbour was
// refined: OpenFOAM's split faces) has straight corners. A fan from a point
// next to one made a triangle of three points on a line (no area: dropped
// at one step and not at the next, where rounding gave it a sliver). Each
// triangle now has area, and together they cover the polygon.
TEST(Polygon, NoTriangleHasItsPointsOnALine) {
  // A square with a point in the middle of each of two edges, the first
  // such point next to point 0.
  const std::vector<glm::vec3> points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0},
                                         {2, 2, 0}, {0, 2, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> ids{0, 1, 2, 3, 4, 5};
  const std::vector<Triangle> triangles = triangulate_polygon(ids, points);
  ASSERT_EQ(triangles.size(), 4u);
  float area = 0.0f;
  for (const Triangle& t : triangles) {
    EXPECT_GT(twice_area(t, points), 0.1f) << t[0] << " " << t[1] << " " << t[2];
    area += 0.5f * twice_area(t, points);
  }
  EXPECT_NEAR(area, 4.0f, 1e-5f);
}

// A list of polygons of every size: triangles as they are, a kite along its
// shorter diagonal, a pentagon, and what has no triangle (two points, a
// repeated point, three points on a line) left out and counted.
TEST(SplitPolygons, EachPolygonByItsSizeAndTheDegenerateOnesCounted) {
  const std::vector<glm::vec3> points = {{0, 0, 0}, {1, 0, 0},    {0, 1, 0}, {1, -0.2f, 0},
                                         {3, 0, 0}, {1, 0.2f, 0}, {5, 0, 0}, {6, 0, 0},
                                         {6, 1, 0}, {5.5f, 2, 0}, {5, 1, 0}, {2, 0, 0}};
  const std::vector<int> ids = {0, 1, 2, 3, 4, 5, 0, 6, 7, 8, 9, 10, 0, 1, 0, 0, 2, 0, 1, 11};
  const std::vector<int> offsets = {0, 3, 7, 12, 14, 17, 20};
  const PolygonSplit split = split_polygons(PolygonList<int>{offsets, ids}, points);
  EXPECT_EQ(
      split.triangles,
      (std::vector<Triangle>{{0, 1, 2}, {3, 4, 5}, {3, 5, 0}, {6, 7, 8}, {6, 8, 9}, {6, 9, 10}}));
  EXPECT_EQ(split.polygon, (std::vector<std::uint32_t>{0, 1, 1, 2, 2, 2}));
  EXPECT_EQ(split.dropped, 2u);  // 0 0 2 and 0 1 11 (on the x axis)
  // Offsets that do not span the ids are refused; a point that is not there
  // is fanned without being read (validate_mesh names it later).
  const std::vector<int> short_offsets = {0, 3, 7};
  EXPECT_THROW(split_polygons(PolygonList<int>{short_offsets, ids}, points), InputError);
  const std::vector<long> far = {0, 1, 99, 2}, one = {0, 4};
  const PolygonSplit fanned = split_polygons(PolygonList<long>{one, far}, points);
  EXPECT_EQ(fanned.triangles, (std::vector<Triangle>{{0, 1, 99}, {0, 99, 2}}));
}

// The test: the rotor turned through 360 degrees, one degree at a
// time, about an axis off +Z; its triangles never change. Split afresh,
// the rounding of the turned points changes them at some turns (the test
// would fail without the memory).
TEST(SplitMemory, TheSameCellsKeepTheirTrianglesThroughAWholeTurn) {
  const test::Rotor rotor = test::nearly_tied_rotor();
  const PolygonList<long> cells{rotor.offsets, rotor.ids};
  SplitMemory memory;
  const std::shared_ptr<const PolygonSplit> first = memory.split(cells, rotor.points);
  ASSERT_EQ(first->triangles.size(), 400u * 3 + 400u * 2);
  EXPECT_EQ(first->dropped, 0u);
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, 0.2, 1.0));
  int afresh_differs = 0;
  for (int degrees = 1; degrees <= 360; ++degrees) {
    const std::vector<glm::vec3> turned = test::turned(rotor.points, degrees, axis);
    const std::shared_ptr<const PolygonSplit> kept = memory.split(cells, turned);
    EXPECT_EQ(kept->triangles, first->triangles) << degrees << " degrees";
    EXPECT_EQ(kept->polygon, first->polygon);
    afresh_differs += split_polygons(cells, turned).triangles != first->triangles ? 1 : 0;
  }
  EXPECT_EQ(memory.size(), 1u);
  EXPECT_GT(afresh_differs, 0) << "the rotor's ties no longer flip: the test tests nothing";
  std::printf("split afresh, the rotor's triangles differ at %d of 360 turns\n", afresh_differs);
}

// Other cells, or the same ids on another number of points, are split
// afresh (and kept too); a split made in a child comes back to the parent
// (put_since, take); the least recently used go when over the budget.
TEST(SplitMemory, OtherCellsAreSplitAfreshAndSplitsTravel) {
  const test::Rotor rotor = test::nearly_tied_rotor();
  const PolygonList<long> cells{rotor.offsets, rotor.ids};
  SplitMemory memory;
  const auto first = memory.split(cells, rotor.points);
  const std::uint64_t mark = memory.made();
  std::vector<long> flipped = rotor.ids;  // the first pentagon's points in reverse
  std::reverse(flipped.begin(), flipped.begin() + 5);
  const PolygonList<long> other{rotor.offsets, flipped};
  const auto second = memory.split(other, rotor.points);
  EXPECT_NE(second->triangles, first->triangles);
  std::vector<glm::vec3> more = rotor.points;
  more.emplace_back(0.0f);
  EXPECT_EQ(memory.split(cells, more)->triangles, first->triangles);  // split afresh, alike
  EXPECT_EQ(memory.size(), 3u);
  // The same cells in 32-bit storage find the same split.
  const std::vector<int> offsets32(rotor.offsets.begin(), rotor.offsets.end());
  const std::vector<int> ids32(rotor.ids.begin(), rotor.ids.end());
  EXPECT_EQ(memory.split(PolygonList<int>{offsets32, ids32}, rotor.points), first);
  EXPECT_EQ(memory.size(), 3u);

  ByteWriter out;
  memory.put_since(out, mark);  // the two made after the mark
  const std::string bytes = out.take();
  SplitMemory parent;
  ByteReader in(bytes, "child");
  parent.take(in);
  EXPECT_TRUE(in.done());
  EXPECT_EQ(parent.size(), 2u);
  EXPECT_EQ(parent.split(other, rotor.points)->triangles, second->triangles);
  EXPECT_EQ(parent.size(), 2u);  // found, not split again
  ByteReader cut(std::string_view(bytes).substr(0, bytes.size() / 2), "child");
  EXPECT_THROW(parent.take(cut), InputError);

  // A budget that holds one list: the older goes.
  SplitMemory small(first->triangles.size() * sizeof(Triangle) * 3);
  small.split(cells, rotor.points);
  small.split(other, rotor.points);
  EXPECT_EQ(small.size(), 1u);
}

}  // namespace
}  // namespace ibfvs
