#pragma once
// What the VTK tests share: the fixture (the readers installed, a scratch
// folder) and the files they write with VTK's own writers or by hand.

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include "helpers.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/vtk/vtk_io.h"

namespace ibfvs::vtktest {

namespace fs = std::filesystem;
using test::TempDir;
using test::write_file;

class VtkIo : public ::testing::Test {
 protected:
  void SetUp() override { vtk::install_vtk_io(); }
  TempDir dir_;
};

/// A unit square in z = 0 as one quad; point vectors v = (1, 0, 0), point
/// scalar p = index, cell vectors w = (0, 1, 0), a 9-component cell tensor T;
/// `extra_points` unused points beside it.
vtkSmartPointer<vtkPolyData> square(int extra_points = 0);
/// The square as read: two triangles, its arrays on the vertices, no times.
void expect_square(const Dataset& d);
/// A 2 x 2 x 2 block of hexahedra with U = (x, 2y, 3z) at the points.
vtkSmartPointer<vtkUnstructuredGrid> hex_block();
/// A .vtm of the square ("wing") and the block.
fs::path write_multiblock(const TempDir& dir);
/// A .pvd of three steps of the square (step0.vtp .. step2.vtp), v = (k+1, 0, 0) at step k.
fs::path write_series(const TempDir& dir);
/// A one-cell OpenFOAM case: the unit cube, patches "inlet" and "walls", times 1 and 2.
fs::path write_openfoam_case(const TempDir& dir);
/// Reading `path` fails with one line that names the file and says `problem`.
void expect_bad(const fs::path& path, const std::string& problem,
                const std::vector<std::string>& blocks = {});
/// Either one line naming the file, or a mesh whose every index is in range.
void expect_line_or_valid_mesh(const fs::path& path);
/// A legacy POLYDATA file of these sections.
std::string legacy(const std::string& points, const std::string& polygons,
                   const std::string& extra = "");

}  // namespace ibfvs::vtktest
