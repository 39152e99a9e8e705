#pragma once
// What the parts of ibfvs::vtk share (not installed): the lock and message
// capture every VTK call runs under (messages.cpp), and the surface of a
// data object (surfaces.cpp). vtk_io.cpp reads files with them.

#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/mesh/polygon.h"

class vtkDataObject;
class vtkDataSet;

namespace ibfvs::vtk::detail {

/// The lock every VTK call runs under, behind a pointer: a reading child
/// (read_in_child) starts with a fresh one, since the parent's holder does
/// not exist there.
std::recursive_mutex*& vtk_mutex_slot();
std::recursive_mutex& vtk_mutex();

/// Routes VTK's output window and logger into the messages Guard reads.
void install_messages();

/// Holds the lock for one operation on one file; check() throws the first
/// error VTK reported since it began, as "PATH: message" on one line.
class Guard {
 public:
  /// capture false: a host application's data in memory (ParaView's),
  /// whose output window stays the host's.
  explicit Guard(std::filesystem::path path, bool capture = true);
  void check() const;
  [[noreturn]] void fail(std::string problem) const;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::unique_lock<std::recursive_mutex> lock_;
  std::filesystem::path path_;
  bool capture_ = true;
};

std::string lower_extension(const std::filesystem::path& p);
/// A .foam file or a folder (an OpenFOAM case).
bool is_openfoam(const std::filesystem::path& p);
/// Fails unless the guard's path exists and is a non-empty file (or a case).
void require_file(const Guard& g);

/// One data set of a composite, by name and path ("boundary/wing").
struct Block {
  std::string name, path;
  vtkDataSet* data = nullptr;
};

/// The data sets of a (composite) data object, depth first.
void collect_blocks(vtkDataObject* obj, const std::string& name, const std::string& path,
                    std::vector<Block>& out);

/// Connectivity in range, cells of the points their type has, points finite.
void check_dataset(vtkDataSet* ds, const Block& b, const Guard& g);

/// The surfaces of the blocks `patterns` choose (all when empty or when
/// the reader chose them: patterns_applied), merged into one mesh (see
/// vtk_io.h, surface_mesh, for cells_apart). Each block's polygons split as
/// `memory` split the same cells before (null: split anew); `dropped`
/// (where given) adds the degenerate triangles the splits left out.
TriMesh surface_of(vtkDataObject* obj, const std::vector<std::string>& patterns,
                   std::vector<std::string>* block_names, std::vector<std::string>& warnings,
                   const Guard& g, bool patterns_applied, bool cells_apart = false,
                   SplitMemory* memory = nullptr, std::size_t* dropped = nullptr);

}  // namespace ibfvs::vtk::detail
