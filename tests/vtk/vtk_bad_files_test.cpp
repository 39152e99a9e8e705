// Bad VTK files, legacy and XML: each gives one clear line naming the file
// (or, where VTK itself reads past what the file holds, a valid mesh), never
// a crash; the fuzzers' findings among them. Files written by hand, byte by
// byte where the exact bytes matter.

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
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/core/scene/mesh_source.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/vtk/vtk_io.h"

#include "vtk_test_files.h"

namespace ibfvs::vtktest {
namespace {

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
}  // namespace ibfvs::vtktest
