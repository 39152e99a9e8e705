// The dataset formats through ParaView's VTK: every layout and encoding a
// solver writes, arrays by name, cell data carried to the vertices,
// multiblocks, series, OpenFOAM cases, volume sampling, .vtp out (bad files:
// vtk_bad_files_test.cpp). Files are written on the fly (VTK's own writers,
// or by hand where the exact bytes matter; vtk_test_files.h).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSmartPointer.h>
#include <vtkStructuredGrid.h>
#include <vtkStructuredGridWriter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLMultiBlockDataWriter.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <glm/geometric.hpp>

#include "helpers.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/core/mesh/polygon.h"
#include "ibfvs/core/scene/mesh_source.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/vtk/vtk_io.h"

#include "vtk_test_files.h"

namespace ibfvs::vtktest {
namespace {

TEST_F(VtkIo, LegacyLayoutsAndEncodings) {
  for (const int version : {42, 51})
    for (const bool binary : {false, true}) {
      const fs::path path =
          dir_ / ("square" + std::to_string(version) + (binary ? "b" : "a") + ".vtk");
      vtkNew<vtkPolyDataWriter> w;
      w->SetInputData(square());
      w->SetFileName(path.c_str());
      w->SetFileVersion(version);
      if (binary) w->SetFileTypeToBinary();
      ASSERT_EQ(w->Write(), 1);
      SCOPED_TRACE(path.string());
      expect_square(read_dataset({path, {}}));
    }
}

TEST_F(VtkIo, LegacyFieldDataStripsLinesAndVertices) {
  // A strip of 4 points (2 triangles), a line and a vertex (dropped); point
  // data as FIELD, cell data as SCALARS on a strip of different areas.
  const fs::path path = write_file(dir_ / "strip.vtk", R"(# vtk DataFile Version 3.0
strip
ASCII
DATASET POLYDATA
POINTS 5 float
0 0 0  1 0 0  0 1 0  3 1 0  9 9 9
VERTICES 1 2
1 4
LINES 1 3
2 0 4
TRIANGLE_STRIPS 1 5
4 0 1 2 3
POINT_DATA 5
FIELD attributes 1
vel 3 5 double
1 0 0  1 0 0  1 0 0  1 0 0  1 0 0
CELL_DATA 3
SCALARS s float 1
LOOKUP_TABLE default
7 8 10
)");
  const Dataset d = read_dataset({path, {}});
  EXPECT_EQ(d.mesh.triangle_count(), 2u);
  ASSERT_TRUE(d.mesh.vector_arrays.count("vel"));
  // The strip is one cell: both triangles carry 10; vertex 4 (of no
  // triangle) is not in the mesh's triangles.
  ASSERT_TRUE(d.mesh.scalars.count("s"));
  EXPECT_FLOAT_EQ(d.mesh.scalars.at("s")[0], 10.0f);
}

TEST_F(VtkIo, CellDataReachesTheVerticesAreaWeighted) {
  // Triangles (0,1,2) area 0.5 value 1 and (1,3,2) area 1.5 value 5:
  // the shared vertices 1 and 2 get (0.5*1 + 1.5*5) / 2 = 4.
  const fs::path path = write_file(dir_ / "two.vtk", R"(# vtk DataFile Version 4.2
two
ASCII
DATASET POLYDATA
POINTS 4 float
0 0 0  1 0 0  0 1 0  2 2 0
POLYGONS 2 8
3 0 1 2
3 1 3 2
CELL_DATA 2
SCALARS c float 1
LOOKUP_TABLE default
1 5
)");
  const Dataset d = read_dataset({path, {}});
  const std::vector<float>& c = d.mesh.scalars.at("c");
  EXPECT_FLOAT_EQ(c[0], 1.0f);
  EXPECT_FLOAT_EQ(c[1], 4.0f);
  EXPECT_FLOAT_EQ(c[2], 4.0f);
  EXPECT_FLOAT_EQ(c[3], 5.0f);
}

TEST_F(VtkIo, XmlPolyDataEveryEncoding) {
  struct Mode {
    const char* name;
    int data_mode;
    bool zlib;
  };
  for (const Mode m :
       {Mode{"ascii", vtkXMLWriter::Ascii, false}, Mode{"base64", vtkXMLWriter::Binary, false},
        Mode{"raw", vtkXMLWriter::Appended, false}, Mode{"zlib", vtkXMLWriter::Appended, true}}) {
    const fs::path path = dir_ / (std::string(m.name) + ".vtp");
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetInputData(square());
    w->SetFileName(path.c_str());
    w->SetDataMode(m.data_mode);
    if (m.data_mode == vtkXMLWriter::Appended) w->SetEncodeAppendedData(false);
    if (m.zlib)
      w->SetCompressorTypeToZLib();
    else
      w->SetCompressorTypeToNone();
    ASSERT_EQ(w->Write(), 1);
    SCOPED_TRACE(m.name);
    expect_square(read_dataset({path, {}}));
  }
}

TEST_F(VtkIo, VolumeGridShowsItsOuterSurface) {
  std::vector<fs::path> files;
  for (const int mode : {vtkXMLWriter::Ascii, vtkXMLWriter::Binary, vtkXMLWriter::Appended})
    for (const bool zlib : {false, true}) {
      files.push_back(dir_ / ("block" + std::to_string(mode) + (zlib ? "z" : "") + ".vtu"));
      vtkNew<vtkXMLUnstructuredGridWriter> w;
      w->SetInputData(hex_block());
      w->SetFileName(files.back().c_str());
      w->SetDataMode(mode);
      w->SetEncodeAppendedData(false);
      if (zlib)
        w->SetCompressorTypeToZLib();
      else
        w->SetCompressorTypeToNone();
      ASSERT_EQ(w->Write(), 1);
    }
  for (const int version : {42, 51}) {
    files.push_back(dir_ / ("block" + std::to_string(version) + ".vtk"));
    vtkNew<vtkUnstructuredGridWriter> w;  // legacy UNSTRUCTURED_GRID, binary
    w->SetInputData(hex_block());
    w->SetFileName(files.back().c_str());
    w->SetFileVersion(version);
    w->SetFileTypeToBinary();
    ASSERT_EQ(w->Write(), 1);
  }
  for (const fs::path& path : files) {
    SCOPED_TRACE(path.string());
    const Dataset d = read_dataset({path, {}});
    EXPECT_EQ(d.mesh.triangle_count(), 6u * 4u * 2u);  // 6 sides of 2 x 2 quads
    EXPECT_EQ(d.mesh.vertex_count(), 26u);             // all but the centre point
    ASSERT_TRUE(d.mesh.vector_arrays.count("U"));
    // U = (x, 2y, 3z) came along with its points.
    EXPECT_EQ(d.mesh.vector_arrays.at("U")[5], d.mesh.positions[5] * glm::vec3(1, 2, 3));
  }
}

TEST_F(VtkIo, MultiblockBlocksByNameAndPattern) {
  const fs::path path = write_multiblock(dir_);
  const Dataset all = read_dataset({path, {}});
  // Welded where the blocks meet; the face the two blocks share, once.
  EXPECT_EQ(all.mesh.triangle_count(), 3u);
  EXPECT_EQ(all.mesh.vertex_count(), 5u);
  EXPECT_EQ(all.blocks, (std::vector<std::string>{"wing", "body"}));
  const Dataset wing = read_dataset({path, {"wing"}});
  EXPECT_EQ(wing.mesh.triangle_count(), 2u);
  EXPECT_EQ(wing.blocks, std::vector<std::string>{"wing"});
  EXPECT_EQ(read_dataset({path, {"b*"}}).blocks, std::vector<std::string>{"body"});
  try {
    read_dataset({path, {"tail"}});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              path.string() + ": no block matches 'tail' (blocks: wing, body)");
  }
}

TEST_F(VtkIo, PvdSeriesIsUnsteady) {
  const fs::path path = write_series(dir_);
  const Dataset d = read_dataset({path, {}});
  EXPECT_EQ(d.times, (std::vector<double>{0.0, 0.5, 1.0}));
  ASSERT_TRUE(d.step);
  EXPECT_EQ(d.step(2).vector_arrays.at("v")[0], glm::vec3(3, 0, 0));

  // Through a scene: three steps, played through the field's GPU
  // interpolation; `time 1` picks one.
  Scene scene;
  scene.mesh = path.string();
  scene.field = FieldSpec::parse("file:v");
  scene.tangent = TangentMode::Full3D;
  const PreparedScene p = prepare_scene(scene);
  EXPECT_EQ(p.step_count, 3u);
  EXPECT_NEAR(p.step_data(1).field[0].x, 2.0f, 1e-6f);
  scene.time = TimeRange::parse("1");
  scene.reverse = true;
  const PreparedScene one = prepare_scene(scene);
  EXPECT_EQ(one.step_count, 1u);
  EXPECT_NEAR(one.field[0].x, -2.0f, 1e-6f);
  scene.time = TimeRange::parse("1:5");
  EXPECT_THROW(prepare_scene(scene), SettingError);
}

// A rotor's cells: an annulus of quadrilaterals (their two diagonals equal)
// turned by `degrees` about +Z, with cell and point arrays.
vtkSmartPointer<vtkPolyData> turned_annulus(double degrees) {
  constexpr int rings = 6, sectors = 48;
  vtkNew<vtkPoints> points;
  const double a0 = degrees * 3.14159265358979 / 180.0;
  for (int r = 0; r <= rings; ++r)
    for (int k = 0; k < sectors; ++k) {
      const double radius = 0.2 + 0.8 * r / rings, a = a0 + 2.0 * 3.14159265358979 * k / sectors;
      points->InsertNextPoint(radius * std::cos(a), radius * std::sin(a), 0.0);
    }
  vtkNew<vtkCellArray> quads;
  vtkNew<vtkFloatArray> id;
  id->SetName("id");
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < sectors; ++k) {
      const vtkIdType q[4] = {r * sectors + k, r * sectors + (k + 1) % sectors,
                              (r + 1) * sectors + (k + 1) % sectors, (r + 1) * sectors + k};
      quads->InsertNextCell(4, q);
      id->InsertNextValue(static_cast<float>(r * sectors + k));
    }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(quads);
  poly->GetCellData()->AddArray(id);
  return poly;
}

// The surface `at(0)` as read, after expecting the same triangles of
// `at(degrees)` for every turn from `from` to `below` by `by` degrees.
template <typename At>
TriMesh same_triangles_as_it_turns(At at, double by, double below, double from = -1.0) {
  const TriMesh first = vtk::surface_mesh(at(0.0), "turned");
  for (double degrees = from < 0.0 ? by : from; degrees < below; degrees += by)
    EXPECT_EQ(vtk::surface_mesh(at(degrees), "turned").triangles, first.triangles)
        << degrees << " degrees";
  return first;
}

TEST_F(VtkIo, QuadrilateralsSplitTheSameWayWhereverThePointsMove) {
  // A moving mesh keeps its triangles from step to step (scene_prep then
  // carries the texture with its points): VTK's triangle filter takes the
  // shorter diagonal, which for equal diagonals flips with the rounding.
  const TriMesh first = same_triangles_as_it_turns(turned_annulus, 7.3, 360.0, 0.7);
  ASSERT_EQ(first.triangle_count(), 2u * 6 * 48);
  // Each triangle keeps its cell's value.
  const std::vector<float>& id = first.scalars.at("id");
  EXPECT_GT(id.size(), 0u);
  // And a quadrilateral whose diagonal from its first point is clearly the
  // shorter splits along it.
  vtkNew<vtkPoints> kite;
  for (const auto& p :
       {glm::vec3(1, -0.2f, 0), glm::vec3(3, 0, 0), glm::vec3(1, 0.2f, 0), glm::vec3(0, 0, 0)})
    kite->InsertNextPoint(p.x, p.y, p.z);
  vtkNew<vtkCellArray> one;
  const vtkIdType q[4] = {0, 1, 2, 3};
  one->InsertNextCell(4, q);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(kite);
  poly->SetPolys(one);
  const TriMesh split = vtk::surface_mesh(poly, "kite");
  ASSERT_EQ(split.triangle_count(), 2u);
  for (const Triangle& t : split.triangles)  // the diagonal 0-2 in both
    EXPECT_TRUE(std::count(t.begin(), t.end(), 0u) && std::count(t.begin(), t.end(), 2u));
}

// Hexagons on a cylinder of radius 10 (each of its own six points), turned
// about the cylinder's axis: the faces of a polyhedral rotor's wall.
vtkSmartPointer<vtkPolyData> turned_hexagons(double degrees) {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  const double turn = degrees * 3.14159265358979 / 180.0, radius = 10.0;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 6; ++j) {
      const double cx = 1.5 * i, cy = std::sqrt(3.0) * (j + 0.5 * (i % 2));
      std::array<vtkIdType, 6> ids{};
      for (int k = 0; k < 6; ++k) {
        const double a = 3.14159265358979 / 3.0 * k, x = cx + std::cos(a), y = cy + std::sin(a);
        const double around = x / radius + turn;
        ids[static_cast<std::size_t>(k)] =
            points->InsertNextPoint(radius * std::cos(around), radius * std::sin(around), y);
      }
      cells->InsertNextCell(6, ids.data());
    }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  return poly;
}

TEST_F(VtkIo, PolygonsSplitTheSameWayWhereverThePointsMove) {
  // VTK's triangle filter gives 40-60% of these triangles others after a turn
  // of a few degrees (its ears by their shape, equal for a regular hexagon):
  // the steps of a moving mesh were then surfaces of their own, the texture
  // left standing in the image.
  const TriMesh first = same_triangles_as_it_turns(turned_hexagons, 2.9, 60.0);
  ASSERT_EQ(first.triangle_count(), 4u * 30 * 6);
  // A polygon that is not convex (an L of six points) is cut into triangles
  // that cover it: four, their area the L's (3 units).
  vtkNew<vtkPoints> l;
  for (const auto& p : {glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(2, 1, 0),
                        glm::vec3(1, 1, 0), glm::vec3(1, 2, 0), glm::vec3(0, 2, 0)})
    l->InsertNextPoint(p.x, p.y, p.z);
  vtkNew<vtkCellArray> one;
  const vtkIdType ids[6] = {2, 3, 4, 5, 0, 1};  // starting at a convex corner before the notch
  one->InsertNextCell(6, ids);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(l);
  poly->SetPolys(one);
  const TriMesh cut = vtk::surface_mesh(poly, "L");
  ASSERT_EQ(cut.triangle_count(), 4u);
  float area = 0.0f;
  for (const Triangle& t : cut.triangles) {
    const glm::vec3 n = glm::cross(cut.positions[t[1]] - cut.positions[t[0]],
                                   cut.positions[t[2]] - cut.positions[t[0]]);
    EXPECT_GT(n.z, 0.0f);  // the polygon's winding, no triangle folded over
    area += 0.5f * n.z;
  }
  EXPECT_NEAR(area, 3.0f, 1e-5f);
}

// Two blocks that share an edge are welded along it, also where one gives a
// shared point's coordinate as -0 and the other as +0 (a point on a turning
// part's axis comes back as -0 at some steps: it was welded at some steps
// and not at others, and those steps played as meshes of their own).
TEST_F(VtkIo, BlocksWeldWhereTheirPointsAreEqualMinusZeroToo) {
  const auto triangle = [](std::array<glm::vec3, 3> corners) {
    vtkNew<vtkPoints> p;
    for (const glm::vec3& c : corners) p->InsertNextPoint(c.x, c.y, c.z);
    vtkNew<vtkCellArray> cells;
    const vtkIdType ids[3] = {0, 1, 2};
    cells->InsertNextCell(3, ids);
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(p);
    poly->SetPolys(cells);
    return poly;
  };
  vtkNew<vtkMultiBlockDataSet> both;
  both->SetBlock(0, triangle({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}));
  both->SetBlock(1, triangle({glm::vec3(-0.0f, 1, -0.0f), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0)}));
  const TriMesh welded = vtk::surface_mesh(both, "two blocks");
  EXPECT_EQ(welded.vertex_count(), 4u);
  EXPECT_EQ(welded.triangle_count(), 2u);
}

// The rotor of helpers.h (cells whose splits are nearly tied) on `points`,
// with a point vector array v.
vtkSmartPointer<vtkPolyData> rotor_data(const test::Rotor& rotor,
                                        const std::vector<glm::vec3>& points) {
  vtkNew<vtkPoints> p;
  p->SetDataTypeToFloat();
  for (const glm::vec3& x : points) p->InsertNextPoint(x.x, x.y, x.z);
  vtkNew<vtkCellArray> cells;
  for (std::size_t c = 0; c + 1 < rotor.offsets.size(); ++c) {
    std::vector<vtkIdType> ids(rotor.ids.begin() + rotor.offsets[c],
                               rotor.ids.begin() + rotor.offsets[c + 1]);
    cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  vtkNew<vtkFloatArray> v;
  v->SetName("v");
  v->SetNumberOfComponents(3);
  for (const glm::vec3& x : points) v->InsertNextTuple3(-x.y, x.x, 0.0);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(p);
  poly->SetPolys(cells);
  poly->GetPointData()->AddArray(v);
  return poly;
}

// The issue's test of a moving mesh whose cells stay the same: a turning
// rotor with nearly straight corners and nearly equal diagonals gets the
// same triangles at every step, whatever reads it. Split afresh, nearly
// every turn of a degree changes some (core's SplitMemory test), and a step
// with other triangles plays as a surface of its own.
TEST_F(VtkIo, TheSameCellsHaveTheSameTrianglesAtEveryStep) {
  const test::Rotor rotor = test::nearly_tied_rotor();
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, 0.2, 1.0));
  // A host (ParaView's mapper): 360 states a degree apart.
  SplitMemory memory;
  const TriMesh first = vtk::surface_mesh(rotor_data(rotor, rotor.points), "rotor", false, &memory);
  ASSERT_EQ(first.triangle_count(), 400u * 3 + 400u * 2);
  int afresh_differs = 0;
  for (int degrees = 1; degrees < 360; ++degrees) {
    const vtkSmartPointer<vtkPolyData> at =
        rotor_data(rotor, test::turned(rotor.points, degrees, axis));
    EXPECT_EQ(vtk::surface_mesh(at, "rotor", false, &memory).triangles, first.triangles)
        << degrees << " degrees";
    afresh_differs += vtk::surface_mesh(at, "rotor").triangles != first.triangles ? 1 : 0;
  }
  EXPECT_EQ(memory.size(), 1u);
  EXPECT_GT(afresh_differs, 300);
  // A file series (each step read in a child process of its own): 24 steps
  // 15 degrees apart.
  std::string series = "{\"file-series-version\": \"1.0\", \"files\": [";
  for (int k = 0; k < 24; ++k) {
    const std::string name = "rotor" + std::to_string(k) + ".vtp";
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetInputData(rotor_data(rotor, test::turned(rotor.points, 15.0 * k, axis)));
    w->SetFileName((dir_ / name).c_str());
    ASSERT_EQ(w->Write(), 1);
    series += std::string(k ? ", " : "") + "{\"name\": \"" + name +
              "\", \"time\": " + std::to_string(k) + "}";
  }
  const fs::path path = write_file(dir_ / "rotor.vtp.series", series + "]}");
  const Dataset d = read_dataset({path, {}});
  ASSERT_EQ(d.times.size(), 24u);
  EXPECT_EQ(d.mesh.triangles, first.triangles);
  for (std::size_t k = 1; k < 24; ++k) {
    const TriMesh step = d.step(k);
    EXPECT_EQ(step.triangles, d.mesh.triangles) << "step " << k;
    EXPECT_EQ(topology_hash(step), topology_hash(d.mesh)) << "step " << k;
  }
}

TEST_F(VtkIo, NumberedFilesAreASeries) {
  write_series(dir_);
  Scene scene;
  scene.mesh = (dir_ / "step*.vtp").string();
  scene.field = FieldSpec::parse("file:v");
  scene.tangent = TangentMode::Full3D;
  const PreparedScene p = prepare_scene(scene);
  EXPECT_EQ(p.step_count, 3u);
  EXPECT_NEAR(p.step_data(2).field[0].x, 3.0f, 1e-6f);
}

TEST_F(VtkIo, JsonFileSeriesIsUnsteady) {
  write_series(dir_);  // step0.vtp .. step2.vtp
  // ParaView's and foamToVTK's .series; times out of order are sorted.
  const fs::path path = write_file(dir_ / "run.vtp.series", R"({
  "file-series-version" : "1.0",
  "files" : [
    { "name" : "step2.vtp", "time" : 20 },
    { "name" : "step0.vtp", "time" : 0 },
    { "name" : "step1.vtp", "time" : 10 }
  ]
})");
  const Dataset d = read_dataset({path, {}});
  EXPECT_EQ(d.times, (std::vector<double>{0.0, 10.0, 20.0}));
  ASSERT_TRUE(d.step);
  EXPECT_EQ(d.step(2).vector_arrays.at("v")[0], glm::vec3(3, 0, 0));
  // OpenFOAM 1912's foamToVTK -legacy writes "_1" for CASE_1.vtk.
  {
    vtkNew<vtkPolyDataWriter> w;
    w->SetInputData(square());
    for (int k = 0; k < 2; ++k) {
      w->SetFileName((dir_ / ("case_" + std::to_string(k) + ".vtk")).c_str());
      ASSERT_EQ(w->Write(), 1);
    }
  }
  const Dataset legacy = read_dataset(
      {write_file(dir_ / "case.vtk.series",
                  R"({"files": [{"name": "_0", "time": 0}, {"name": "_1", "time": 1}]})"),
       {}});
  EXPECT_EQ(legacy.times, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(legacy.mesh.triangle_count(), 2u);

  expect_bad(write_file(dir_ / "bad.vtp.series", "{\"files\": [ {\"name\": "),
             "not a well-formed .series (JSON) file");
  expect_bad(write_file(dir_ / "list.vtp.series", "[1, 2]"),
             "not a ParaView file series: no \"files\" list");
  expect_bad(write_file(dir_ / "noname.vtp.series", R"({"files": [{"time": 1}]})"),
             "an entry of \"files\" without a \"name\"");
  expect_bad(
      write_file(dir_ / "time.vtp.series", R"({"files": [{"name": "step0.vtp", "time": "x"}]})"),
      "the time of 'step0.vtp' is not a number");
  expect_bad(write_file(dir_ / "empty.vtp.series", R"({"files": []})"),
             "the series lists no data sets");
  expect_bad(
      write_file(dir_ / "gone.vtp.series", R"({"files": [{"name": "gone.vtp", "time": 0}]})"),
      "gone.vtp: no such file");
}

TEST_F(VtkIo, OpenFoamPatchesAndTimes) {
  const fs::path root = write_openfoam_case(dir_);
  for (const fs::path& path : {root / "cube.foam", root}) {
    SCOPED_TRACE(path.string());
    const Dataset all = read_dataset({path, {}});
    EXPECT_EQ(all.mesh.triangle_count(), 12u);
    EXPECT_EQ(all.mesh.vertex_count(), 8u);  // the patches welded
    EXPECT_EQ(all.times, (std::vector<double>{1.0, 2.0}));
    const Dataset walls = read_dataset({path, {"walls"}});
    EXPECT_EQ(walls.mesh.triangle_count(), 10u);
    ASSERT_TRUE(walls.mesh.vector_arrays.count("wallShearStress"));
    EXPECT_NEAR(walls.mesh.vector_arrays.at("wallShearStress")[0].x, -1.0f, 1e-6f);
    EXPECT_NEAR(walls.step(1).vector_arrays.at("wallShearStress")[0].x, -2.0f, 1e-6f);
  }
  try {
    read_dataset({root / "cube.foam", {"wing"}});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no patch matches 'wing' (patches: inlet, walls)"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(VtkIo, SamplesAVolumeAtPointsAndAlongNormals) {
  const fs::path path = dir_ / "block.vtu";
  vtkNew<vtkXMLUnstructuredGridWriter> w;
  w->SetInputData(hex_block());
  w->SetFileName(path.c_str());
  ASSERT_EQ(w->Write(), 1);
  const VolumeSample s = sample_volume(path, "U", 0, {{0.5f, 1.25f, 1.5f}, {5, 5, 5}});
  EXPECT_EQ(s.found, (std::vector<std::uint8_t>{1, 0}));
  EXPECT_NEAR(glm::length(s.values[0] - glm::vec3(0.5f, 2.5f, 4.5f)), 0.0f, 1e-5f);
  EXPECT_EQ(s.values[1], glm::vec3(0.0f));
  EXPECT_THROW(sample_volume(path, "nope", 0, {{1, 1, 1}}), InputError);

  // A surface inside the block whose normals point both ways: with an offset
  // every vertex finds the volume, along or against its normal.
  TriMesh plane;
  plane.positions = {{0.5f, 0.5f, 1}, {1.5f, 0.5f, 1}, {1.5f, 1.5f, 1}};
  plane.triangles = {{0, 1, 2}};
  plane.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  FieldSpec spec = FieldSpec::parse("sample:" + path.string() + ":U:0.25");
  FieldReport report;
  const std::vector<glm::vec3> v = evaluate_field(plane, spec, TangentMode::Full3D, &report);
  EXPECT_EQ(report.outside_volume, 0u);
  EXPECT_NEAR(v[0].z, 3.75f, 1e-5f);  // z = 1.25
  spec.offset = 1.5f;                 // z = 2.5 is outside; z = -0.5 too
  EXPECT_THROW(evaluate_field(plane, spec, TangentMode::Full3D), InputError);
}

TEST_F(VtkIo, WritesPolyDataWithTextureCoordinates) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  compute_vertex_normals(m);
  m.scalars["kmin"] = {1, 2, 3};
  m.scalars["dminx"] = {1, 1, 1};
  m.scalars["dminy"] = {0, 0, 0};
  m.scalars["dminz"] = {0, 0, 0};
  m.vector_arrays["U"] = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {0, 1}};
  const fs::path path = dir_ / "out.vtp";
  write_polydata(m, &uv, path, "out.png");
  const Dataset d = read_dataset({path, {}});
  EXPECT_EQ(d.mesh.scalars.at("kmin"), (std::vector<float>{1, 2, 3}));
  EXPECT_EQ(d.mesh.vector_arrays.at("U")[2], glm::vec3(7, 8, 9));
  EXPECT_EQ(d.mesh.vector_arrays.at("dmin")[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(d.mesh.other_arrays.at("TCoords"), 2);
  EXPECT_NE(test::read_file(path).find("TextureFile"), std::string::npos);
}

// On the motorBike case of scripts/cfd_motorbike.sh (skipped without it):
// OpenFOAM's wallShearStress, reversed, points along the near-wall flow
// (U sampled 5 mm off the wall), as docs/cfd.md says.
TEST_F(VtkIo, ReversedWallShearStressFollowsTheNearWallFlow) {
  const fs::path foam = fs::path(IBFVS_TEST_DATA_DIR) / "cfd" / "motorBike" / "motorBike.foam";
  if (!fs::exists(foam)) GTEST_SKIP() << "no " << foam << " (scripts/cfd_motorbike.sh makes it)";
  Scene scene;
  scene.mesh = foam.string();
  scene.blocks = {"motorBike*"};
  scene.time = TimeRange::parse("4");
  scene.field = FieldSpec::parse("file:wallShearStress");
  scene.reverse = true;
  const PreparedScene wss = prepare_scene(scene);
  const std::vector<glm::vec3> near_wall = evaluate_field(
      *wss.mesh, FieldSpec::parse("sample:" + foam.string() + ":U:0.005"), TangentMode::Project);
  double sum = 0.0;
  std::size_t n = 0, along = 0;
  for (std::size_t i = 0; i < near_wall.size(); ++i) {
    const float a = glm::length(wss.field[i]), b = glm::length(near_wall[i]);
    if (a < 1e-9f || b < 1e-6f) continue;
    const double c = glm::dot(wss.field[i], near_wall[i]) / (a * b);
    sum += c;
    along += c > 0.0;
    ++n;
  }
  ASSERT_GT(n, 1000u);
  std::printf(
      "reversed wallShearStress vs U 5 mm off the wall: mean cosine %.3f, %.1f%% of %zu "
      "vertices within 90 degrees\n",
      sum / static_cast<double>(n), 100.0 * static_cast<double>(along) / static_cast<double>(n), n);
  EXPECT_GT(sum / static_cast<double>(n), 0.5);
}

}  // namespace
}  // namespace ibfvs::vtktest
