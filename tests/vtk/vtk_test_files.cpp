// The files the VTK tests write (vtk_test_files.h).

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

#include "vtk_test_files.h"

#include "helpers.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/core/scene/mesh_source.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/vtk/vtk_io.h"

namespace ibfvs::vtktest {

// Two triangles of areas 0.5 and 1.5 sharing the edge (1,0)-(0,1)... as a
// quad (0,0) (1,0) (2,2) (0,1) split by VTK, plus a point vector and scalar.
// A unit square in z = 0 as one quad; point vectors v = (1, 0, 0), point
// scalar p = index, cell vectors w = (0, 1, 0), a 9-component cell tensor.
vtkSmartPointer<vtkPolyData> square(int extra_points) {
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

// Reading `path` fails with one line that names the file and says `problem`.
void expect_bad(const fs::path& path, const std::string& problem,
                const std::vector<std::string>& blocks) {
  try {
    const Dataset d = read_dataset({path, blocks});
    ADD_FAILURE() << path << ": read " << d.mesh.triangle_count() << " triangles, no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
#if defined(__SANITIZE_ADDRESS__) || \
    defined(IBFVS_ASAN_RUNTIME)  // the runtime, built with it or not
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
                   const std::string& extra) {
  return "# vtk DataFile Version 4.2\nbad\nASCII\nDATASET POLYDATA\n" + points + polygons + extra;
}

}  // namespace ibfvs::vtktest
