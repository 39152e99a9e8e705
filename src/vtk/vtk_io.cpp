#include "ibfvs/vtk/vtk_io.h"

// Sections: reading one file (VTK's readers by extension, OpenFOAM's times) |
// series (.pvd, .series) | the source of a request and reading it in a child
// process | volumes for sampling | public (read, sample, write). Message
// capture: messages.cpp; surfaces of every dataset kind: surfaces.cpp.

#include "internal.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include <vtkAppendFilter.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkLogger.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkMultiPieceDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOpenFOAMReader.h>
#include <vtkOutputWindow.h>
#include <vtkPartitionedDataSet.h>
#include <vtkPartitionedDataSetCollection.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProbeFilter.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>
#include <vtkStringArray.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkVersion.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLGenericDataObjectReader.h>
#include <vtkXMLPartitionedDataSetCollectionReader.h>
#include <vtkXMLPartitionedDataSetReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtk_nlohmannjson.h>
#include VTK_NLOHMANN_JSON(json.hpp)

#include "ibfvs/core/mesh/mesh_bytes.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"
#include "ibfvs/core/support/isolation.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs::vtk {
namespace fs = std::filesystem;
using namespace detail;

namespace {

// ------------------------------------------------------------ reading one file

// The OpenFOAM reader, set up for the boundary patches (surface) or the
// internal mesh (volume); `blocks` picks patches.
vtkSmartPointer<vtkOpenFOAMReader> openfoam_reader(const Guard& g, bool volume,
                                                   const std::vector<std::string>& blocks) {
  fs::path file = g.path();
  std::error_code ec;
  if (fs::is_directory(file, ec)) {
    if (!fs::is_regular_file(file / "system" / "controlDict", ec))
      g.fail("not an OpenFOAM case (no system/controlDict)");
    file = file / "system" / "controlDict";
  } else if (!fs::is_regular_file(file.parent_path().empty()
                                      ? fs::path("system/controlDict")
                                      : file.parent_path() / "system" / "controlDict",
                                  ec)) {
    g.fail("not in an OpenFOAM case (no system/controlDict beside it)");
  }
  auto reader = vtkSmartPointer<vtkOpenFOAMReader>::New();
  reader->SetFileName(file.string().c_str());
  reader->SetCreateCellToPoint(volume ? 1 : 0);  // surfaces: area-weighted here instead
  reader->SetReadZones(0);
  reader->SetSkipZeroTime(1);
  reader->SetCacheMesh(1);
  reader->UpdateInformation();
  g.check();
  std::vector<std::string> patches;
  for (int i = 0; i < reader->GetNumberOfPatchArrays(); ++i)
    patches.emplace_back(reader->GetPatchArrayName(i));
  std::vector<bool> used(blocks.size(), false);
  for (const std::string& name : patches) {
    bool on = false;
    if (volume) {
      on = name == "internalMesh";
    } else if (name.rfind("patch/", 0) == 0) {
      const std::string bare = name.substr(6);
      if (blocks.empty()) on = true;
      for (std::size_t b = 0; b < blocks.size(); ++b)
        if (glob_match(blocks[b], bare) || glob_match(blocks[b], name)) on = used[b] = true;
    }
    reader->SetPatchArrayStatus(name.c_str(), on ? 1 : 0);
  }
  for (std::size_t b = 0; b < blocks.size(); ++b)
    if (!used[b]) {
      std::string known;
      for (const std::string& name : patches)
        if (name.rfind("patch/", 0) == 0) known += (known.empty() ? "" : ", ") + name.substr(6);
      g.fail("no patch matches '" + blocks[b] + "' (patches: " + (known.empty() ? "none" : known) +
             ")");
    }
  // Every field, as cell data.
  for (int i = 0; i < reader->GetNumberOfCellArrays(); ++i)
    reader->SetCellArrayStatus(reader->GetCellArrayName(i), 1);
  return reader;
}

std::vector<double> openfoam_times(vtkOpenFOAMReader* reader) {
  std::vector<double> times;
  if (vtkDoubleArray* t = reader->GetTimeValues())
    for (vtkIdType i = 0; i < t->GetNumberOfTuples(); ++i) times.push_back(t->GetValue(i));
  return times;
}

vtkSmartPointer<vtkDataObject> read_openfoam_step(vtkOpenFOAMReader* reader,
                                                  const std::vector<double>& times,
                                                  std::size_t step, const Guard& g) {
  if (!times.empty()) {
    if (step >= times.size())
      g.fail("has " + std::to_string(times.size()) + " time steps, asked for step " +
             std::to_string(step));
    reader->UpdateTimeStep(times[step]);
  } else {
    reader->Update();
  }
  g.check();
  vtkSmartPointer<vtkDataObject> out = reader->GetOutput();
  return out;
}

// A single VTK file (legacy or XML, any dataset kind).
vtkSmartPointer<vtkDataObject> read_vtk_file(const Guard& g) {
  require_file(g);
  vtkSmartPointer<vtkDataObject> out;
  if (lower_extension(g.path()) == ".vtk") {
    vtkNew<vtkGenericDataObjectReader> reader;
    reader->SetFileName(g.path().string().c_str());
    reader->ReadAllScalarsOn();
    reader->ReadAllVectorsOn();
    reader->ReadAllNormalsOn();
    reader->ReadAllTensorsOn();
    reader->ReadAllFieldsOn();
    reader->ReadAllTCoordsOn();
    reader->ReadAllColorScalarsOn();
    reader->Update();
    g.check();
    out = reader->GetOutput();
  } else {
    // The generic reader takes every XML kind but VTK 9.2's partitioned
    // data sets and collections, which have readers of their own.
    vtkSmartPointer<vtkXMLReader> reader;
    const std::string ext = lower_extension(g.path());
    if (ext == ".vtpd")
      reader = vtkSmartPointer<vtkXMLPartitionedDataSetReader>::New();
    else if (ext == ".vtpc")
      reader = vtkSmartPointer<vtkXMLPartitionedDataSetCollectionReader>::New();
    else
      reader = vtkSmartPointer<vtkXMLGenericDataObjectReader>::New();
    reader->SetFileName(g.path().string().c_str());
    reader->Update();
    g.check();
    out = reader->GetOutputDataObject(0);
  }
  if (!out) g.fail("VTK could not read it (not a VTK file?)");
  return out;
}

// ------------------------------------------------------------ series (.pvd, .series)

// A time series of files: for each distinct time, its files (parts).
using SeriesSteps = std::vector<std::pair<double, std::vector<fs::path>>>;

struct SeriesEntry {
  double time = 0.0;
  fs::path file;
};

// Entries in time order, those of one time together (the parts of a step).
SeriesSteps group_steps(std::vector<SeriesEntry> entries, const Guard& g) {
  if (entries.empty()) g.fail("the series lists no data sets");
  std::stable_sort(entries.begin(), entries.end(),
                   [](const SeriesEntry& a, const SeriesEntry& b) { return a.time < b.time; });
  SeriesSteps steps;
  for (const SeriesEntry& e : entries) {
    if (steps.empty() || steps.back().first != e.time) steps.push_back({e.time, {}});
    steps.back().second.push_back(e.file);
  }
  return steps;
}

fs::path beside(const Guard& g, const std::string& file) {
  if (fs::path(file).is_absolute()) return file;
  fs::path path = g.path().parent_path() / file;
  // OpenFOAM 1912's foamToVTK -legacy lists "_10" for CASE_10.vtk in
  // CASE.vtk.series: where the name is missing, the file it meant.
  std::error_code ec;
  const fs::path inner = g.path().stem();  // CASE.vtk
  if (!fs::exists(path, ec) && !inner.extension().empty()) {
    fs::path meant =
        g.path().parent_path() / (inner.stem().string() + file + inner.extension().string());
    if (fs::exists(meant, ec)) path = std::move(meant);
  }
  return path;
}

// A .pvd collection (ParaView's XML: <DataSet timestep= file=>).
SeriesSteps read_pvd(const Guard& g) {
  require_file(g);
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(g.path().string().c_str());
  if (!parser->Parse()) {
    g.check();
    g.fail("not a well-formed .pvd (XML) file");
  }
  vtkXMLDataElement* root = parser->GetRootElement();
  if (!root || std::strcmp(root->GetName(), "VTKFile") != 0 || !root->GetAttribute("type") ||
      std::strcmp(root->GetAttribute("type"), "Collection") != 0)
    g.fail("not a VTK collection (.pvd): expected <VTKFile type=\"Collection\">");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  if (!collection) g.fail("no <Collection> element");
  std::vector<SeriesEntry> entries;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = collection->GetNestedElement(i);
    if (std::strcmp(e->GetName(), "DataSet") != 0) continue;
    const char* file = e->GetAttribute("file");
    if (!file || !*file) g.fail("a <DataSet> without a file attribute");
    SeriesEntry entry;
    if (const char* t = e->GetAttribute("timestep")) {
      try {
        entry.time = parse_number(t);
      } catch (const InputError&) {
        g.fail(std::string("timestep '") + t + "' is not a number");
      }
    }
    entry.file = beside(g, file);
    entries.push_back(entry);
  }
  return group_steps(std::move(entries), g);
}

// ParaView's JSON file series (NAME.EXT.series, as ParaView and foamToVTK
// write it): {"file-series-version": "1.0", "files": [{"name": "a_0.vtu",
// "time": 0}, ...]}; names relative to the .series file.
SeriesSteps read_series(const Guard& g) {
  require_file(g);
  std::ifstream in(g.path(), std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  if (doc.is_discarded()) g.fail("not a well-formed .series (JSON) file");
  if (!doc.is_object() || !doc.contains("files") || !doc["files"].is_array())
    g.fail("not a ParaView file series: no \"files\" list");
  std::vector<SeriesEntry> entries;
  for (const nlohmann::json& f : doc["files"]) {
    if (!f.is_object() || !f.contains("name") || !f["name"].is_string() ||
        f["name"].get<std::string>().empty())
      g.fail("an entry of \"files\" without a \"name\"");
    SeriesEntry entry;
    entry.file = beside(g, f["name"].get<std::string>());
    if (f.contains("time")) {
      if (!f["time"].is_number())
        g.fail("the time of '" + f["name"].get<std::string>() + "' is not a number");
      entry.time = f["time"].get<double>();
    } else {
      entry.time = static_cast<double>(entries.size());
    }
    entries.push_back(entry);
  }
  return group_steps(std::move(entries), g);
}

bool is_series(const fs::path& p) {
  const std::string ext = lower_extension(p);
  return ext == ".pvd" || ext == ".series";
}

SeriesSteps read_series_file(const Guard& g) {
  return lower_extension(g.path()) == ".pvd" ? read_pvd(g) : read_series(g);
}

// One step of a series: its one file, or its parts as blocks named by file.
vtkSmartPointer<vtkDataObject> read_series_step(const SeriesSteps& steps, std::size_t k,
                                                const Guard& g) {
  if (k >= steps.size())
    g.fail("has " + std::to_string(steps.size()) + " time steps, asked for step " +
           std::to_string(k));
  try {
    if (steps[k].second.size() == 1) {
      const Guard part(steps[k].second[0]);
      return read_vtk_file(part);
    }
    vtkNew<vtkMultiBlockDataSet> parts;
    unsigned i = 0;
    for (const fs::path& file : steps[k].second) {
      const Guard part(file);
      parts->SetBlock(i, read_vtk_file(part));
      parts->GetMetaData(i++)->Set(vtkCompositeDataSet::NAME(), file.stem().string().c_str());
    }
    return parts;
  } catch (const InputError& e) {
    g.fail(e.what());  // the series' name first, then the part's
  }
}

// A mesh for ibfvs: degenerate triangles dropped, normals, checked.
// The first step's repairs: degenerate triangles out (`split`: those the
// polygons' splits left out already), normals, the mesh checked.
void finish(TriMesh& mesh, std::vector<std::string>& warnings, const Guard& g, std::size_t split) {
  const std::size_t dropped = split + remove_degenerate_triangles(mesh);
  if (mesh.triangles.empty()) g.fail("every triangle has zero area");
  if (dropped > 0)
    warnings.push_back(g.path().string() + ": " + std::to_string(dropped) +
                       " zero-area triangles dropped");
  compute_vertex_normals(mesh);
  validate_mesh(mesh, g.path().string());
}

// A dataset opened for reading its steps: their times (fewer than 2:
// steady) and how to read step k.
struct Source {
  std::vector<double> times;
  std::function<vtkSmartPointer<vtkDataObject>(std::size_t, const Guard&)> read_step;
  bool patterns_applied = false;  // the reader chose the blocks (OpenFOAM patches)
};

Source open_source(const DatasetRequest& request, const Guard& g) {
  const fs::path& path = request.path;
  Source source;
  if (is_openfoam(path)) {
    require_file(g);
    vtkSmartPointer<vtkOpenFOAMReader> reader = openfoam_reader(g, false, request.blocks);
    source.times = openfoam_times(reader);
    source.read_step = [reader, times = source.times](std::size_t k, const Guard& guard) {
      return read_openfoam_step(reader, times, k, guard);
    };
    source.patterns_applied = true;
  } else if (is_series(path)) {
    const SeriesSteps steps = read_series_file(g);
    for (const auto& s : steps) source.times.push_back(s.first);
    source.read_step = [steps](std::size_t k, const Guard& guard) {
      return read_series_step(steps, k, guard);
    };
  } else {
    source.read_step = [](std::size_t k, const Guard& guard) {
      if (k > 0) guard.fail("is one file, one time step; asked for step " + std::to_string(k));
      return read_vtk_file(guard);
    };
  }
  return source;
}

// Turns out-of-memory and other exceptions from VTK into a line about the file.
template <class F>
auto guarded(const fs::path& path, F&& f) {
  try {
    return f();
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw InputError(path.string() + ": too large to read (out of memory)");
  } catch (const std::exception& e) {
    throw InputError(path.string() + ": " + e.what());
  }
}

// Runs `work` (VTK reading `path`) in a child process: a crash or an
// allocation past the limit there becomes one error line naming the file
// (core/support/isolation.h), so VTK's own parser is the only one, and nothing here
// refuses what it reads.
IsolatedBytes read_in_child(const fs::path& path, const std::function<void(ByteWriter&)>& work) {
  // A file that holds all its data may take 256 times its size (zlib's best
  // ratio is about 1,000:1, real data's rarely beyond 20:1; then VTK's
  // filters), at least 2 GiB, at most the usual half of the memory: so that
  // a damaged header stops at a size near the file's, not after gigabytes.
  // Collections, series and cases name other files: the usual limit.
  IsolationLimits limits = reader_limits();
  static const std::set<std::string> whole = {".vtk", ".vtp", ".vtu", ".vts", ".vtr", ".vti"};
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && whole.count(lower_extension(path)) && limits.memory_bytes > 0)
    limits.memory_bytes = std::min<std::uint64_t>(limits.memory_bytes,
                                                  std::max<std::uint64_t>(2ull << 30, 256 * size));
  // No other thread of ours is inside VTK while the child is made.
  const std::lock_guard lock(vtk_mutex());
  return run_isolated(
      path.string(), "VTK's reader",
      [&](ByteWriter& out) {
        vtk_mutex_slot() = new std::recursive_mutex;  // NOLINT: the parent's stays held, unused
        // One thread: a pool of worker threads made in the parent has none here.
        vtkSMPTools::SetBackend("Sequential");
        guarded(path, [&] { work(out); });
      },
      limits);
}

// Step k's surface (the first: with its blocks and what was repaired), its
// polygons split as `memory` split the same cells before; then the splits
// it made of cells it had not seen.
void read_step_bytes(const DatasetRequest& request, std::size_t k, SplitMemory& memory,
                     ByteWriter& out) {
  const Guard g(request.path);
  const Source source = open_source(request, g);
  std::vector<std::string> blocks, warnings;
  const std::uint64_t known = memory.made();
  std::size_t dropped = 0;
  TriMesh mesh = surface_of(source.read_step(k, g), request.blocks, &blocks, warnings, g,
                            source.patterns_applied, false, &memory, &dropped);
  if (k == 0) {
    finish(mesh, warnings, g, dropped);
  } else {
    // The first step's repairs, by the same cells: the splits left out what
    // had no area when they were made, and a triangle of the same cells
    // that has none here stays (it is the first step's, and has no pixels);
    // its checks (finite points) are the caller's, which names the step.
    remove_degenerate_triangles(mesh, false);
    if (mesh.triangles.empty()) g.fail("step " + std::to_string(k) + ": no triangles");
  }
  put_mesh(out, mesh);
  out.put(blocks);
  out.put(warnings);
  out.put(source.times);
  memory.put_since(out, known);
}

// ------------------------------------------------------------ volumes for sampling

vtkSmartPointer<vtkDataSet> read_volume(const fs::path& path, std::size_t step, const Guard& g) {
  vtkSmartPointer<vtkDataObject> obj;
  if (is_openfoam(path)) {
    std::error_code ec;
    if (!fs::exists(path, ec)) g.fail("no such file");
    auto reader = openfoam_reader(g, true, {});
    obj = read_openfoam_step(reader, openfoam_times(reader), step, g);
  } else if (is_series(path)) {
    obj = read_series_step(read_series_file(g), step, g);
  } else {
    if (step > 0) g.fail("is one file, one time step; asked for step " + std::to_string(step));
    obj = read_vtk_file(g);
  }
  std::vector<Block> blocks;
  collect_blocks(obj, "", "", blocks);
  if (blocks.empty()) g.fail("holds no data set");
  for (const Block& b : blocks) check_dataset(b.data, b, g);
  if (blocks.size() == 1) return blocks[0].data;
  vtkNew<vtkAppendFilter> append;
  for (const Block& b : blocks) append->AddInputData(b.data);
  append->Update();
  g.check();
  return append->GetOutput();
}

std::string describe(vtkFieldData* data) {
  std::string out;
  for (int i = 0; data && i < data->GetNumberOfArrays(); ++i) {
    vtkAbstractArray* a = data->GetAbstractArray(i);
    if (!a || !a->GetName() || std::string(a->GetName()).rfind("vtk", 0) == 0) continue;
    out += (out.empty() ? "" : ", ") + std::string(a->GetName()) + " (" +
           std::to_string(a->GetNumberOfComponents()) + ")";
  }
  return out.empty() ? "none" : out;
}

VolumeSample sample_in_process(const fs::path& path, const std::string& array, std::size_t step,
                               const std::vector<glm::vec3>& points) {
  const Guard g(path);
  vtkSmartPointer<vtkDataSet> volume = read_volume(path, step, g);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToFloat();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    pts->SetPoint(static_cast<vtkIdType>(i), points[i].x, points[i].y, points[i].z);
  vtkNew<vtkPolyData> where;
  where->SetPoints(pts);
  vtkNew<vtkProbeFilter> probe;
  vtkNew<vtkStaticCellLocator> locator;
  probe->SetCellLocatorPrototype(locator);
  probe->SetInputData(where);
  probe->SetSourceData(volume);
  probe->Update();
  g.check();
  vtkDataSet* out = probe->GetOutput();
  vtkDataArray* a = out->GetPointData()->GetArray(array.c_str());
  if (!a) {
    const bool has_point = volume->GetPointData()->GetAbstractArray(array.c_str()) != nullptr;
    const bool has_cell = volume->GetCellData()->GetAbstractArray(array.c_str()) != nullptr;
    if (!has_point && !has_cell)
      g.fail("no array '" + array +
             "' in the volume (point arrays: " + describe(volume->GetPointData()) +
             "; cell arrays: " + describe(volume->GetCellData()) + ")");
    g.fail("the array '" + array + "' is not numeric");
  }
  if (a->GetNumberOfComponents() != 3)
    g.fail("the array '" + array + "' has " + std::to_string(a->GetNumberOfComponents()) +
           " components; a field needs 3");
  vtkDataArray* mask = out->GetPointData()->GetArray(probe->GetValidPointMaskArrayName());
  VolumeSample result;
  result.values.resize(points.size());
  result.found.resize(points.size());
  double v[3];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto id = static_cast<vtkIdType>(i);
    result.found[i] = mask ? static_cast<std::uint8_t>(mask->GetComponent(id, 0) != 0) : 1;
    a->GetTuple(id, v);
    result.values[i] = result.found[i] ? glm::vec3(v[0], v[1], v[2]) : glm::vec3(0.0f);
  }
  return result;
}

}  // namespace

// ------------------------------------------------------------ public

std::string vtk_version() {
  return vtkVersion::GetVTKVersionFull();
}

Dataset read(const DatasetRequest& request) {
  const std::string subject = request.path.string();
  // The splits of the steps' polygons: a later step with the first one's
  // cells gets its triangles (core/mesh/polygon.h says why). The children
  // read it as the fork left it; their new splits come back with the mesh.
  auto memory = std::make_shared<SplitMemory>();
  const IsolatedBytes bytes = read_in_child(
      request.path, [&](ByteWriter& out) { read_step_bytes(request, 0, *memory, out); });
  ByteReader in(bytes.view(), subject);
  Dataset d;
  d.mesh = get_mesh(in);
  d.blocks = in.get_strings();
  d.warnings = in.get_strings();
  std::vector<double> times = in.get_vector<double>();
  memory->take(in);
  validate_mesh(d.mesh, subject);
  if (times.size() > 1) {
    d.times = std::move(times);
    // Each step's whole surface: a moving mesh's points move, a changing
    // mesh's triangles differ (scene_prep takes either on).
    d.step = [request, memory](std::size_t k) {
      try {
        const IsolatedBytes step_bytes = read_in_child(
            request.path, [&](ByteWriter& out) { read_step_bytes(request, k, *memory, out); });
        ByteReader step_in(step_bytes.view(), request.path.string());
        TriMesh mesh = get_mesh(step_in);
        static_cast<void>(
            step_in.get_strings());  // the blocks, warnings and times: the first step's
        static_cast<void>(step_in.get_strings());
        static_cast<void>(step_in.get_vector<double>());
        // Not while another thread makes a child (it would copy the memory
        // half changed): the lock read_in_child makes them under.
        const std::lock_guard lock(vtk_mutex());
        memory->take(step_in);
        return mesh;
      } catch (const InputError& e) {
        // "PATH: problem" becomes "PATH: step K: problem".
        const std::string path = request.path.string(), what = e.what();
        const std::string step = "step " + std::to_string(k) + ": ";
        if (what.rfind(path + ": ", 0) == 0)
          throw InputError(path + ": " + step + what.substr(path.size() + 2));
        throw InputError(path + ": " + step + what);
      }
    };
  }
  return d;
}

VolumeSample sample(const fs::path& path, const std::string& array, std::size_t step,
                    const std::vector<glm::vec3>& points) {
  const IsolatedBytes bytes = read_in_child(path, [&](ByteWriter& out) {
    const VolumeSample s = sample_in_process(path, array, step, points);
    out.put(s.values);
    out.put(s.found);
  });
  ByteReader in(bytes.view(), path.string());
  VolumeSample result;
  result.values = in.get_vector<glm::vec3>();
  result.found = in.get_vector<std::uint8_t>();
  if (result.values.size() != points.size() || result.found.size() != points.size())
    throw InputError(path.string() + ": the sampled values do not match the points");
  return result;
}

void write_polydata(const TriMesh& mesh, const std::vector<glm::vec2>* uv, const fs::path& path,
                    const std::string& texture) {
  guarded(path, [&] {
    const Guard g(path);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.vertex_count()));
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
      points->SetPoint(static_cast<vtkIdType>(i), mesh.positions[i].x, mesh.positions[i].y,
                       mesh.positions[i].z);
    vtkNew<vtkCellArray> polys;
    polys->AllocateExact(static_cast<vtkIdType>(mesh.triangle_count()),
                         static_cast<vtkIdType>(3 * mesh.triangle_count()));
    for (const Triangle& t : mesh.triangles) {
      const vtkIdType ids[3] = {t[0], t[1], t[2]};
      polys->InsertNextCell(3, ids);
    }
    vtkNew<vtkPolyData> poly;
    poly->SetPoints(points);
    poly->SetPolys(polys);
    const auto vectors = [&](const std::string& name, const std::vector<glm::vec3>& v) {
      vtkNew<vtkFloatArray> a;
      a->SetName(name.c_str());
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
      for (std::size_t i = 0; i < v.size(); ++i)
        a->SetTypedTuple(static_cast<vtkIdType>(i), &v[i].x);
      poly->GetPointData()->AddArray(a);
      return a.GetPointer();
    };
    if (mesh.normals.size() == mesh.vertex_count())
      poly->GetPointData()->SetNormals(vectors("Normals", mesh.normals));
    if (mesh.vectors.size() == mesh.vertex_count() && !mesh.vectors.empty())
      poly->GetPointData()->SetVectors(vectors("vectors", mesh.vectors));
    for (const auto& [name, v] : mesh.vector_arrays) vectors(name, v);
    // Scalars NAMEx NAMEy NAMEz (the principal directions dminx.. of ibfvs
    // geometry) become one 3-component array NAME, as ParaView shows them.
    std::vector<std::string> joined;
    for (const auto& [name, values] : mesh.scalars) {
      if (name.size() < 2 || name.back() != 'x') continue;
      const std::string stem = name.substr(0, name.size() - 1);
      const auto y = mesh.scalars.find(stem + "y"), z = mesh.scalars.find(stem + "z");
      if (y == mesh.scalars.end() || z == mesh.scalars.end()) continue;
      joined.insert(joined.end(), {name, stem + "y", stem + "z"});
      if (stem == "n" && mesh.normals.size() == mesh.vertex_count()) continue;
      std::vector<glm::vec3> v(values.size());
      for (std::size_t i = 0; i < v.size(); ++i) v[i] = {values[i], y->second[i], z->second[i]};
      vectors(stem, v);
    }
    for (const auto& [name, values] : mesh.scalars) {
      if (std::find(joined.begin(), joined.end(), name) != joined.end()) continue;
      vtkNew<vtkFloatArray> a;
      a->SetName(name.c_str());
      a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
      for (std::size_t i = 0; i < values.size(); ++i)
        a->SetValue(static_cast<vtkIdType>(i), values[i]);
      poly->GetPointData()->AddArray(a);
    }
    if (uv) {
      vtkNew<vtkFloatArray> t;
      t->SetName("TCoords");
      t->SetNumberOfComponents(2);
      t->SetNumberOfTuples(static_cast<vtkIdType>(uv->size()));
      for (std::size_t i = 0; i < uv->size(); ++i)
        t->SetTypedTuple(static_cast<vtkIdType>(i), &(*uv)[i].x);
      poly->GetPointData()->SetTCoords(t);
    }
    if (!texture.empty()) {
      vtkNew<vtkStringArray> name;
      name->SetName("TextureFile");
      name->InsertNextValue(texture);
      poly->GetFieldData()->AddArray(name);
    }
    PendingFile pending(path);  // whole or not at all
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(pending.temporary().string().c_str());
    writer->SetInputData(poly);
    writer->SetDataModeToAppended();
    writer->SetEncodeAppendedData(0);  // raw bytes: smaller and faster than base64
    writer->SetCompressorTypeToZLib();
    const int ok = writer->Write();
    g.check();
    if (!ok) g.fail("could not be written");
    pending.commit();
  });
}

TriMesh surface_mesh(vtkDataObject* data, const std::string& name, bool cells_apart,
                     SplitMemory* memory) {
  if (!data) throw InputError(name + ": no data");
  const Guard g(name, false);
  std::vector<std::string> warnings;
  return surface_of(data, {}, nullptr, warnings, g, true, cells_apart, memory);
}

void install_vtk_io() {
  install_messages();
  install_dataset_io({read, sample, write_polydata});
}

}  // namespace ibfvs::vtk
