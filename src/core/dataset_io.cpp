#include "ibfvs/core/dataset_io.h"

#include <algorithm>
#include <cctype>
#include <mutex>
#include <optional>
#include <set>

#include "ibfvs/core/error.h"

namespace ibfvs {
namespace fs = std::filesystem;

namespace {

std::mutex& io_mutex() {
  static std::mutex m;
  return m;
}

std::optional<DatasetIo>& installed() {
  static std::optional<DatasetIo> io;
  return io;
}

DatasetIo require(const fs::path& path) {
  {
    const std::lock_guard lock(io_mutex());
    if (installed()) return *installed();
  }
  require_dataset_io(path);
  return {};  // not reached
}

}  // namespace

void install_dataset_io(DatasetIo io) {
  const std::lock_guard lock(io_mutex());
  installed() = std::move(io);
}

bool dataset_io_available() {
  const std::lock_guard lock(io_mutex());
  return installed().has_value();
}

void require_dataset_io(const fs::path& path, const std::string& what) {
  if (!dataset_io_available())
    throw InputError((what.empty() ? "" : what + ": ") + path.string() +
                     ": VTK and OpenFOAM files need ibfvs built with ParaView's VTK (Debian's "
                     "paraview-dev); this build left them out");
}

bool is_dataset_path(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // VTK's legacy and XML files (serial and parallel, every dataset kind,
  // multiblock and partitioned collections), ParaView's series (.pvd,
  // .series) and OpenFOAM cases.
  static const std::set<std::string> kExtensions = {
      ".vtk",  ".vtp",  ".vtu",  ".vts",  ".vtr",  ".vti",  ".vtm", ".vtmb",   ".vtpd",
      ".vtpc", ".pvtp", ".pvtu", ".pvts", ".pvtr", ".pvti", ".pvd", ".series", ".foam"};
  if (kExtensions.count(ext)) return true;
  std::error_code ec;
  return fs::is_directory(path, ec) && fs::is_regular_file(path / "system" / "controlDict", ec);
}

Dataset read_dataset(const DatasetRequest& request) {
  return require(request.path).read(request);
}

VolumeSample sample_volume(const fs::path& path, const std::string& array, std::size_t step,
                           const std::vector<glm::vec3>& points) {
  return require(path).sample(path, array, step, points);
}

void write_polydata(const TriMesh& mesh, const std::vector<glm::vec2>* uv, const fs::path& path,
                    const std::string& texture) {
  require(path).write_polydata(mesh, uv, path, texture);
}

}  // namespace ibfvs
