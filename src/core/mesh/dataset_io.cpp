#include "ibfvs/core/mesh/dataset_io.h"

#include <algorithm>
#include <cctype>
#include <mutex>
#include <optional>

#include "ibfvs/core/support/error.h"

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

const std::vector<std::string>& dataset_extensions() {
  // VTK's legacy and XML files (serial and parallel, every dataset kind,
  // multiblock and partitioned collections) and ParaView's series.
  static const std::vector<std::string> extensions = {
      ".vtk",  ".vtp",  ".vtu", ".vts",  ".vtr",  ".vti",  ".pvtp", ".pvtu",  ".pvts",
      ".pvtr", ".pvti", ".vtm", ".vtmb", ".vtpd", ".vtpc", ".pvd",  ".series"};
  return extensions;
}

std::string dataset_extensions_text() {
  std::string text;
  for (const std::string& e : dataset_extensions()) text += (text.empty() ? "" : " ") + e;
  return text;
}

bool is_dataset_path(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const auto& known = dataset_extensions();
  if (ext == ".foam" || std::find(known.begin(), known.end(), ext) != known.end()) return true;
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
