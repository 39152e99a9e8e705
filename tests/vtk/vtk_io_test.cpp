// The dataset formats through ParaView's VTK: every layout and encoding a
// solver writes, arrays by name, cell data carried to the vertices,
// multiblocks, series, OpenFOAM cases, volume sampling, .vtp out, and one
// clear line for every kind of bad file. Files are written on the fly (VTK's
// own writers, or by hand where the exact bytes matter).

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
#include <vtkStructuredGrid.h>
#include <vtkStructuredGridWriter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLMultiBlockDataWriter.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <glm/geometric.hpp>

#include "helpers.h"
#include "ibfvs/core/dataset_io.h"
#include "ibfvs/core/error.h"
#include "ibfvs/core/mesh_source.h"
#include "ibfvs/core/scene_prep.h"
#include "ibfvs/core/vector_field.h"
#include "ibfvs/vtk/vtk_io.h"

namespace ibfvs {
namespace {
namespace fs = std::filesystem;
using test::TempDir;
using test::write_file;

class VtkIo : public ::testing::Test {
 protected:
  void SetUp() override { vtk::install_vtk_io(); }
  TempDir dir_;
};

// Two triangles of areas 0.5 and 1.5 sharing the edge (1,0)-(0,1)... as a
// quad (0,0) (1,0) (2,2) (0,1) split by VTK, plus a point vector and scalar.
// A unit square in z = 0 as one quad; point vectors v = (1, 0, 0), point
// scalar p = index, cell vectors w = (0, 1, 0), a 9-component cell tensor.
vtkSmartPointer<vtkPolyData> square(int extra_points = 0) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  for (const auto& p :
       {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)})
    pts->InsertNextPoint(p.x, p.y, p.z);
  for (int i = 0; i < extra_points; ++i) pts->InsertNextPoint(5, 5, i);
  poly->SetPoints(pts);
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = {0, 1, 2, 3};
  polys->InsertNextCell(4, quad);
  poly->SetPolys(polys);
  const auto n = pts->GetNumberOfPoints();
  vtkNew<vtkFloatArray> v, p;
  v->SetName("v");
  v->SetNumberOfComponents(3);
  p->SetName("p");
  for (vtkIdType i = 0; i < n; ++i) {
    v->InsertNextTuple3(1, 0, 0);
    p->InsertNextValue(static_cast<float>(i));
  }
  poly->GetPointData()->AddArray(v);
  poly->GetPointData()->AddArray(p);
  vtkNew<vtkFloatArray> w, t;
  w->SetName("w");
  w->SetNumberOfComponents(3);
  w->InsertNextTuple3(0, 1, 0);
  t->SetName("T");
  t->SetNumberOfComponents(9);
  const float nine[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  t->InsertNextTypedTuple(nine);
  poly->GetCellData()->AddArray(w);
  poly->GetCellData()->AddArray(t);
  return poly;
}

void expect_square(const Dataset& d) {
  EXPECT_EQ(d.mesh.triangle_count(), 2u);
  ASSERT_EQ(d.mesh.vertex_count(), 4u);
  ASSERT_TRUE(d.mesh.vector_arrays.count("v"));
  ASSERT_TRUE(d.mesh.vector_arrays.count("w"));  // cell data, now per vertex
  ASSERT_TRUE(d.mesh.scalars.count("p"));
  EXPECT_EQ(d.mesh.other_arrays.at("T"), 9);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(d.mesh.vector_arrays.at("v")[i], glm::vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(d.mesh.vector_arrays.at("w")[i] - glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    EXPECT_EQ(d.mesh.scalars.at("p")[i], static_cast<float>(i));
  }
  EXPECT_TRUE(d.times.empty());
}

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

// A 2 x 2 x 2 block of hexahedra with U = (x, 2y, 3z) at the points.
vtkSmartPointer<vtkUnstructuredGrid> hex_block() {
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> u;
  u->SetName("U");
  u->SetNumberOfComponents(3);
  const auto id = [](int i, int j, int k) { return static_cast<vtkIdType>(i + 3 * (j + 3 * k)); };
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        pts->InsertNextPoint(i, j, k);
        u->InsertNextTuple3(i, 2 * j, 3 * k);
      }
  grid->SetPoints(pts);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const vtkIdType c[8] = {
            id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
            id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        grid->InsertNextCell(VTK_HEXAHEDRON, 8, c);
      }
  grid->GetPointData()->AddArray(u);
  return grid;
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

fs::path write_multiblock(const TempDir& dir) {
  vtkNew<vtkMultiBlockDataSet> mb;
  mb->SetBlock(0, square());
  mb->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "wing");
  auto body = square();
  body->GetPoints()->SetPoint(0, 0, 0, -1);
  mb->SetBlock(1, body);
  mb->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "body");
  const fs::path path = dir / "plane.vtm";
  vtkNew<vtkXMLMultiBlockDataWriter> w;
  w->SetInputData(mb);
  w->SetFileName(path.c_str());
  EXPECT_EQ(w->Write(), 1);
  return path;
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

// A .pvd of three steps of the square, v = (k+1, 0, 0) at step k.
fs::path write_series(const TempDir& dir) {
  std::string pvd =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
      "<Collection>\n";
  for (int k = 0; k < 3; ++k) {
    auto poly = square();
    auto* v = vtkFloatArray::SafeDownCast(poly->GetPointData()->GetArray("v"));
    for (vtkIdType i = 0; i < 4; ++i) v->SetTuple3(i, k + 1, 0, 0);
    const std::string name = "step" + std::to_string(k) + ".vtp";
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetInputData(poly);
    w->SetFileName((dir / name).c_str());
    EXPECT_EQ(w->Write(), 1);
    pvd += "<DataSet timestep=\"" + std::to_string(0.5 * k) + "\" part=\"0\" file=\"" + name +
           "\"/>\n";
  }
  pvd += "</Collection>\n</VTKFile>\n";
  return write_file(dir / "run.pvd", pvd);
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
  EXPECT_NEAR(p.step_field(1)[0].x, 2.0f, 1e-6f);
  scene.time = TimeRange::parse("1");
  scene.reverse = true;
  const PreparedScene one = prepare_scene(scene);
  EXPECT_EQ(one.step_count, 1u);
  EXPECT_NEAR(one.field[0].x, -2.0f, 1e-6f);
  scene.time = TimeRange::parse("1:5");
  EXPECT_THROW(prepare_scene(scene), SettingError);
}

TEST_F(VtkIo, NumberedFilesAreASeries) {
  write_series(dir_);
  Scene scene;
  scene.mesh = (dir_ / "step*.vtp").string();
  scene.field = FieldSpec::parse("file:v");
  scene.tangent = TangentMode::Full3D;
  const PreparedScene p = prepare_scene(scene);
  EXPECT_EQ(p.step_count, 3u);
  EXPECT_NEAR(p.step_field(2)[0].x, 3.0f, 1e-6f);
}

// A one-cell OpenFOAM case: the unit cube, patches "inlet" (x = 0) and
// "walls" (the other five sides), times 1 and 2 with U = k * (1, 0, 0) in
// the cell and wallShearStress on the walls.
fs::path write_openfoam_case(const TempDir& dir) {
  const fs::path root = dir / "cube";
  fs::create_directories(root / "system");
  fs::create_directories(root / "constant" / "polyMesh");
  const auto header = [](const char* cls, const char* object) {
    return std::string("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class ") + cls +
           ";\n    object " + object + ";\n}\n";
  };
  write_file(root / "system" / "controlDict",
             header("dictionary", "controlDict") +
                 "application simpleFoam;\nstartTime 0;\nendTime 2;\ndeltaT 1;\n"
                 "writeControl timeStep;\nwriteInterval 1;\n");
  const fs::path mesh = root / "constant" / "polyMesh";
  write_file(mesh / "points", header("vectorField", "points") +
                                  "8\n(\n(0 0 0)\n(1 0 0)\n(1 1 0)\n(0 1 0)\n(0 0 1)\n(1 0 1)\n"
                                  "(1 1 1)\n(0 1 1)\n)\n");
  // Faces, normals out of the cell: inlet (x = 0) first, then the walls.
  write_file(mesh / "faces", header("faceList", "faces") +
                                 "6\n(\n4(0 4 7 3)\n4(1 2 6 5)\n4(0 1 5 4)\n4(3 7 6 2)\n"
                                 "4(0 3 2 1)\n4(4 5 6 7)\n)\n");
  write_file(mesh / "owner", header("labelList", "owner") + "6\n(\n0 0 0 0 0 0\n)\n");
  write_file(mesh / "neighbour", header("labelList", "neighbour") + "0\n(\n)\n");
  write_file(mesh / "boundary",
             header("polyBoundaryMesh", "boundary") +
                 "2\n(\ninlet\n{\n    type patch;\n    nFaces 1;\n    startFace 0;\n}\n"
                 "walls\n{\n    type wall;\n    nFaces 5;\n    startFace 1;\n}\n)\n");
  for (int k = 1; k <= 2; ++k) {
    const fs::path t = root / std::to_string(k);
    fs::create_directories(t);
    const std::string u = "(" + std::to_string(k) + " 0 0)";
    write_file(t / "U", header("volVectorField", "U") +
                            "dimensions [0 1 -1 0 0 0 0];\ninternalField uniform " + u +
                            ";\nboundaryField\n{\n    inlet { type fixedValue; value uniform " + u +
                            "; }\n    walls { type fixedValue; value uniform (0 0 0); }\n}\n");
    write_file(t / "wallShearStress",
               header("volVectorField", "wallShearStress") +
                   "dimensions [0 2 -2 0 0 0 0];\ninternalField uniform (0 0 0);\n"
                   "boundaryField\n{\n    inlet { type calculated; value uniform (0 0 0); }\n"
                   "    walls { type calculated; value uniform (-" +
                   std::to_string(k) + " 0 0); }\n}\n");
  }
  write_file(root / "cube.foam", "");
  return root;
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

// ------------------------------------------------------------ bad input

// Reading `path` fails with one line that names the file and says `problem`.
void expect_bad(const fs::path& path, const std::string& problem,
                const std::vector<std::string>& blocks = {}) {
  try {
    const Dataset d = read_dataset({path, blocks});
    ADD_FAILURE() << path << ": read " << d.mesh.triangle_count() << " triangles, no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
#ifdef __SANITIZE_ADDRESS__
    // Under AddressSanitizer an allocation past the child's limit ends the
    // child with the sanitizer's own report (exit status 1), before VTK's
    // abort or our bad_alloc can say so.
    const bool memory = problem.find("too large to read") != std::string::npos ||
                        problem.find("(SIGABRT)") != std::string::npos;
    if (memory && what.find("VTK's reader stopped on it without an answer (exit status 1") !=
                      std::string::npos)
      return;
#endif
    EXPECT_NE(what.find(problem), std::string::npos) << what;
  }
}

// A file whose cells VTK reads past into memory it never wrote: what comes
// out varies from run to run (ParaView shows the same). Either one line
// naming the file, or a mesh whose every index is in range.
void expect_line_or_valid_mesh(const fs::path& path) {
  try {
    const Dataset d = read_dataset({path, {}});
    EXPECT_NO_THROW(validate_mesh(d.mesh, path.string()));
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

std::string legacy(const std::string& points, const std::string& polygons,
                   const std::string& extra = "") {
  return "# vtk DataFile Version 4.2\nbad\nASCII\nDATASET POLYDATA\n" + points + polygons + extra;
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

TEST_F(VtkIo, BadLegacyFiles) {
  const std::string pts = "POINTS 3 float\n0 0 0 1 0 0 0 1 0\n";
  expect_bad(write_file(dir_ / "empty.vtk", ""), "empty");
  expect_bad(dir_ / "missing.vtk", "no such file");
  expect_bad(write_file(dir_ / "garbage.vtk", std::string("\x7f\x45\x4c\x46 \x01\x02 garbage", 16)),
             "");
  expect_bad(write_file(dir_ / "truncated.vtk", legacy("POINTS 3 float\n0 0 0 1 0", "")), "");
  expect_bad(write_file(dir_ / "negative.vtk", legacy("POINTS -5 float\n", "")), "");
  expect_bad(write_file(dir_ / "huge.vtk", legacy("POINTS 400000000000 float\n0 0 0\n", "")), "");
  // A cell count no file holds, but a size that VTK reads by: VTK reads the
  // one triangle, and so does ibfvs (VTK's parser is the only one).
  EXPECT_EQ(read_dataset({write_file(dir_ / "huge_cells.vtk",
                                     legacy(pts, "POLYGONS 900000000000 4\n3 0 1 2\n")),
                          {}})
                .mesh.triangle_count(),
            1u);
  expect_bad(write_file(dir_ / "huge_field.vtk",
                        legacy(pts, "POLYGONS 1 4\n3 0 1 2\n",
                               "POINT_DATA 3\nFIELD FieldData 1\nwss 3 900000000000 float\n")),
             "VTK's reader crashed on it (SIGABRT)");
  expect_bad(write_file(dir_ / "range.vtk", legacy(pts, "POLYGONS 1 4\n3 0 1 99\n")),
             "refers to point 99 but there are only 3");
  {
    auto poly = square();
    poly->GetPoints()->SetPoint(2, 1, std::nan(""), 0);
    vtkNew<vtkPolyDataWriter> w;
    w->SetInputData(poly);
    w->SetFileName((dir_ / "nan.vtk").c_str());
    w->SetFileTypeToBinary();
    ASSERT_EQ(w->Write(), 1);
    expect_bad(dir_ / "nan.vtk", "point 2 has a non-finite coordinate");
  }
  expect_bad(write_file(dir_ / "lines.vtk", legacy(pts, "LINES 1 4\n3 0 1 2\n")), "has no surface");
  // What the fuzzers found: VTK 9.2 crashed on these (docs/reliability.md);
  // read in a child process, a crash is one line naming the file.
  expect_bad(write_file(dir_ / "types.vtk",
                        "# vtk DataFile Version 4.2\nbad\nASCII\nDATASET UNSTRUCTURED_GRID\n" +
                            pts + "CELLS 1 4\n3 0 1 2\n"),
             "has no surface to show (3 points, 0 cells");
  expect_bad(write_file(dir_ / "1e299.vtk", legacy("POINTS 1e299 float\n0 0 0\n", "")),
             "Unsupported data type: e299");
  expect_line_or_valid_mesh(
      write_file(dir_ / "cells.vtk", legacy(pts, "POLYGONS 2 6\n3 0 1 2\n9 0\n")));
  const std::string v5 = "# vtk DataFile Version 5.1\nv5\nASCII\nDATASET POLYDATA\n" + pts +
                         "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n0 1\n"
                         "FIELD FieldData 1\n";
  expect_bad(write_file(dir_ / "cut.vtk", v5), "VTK's reader crashed on it (SIGSEGV)");
  // A binary cell list before version 5 whose records do not fill its size:
  // VTK 9.2's ImportLegacyFormat read past its array (SEGV).
  const auto be = [](std::initializer_list<std::uint32_t> values) {
    std::string out;
    for (const std::uint32_t v : values)
      for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> shift) & 0xFF);
    return out;
  };
  const std::string binary_head =
      "# vtk DataFile Version 4.2\nb\nBINARY\nDATASET POLYDATA\n"
      "POINTS 3 int\n" +
      be({0, 0, 0, 1, 0, 0, 0, 1, 0}) + "\n";
  expect_bad(write_file(dir_ / "binary_cells.vtk",
                        binary_head + "POLYGONS 1 4\n" + be({70000, 0, 1, 2}) + "\n"),
             "VTK's reader crashed on it (SIGSEGV)");
  expect_line_or_valid_mesh(write_file(
      dir_ / "binary_short.vtk", binary_head + "POLYGONS 2 6\n" + be({3, 0, 1, 2, 0, 5}) + "\n"));
  expect_bad(write_file(dir_ / "binary_cut.vtk", binary_head + "POLYGONS 1 4\n" + be({3, 0})),
             "Error reading binary cell data!");
  expect_bad(write_file(dir_ / "binary_points.vtk",
                        "# vtk DataFile Version 4.2\nb\nBINARY\nDATASET POLYDATA\n"
                        "POINTS 3 double\n" +
                            be({0, 0, 0})),
             "Error reading binary data!");
  // "Version 5" without a minor number is version 0 to VTK: cell records,
  // here the text of an OFFSETS line.
  std::string no_minor =
      binary_head + "POLYGONS 2 3\nOFFSETS vtktypeint64\n" + be({0, 0, 0, 3}) + "\n";
  no_minor.replace(0, no_minor.find('\n') + 1, "# vtk DataFile Version 5\n");
  expect_bad(write_file(dir_ / "no_minor.vtk", no_minor), "VTK's reader crashed on it (SIGSEGV)");
  // A block cut short: VTK takes its neighbour's bytes and reads on from
  // the middle of a section (VTK 9.2 crashed on some of these).
  std::string overrun = binary_head + "POLYGONS 1 4\n" + be({3, 0, 1, 2}) + "\n";
  overrun.replace(overrun.find("POINTS 3"), 8, "POINTS 4");
  expect_bad(write_file(dir_ / "overrun.vtk", overrun), "Unrecognized keyword: 4");
  std::string types_only = binary_head + "CELL_TYPES 1\n" + be({5}) + "\n";
  types_only.replace(types_only.find("POLYDATA"), 8, "UNSTRUCTURED_GRID");
  expect_bad(write_file(dir_ / "types_only.vtk", types_only),
             "has no surface to show (3 points, 0 cells");
  // Points of a type that is no number type: VTK 9.2 read none (SEGV).
  expect_bad(write_file(dir_ / "ptype.vtk", legacy("POINTS 3 FIELD\n0 0 0 1 0 0 0 1 0\n", "")),
             "Unsupported data type: field");
  std::string binary_type = binary_head;
  binary_type.replace(binary_type.find("POINTS 3 int"), 12, "POINTS 3 FIELD");
  expect_bad(write_file(dir_ / "binary_ptype.vtk", binary_type), "Unsupported data type: field");
  // VTK takes a word for the keyword it begins with, in any case: "FIELDS
  // 12 float" is a FIELD without an array count (VTK 9.2: SEGV), and
  // "ASCII?" is ASCII.
  expect_bad(write_file(dir_ / "fields.vtk",
                        "# vtk DataFile Version 4.2\nx\nASCII?\nDATASET POLYDATA\nFIELDS 12 float\n"
                        "0 0 0\n"),
             "VTK's reader crashed on it (SIGSEGV)");
  // and the same list, whole, reads.
  EXPECT_EQ(read_dataset({write_file(dir_ / "binary_ok.vtk",
                                     binary_head + "POLYGONS 1 4\n" + be({3, 0, 1, 2}) + "\n"),
                          {}})
                .mesh.triangle_count(),
            1u);
  // After an array VTK reads a METADATA section, up to a blank line; a line
  // that only began with that word made VTK 9.2 crash (fuzzing).
  EXPECT_EQ(read_dataset({write_file(dir_ / "metadata_ok.vtk",
                                     binary_head + "METADATA\nINFORMATION 0\n\nPOLYGONS 1 4\n" +
                                         be({3, 0, 1, 2}) + "\n"),
                          {}})
                .mesh.triangle_count(),
            1u);
  EXPECT_EQ(read_dataset({write_file(dir_ / "metadata_bad.vtk",
                                     binary_head + "metadata!" + std::string("\0\x05", 2) +
                                         "\n\nPOLYGONS 1 4\n" + be({3, 0, 1, 2}) + "\n"),
                          {}})
                .mesh.triangle_count(),
            1u);
  // A structured grid: before reading, VTK 9.2 takes every word of the file
  // for a keyword, binary data included, and crashed on "FieldD" inside the
  // points (fuzzing). One that VTK wrote, field data included, reads.
  {
    vtkNew<vtkStructuredGrid> grid;
    grid->SetDimensions(2, 2, 1);
    vtkNew<vtkPoints> points;
    for (const auto& p : {glm::vec3(0, 0, 0), {1, 0, 0}, {0, 1, 0}, {1, 1, 0}})
      points->InsertNextPoint(p.x, p.y, p.z);
    grid->SetPoints(points);
    vtkNew<vtkFloatArray> field;
    field->SetName("f");
    field->InsertNextValue(1);
    field->InsertNextValue(2);
    grid->GetFieldData()->AddArray(field);
    vtkNew<vtkStructuredGridWriter> w;
    w->SetInputData(grid);
    w->SetFileName((dir_ / "grid.vtk").c_str());
    w->SetFileTypeToBinary();
    ASSERT_EQ(w->Write(), 1);
    EXPECT_EQ(read_dataset({dir_ / "grid.vtk", {}}).mesh.triangle_count(), 2u);
  }
  expect_bad(write_file(dir_ / "grid_bad.vtk",
                        "# vtk DataFile Version 5.1\ng\nBINARY\nDATASET STRUCTURED_GRID\n"
                        "DIMENSIONS 2 2 1\nPOINTS 4 float\n" +
                            std::string(41, '\0') + " FieldD\n"),
             "VTK's reader crashed on it (SIGSEGV)");
  expect_bad(
      write_file(dir_ / "short_array.vtk", legacy(pts, "POLYGONS 1 4\n3 0 1 2\n",
                                                  "POINT_DATA 3\nVECTORS v float\n1 0 0 1 0 0\n")),
      "");
}

TEST_F(VtkIo, BadXmlFiles) {
  const fs::path good = dir_ / "good.vtp";
  {
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetInputData(square());
    w->SetFileName(good.c_str());
    w->SetDataModeToAscii();
    ASSERT_EQ(w->Write(), 1);
  }
  const std::string text = test::read_file(good);
  expect_bad(write_file(dir_ / "truncated.vtp", text.substr(0, text.size() / 2)), "");
  expect_bad(write_file(dir_ / "garbage.vtp", "<<<< not xml at all"), "");
  std::string range = text;
  const std::size_t conn = range.find("Name=\"connectivity\"", range.find("<Polys>"));
  ASSERT_NE(conn, std::string::npos);
  const std::size_t values = range.find('>', conn) + 1;
  range.replace(values, range.find('<', values) - values, "\n0 1 2 77\n");
  expect_bad(write_file(dir_ / "range.vtp", range), "refers to point 77");
  // Two cell arrays of one name (here one in other quotes, spaces and an
  // entity): VTK 9.2's XML readers crashed on the second (fuzzing).
  std::string twice = text;
  const std::size_t cell_data = twice.find("<CellData");
  ASSERT_NE(cell_data, std::string::npos);
  const std::size_t first_array = twice.find("<DataArray", cell_data);
  const std::size_t name_at = twice.find("Name=\"", first_array) + 6;
  const std::string array_name = twice.substr(name_at, twice.find('"', name_at) - name_at);
  ASSERT_FALSE(array_name.empty());
  twice.insert(first_array, "<DataArray type='Float32' Name = '&#" +
                                std::to_string(static_cast<int>(array_name[0])) + ";" +
                                array_name.substr(1) + "' format='ascii'>1</DataArray>\n");
  expect_bad(write_file(dir_ / "twice.vtp", twice), "Cannot read cell data array");
  std::string huge = text;
  const std::size_t np = huge.find("NumberOfPoints=\"4\"");
  ASSERT_NE(np, std::string::npos);
  huge.replace(np, 18, "NumberOfPoints=\"900000000000\"");
  expect_bad(write_file(dir_ / "huge.vtp", huge), "");
  std::string negative = text;
  negative.replace(np, 18, "NumberOfPoints=\"-4\"");
  expect_bad(write_file(dir_ / "negative.vtp", negative), "");
  // Binary data whose headers declare what the file cannot hold: VTK 9.2
  // allocated 12 GB for a 6 KB file (a compressed block count) and aborted
  // (a last cell offset of 2^62), which fuzzing found.
  const auto appended = [&](const std::string& name, bool compressed) {
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetInputData(square());
    w->SetFileName((dir_ / name).c_str());
    w->SetDataModeToAppended();
    w->EncodeAppendedDataOff();
    w->SetHeaderTypeToUInt32();
    w->SetByteOrderToLittleEndian();
    if (compressed)
      w->SetCompressorTypeToZLib();
    else
      w->SetCompressorTypeToNone();
    EXPECT_EQ(w->Write(), 1);
    return test::read_file(dir_ / name);
  };
  // The appended bytes of the array `array` (after the "_" marker).
  const auto data_of = [](const std::string& file, const std::string& array) {
    // (the polygons' arrays: the empty vertex, line and strip lists come first)
    const std::size_t tag =
        file.find("Name=\"" + array + "\"", array == "offsets" ? file.find("<Polys>") : 0);
    const std::size_t at = file.find("offset=\"", tag) + 8;
    return file.find('_', file.find("<AppendedData")) + 1 + std::stoul(file.substr(at));
  };
  std::string blocks = appended("blocks.vtp", true);
  blocks.replace(data_of(blocks, "v"), 4, std::string("\xff\xff\xff\x7f", 4));
  expect_bad(write_file(dir_ / "blocks.vtp", blocks), "too large to read");
  // A block table that disagrees with itself: VTK read past it (SEGV).
  std::string table = appended("table.vtp", true);
  table.replace(data_of(table, "v") + 8, 4, std::string("\0\0\0\x7f", 4));
  expect_bad(write_file(dir_ / "table.vtp", table), "Decompression produced incorrect size");
  // A cell with fewer points than its type has: VTK's surface filter read
  // past the cell (SEGV).
  {
    auto grid = hex_block();
    const vtkIdType three[3] = {0, 1, 2};
    grid->InsertNextCell(VTK_WEDGE, 3, three);
    vtkNew<vtkXMLUnstructuredGridWriter> w;
    w->SetInputData(grid);
    w->SetFileName((dir_ / "wedge.vtu").c_str());
    ASSERT_EQ(w->Write(), 1);
    expect_bad(dir_ / "wedge.vtu", "has 3 points; it needs 6");
  }
  std::string offsets = appended("offsets.vtp", false);
  ASSERT_NE(offsets.find("type=\"Int64\" Name=\"offsets\""), std::string::npos);
  // One polygon: its 4-byte size header, then the one Int64 offset.
  offsets.replace(data_of(offsets, "offsets") + 4, 8, std::string("\0\0\0\0\0\0\0\x40", 8));
  expect_bad(write_file(dir_ / "offsets.vtp", offsets),
             "the \"connectivity\" array is not long enough");
  std::string bytes = appended("bytes.vtp", false);
  bytes.replace(data_of(bytes, "Points"), 4, std::string("\0\0\0\x10", 4));
  // A size header larger than the data: VTK reads the points it needs.
  EXPECT_EQ(read_dataset({write_file(dir_ / "bytes.vtp", bytes), {}}).mesh.triangle_count(), 2u);
  // A multiblock whose piece is missing; a .pvd naming a missing file.
  const fs::path vtm = write_multiblock(dir_);
  fs::remove_all(dir_ / "plane");
  expect_bad(vtm, "");
  expect_bad(write_file(dir_ / "bad.pvd",
                        "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" "
                        "file=\"nowhere.vtp\"/></Collection></VTKFile>"),
             "nowhere.vtp: no such file");
  expect_bad(write_file(dir_ / "notpvd.pvd", "<VTKFile type=\"PolyData\"></VTKFile>"),
             "not a VTK collection");
  fs::create_directories(dir_ / "nocase");
  expect_bad(dir_ / "nocase" / "x.foam", "");
}

TEST_F(VtkIo, MissingAndWrongSizedArraysNameWhatThereIs) {
  const fs::path path = dir_ / "sq.vtp";
  vtkNew<vtkXMLPolyDataWriter> w;
  w->SetInputData(square());
  w->SetFileName(path.c_str());
  ASSERT_EQ(w->Write(), 1);
  const Dataset d = read_dataset({path, {}});
  try {
    file_vectors(d.mesh, "wallShearStress");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "file:wallShearStress: no such array (arrays: v (3), w (3), p (1), T (9))");
  }
  EXPECT_THROW(file_vectors(d.mesh, "T"), InputError);
  EXPECT_THROW(file_vectors(d.mesh, ""), InputError);  // two vector arrays: name one
}

}  // namespace
}  // namespace ibfvs

namespace ibfvs {
namespace {

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
}  // namespace ibfvs
