#include "ibfvs/vtk/vtk_io.h"

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

#include "ibfvs/core/error.h"
#include "ibfvs/core/file_names.h"
#include "ibfvs/core/isolation.h"
#include "ibfvs/core/text.h"

namespace ibfvs::vtk {
namespace fs = std::filesystem;

namespace {

// ------------------------------------------------------------ VTK's messages
// VTK reports problems through its output window (standard error by
// default) and carries on with an empty output. All our VTK calls run under
// one lock with this window installed, so that each read can turn the first
// error into the one line the user sees.

// The lock itself behind a pointer: a reading child (read_in_child) starts
// with a fresh one, since the parent's holder does not exist there.
std::recursive_mutex*& vtk_mutex_slot() {
  static auto* m = new std::recursive_mutex;
  return m;
}

std::recursive_mutex& vtk_mutex() {
  return *vtk_mutex_slot();
}

// "ERROR: In /path/vtkXMLReader.cxx, line 12\nvtkXMLPolyDataReader (0x55): text\n\n" -> "text".
std::string clean_message(const char* raw) {
  std::string text = raw ? raw : "";
  if (const std::size_t at = text.find("): "); at != std::string::npos) {
    text = text.substr(at + 3);
  } else if (const std::size_t line = text.find(", line "); line != std::string::npos) {
    // "Generic Warning: In vtkDataReader.cxx, line 1537\nError reading ..."
    std::size_t k = line + 7;
    while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) ++k;
    text = text.substr(k);
  }
  while (!text.empty() && (text.front() == '\n' || text.front() == ' ')) text.erase(0, 1);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ' || text.back() == '\r'))
    text.pop_back();
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

class CaptureWindow : public vtkOutputWindow {
 public:
  static CaptureWindow* New();
  vtkTypeMacro(CaptureWindow, vtkOutputWindow) void DisplayText(const char*) override {}
  void DisplayErrorText(const char* text) override {
    errors.push_back(clean_message(text));
    last_words(errors.back());  // said if VTK aborts next (run_isolated)
  }
  void DisplayWarningText(const char* text) override { warnings.push_back(clean_message(text)); }
  void DisplayGenericWarningText(const char* text) override {
    warnings.push_back(clean_message(text));
  }
  void DisplayDebugText(const char*) override {}
  std::vector<std::string> errors, warnings;
};
vtkStandardNewMacro(CaptureWindow);

CaptureWindow* capture_window() {
  static vtkSmartPointer<CaptureWindow> window = [] {
    // VTK's logger also writes errors to standard error; the window is
    // where they are collected instead.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    auto w = vtkSmartPointer<CaptureWindow>::New();
    vtkOutputWindow::SetInstance(w);
    return w;
  }();
  return window;
}

// Holds the lock for one operation on one file; check() throws the first
// error VTK reported since it began.
class Guard {
 public:
  // capture false: a host application's data in memory (ParaView's), whose
  // output window stays the host's.
  explicit Guard(fs::path path, bool capture = true) : path_(std::move(path)), capture_(capture) {
    if (!capture_) return;
    lock_ = std::unique_lock<std::recursive_mutex>(vtk_mutex());
    capture_window()->errors.clear();
    capture_window()->warnings.clear();
  }
  void check() const {
    if (!capture_) return;
    const auto& errors = capture_window()->errors;
    if (!errors.empty()) fail(errors.front());
    // The legacy reader only warns when data runs short ("Error reading
    // ascii data. Possible mismatch of datasize with declaration.").
    for (const std::string& w : capture_window()->warnings)
      if (w.find("rror") != std::string::npos) fail(w);
  }
  [[noreturn]] void fail(std::string problem) const {
    // One line, whatever VTK or the file put into it.
    std::replace_if(
        problem.begin(), problem.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    throw InputError(path_.string() + ": " + problem);
  }
  const fs::path& path() const { return path_; }

 private:
  std::unique_lock<std::recursive_mutex> lock_;
  fs::path path_;
  bool capture_ = true;
};

std::string lower_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool is_openfoam(const fs::path& p) {
  std::error_code ec;
  return lower_extension(p) == ".foam" || fs::is_directory(p, ec);
}

void require_file(const Guard& g) {
  std::error_code ec;
  if (!fs::exists(g.path(), ec)) g.fail("no such file");
  if (!is_openfoam(g.path()) && !fs::is_regular_file(g.path(), ec)) g.fail("not a file");
  if (!is_openfoam(g.path()) && fs::file_size(g.path(), ec) == 0) g.fail("the file is empty");
}

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

// ------------------------------------------------------------ blocks and surfaces

struct Block {
  std::string name, path;
  vtkDataSet* data = nullptr;
};

void collect_blocks(vtkDataObject* obj, const std::string& name, const std::string& path,
                    std::vector<Block>& out) {
  if (!obj) return;
  if (auto* mb = vtkMultiBlockDataSet::SafeDownCast(obj)) {
    for (unsigned i = 0; i < mb->GetNumberOfBlocks(); ++i) {
      std::string child = "block" + std::to_string(i);
      if (mb->HasMetaData(i) && mb->GetMetaData(i)->Has(vtkCompositeDataSet::NAME()))
        child = mb->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
      collect_blocks(mb->GetBlock(i), child, path.empty() ? child : path + "/" + child, out);
    }
  } else if (auto* mp = vtkMultiPieceDataSet::SafeDownCast(obj)) {
    for (unsigned i = 0; i < mp->GetNumberOfPieces(); ++i)
      collect_blocks(mp->GetPieceAsDataObject(i), name, path, out);
  } else if (auto* pc = vtkPartitionedDataSetCollection::SafeDownCast(obj)) {
    for (unsigned i = 0; i < pc->GetNumberOfPartitionedDataSets(); ++i) {
      std::string child = "block" + std::to_string(i);
      if (pc->HasMetaData(i) && pc->GetMetaData(i)->Has(vtkCompositeDataSet::NAME()))
        child = pc->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
      collect_blocks(pc->GetPartitionedDataSet(i), child, path.empty() ? child : path + "/" + child,
                     out);
    }
  } else if (auto* pd = vtkPartitionedDataSet::SafeDownCast(obj)) {
    for (unsigned i = 0; i < pd->GetNumberOfPartitions(); ++i)
      collect_blocks(pd->GetPartitionAsDataObject(i), name, path, out);
  } else if (auto* ds = vtkDataSet::SafeDownCast(obj)) {
    out.push_back({name, path, ds});
  }
}

// Connectivity in range and points finite, before any filter touches them.
void check_cells(vtkCellArray* cells, vtkIdType points, const char* what, const Guard& g) {
  if (!cells || cells->GetNumberOfCells() == 0) return;
  vtkDataArray* conn = cells->GetConnectivityArray();
  vtkDataArray* offsets = cells->GetOffsetsArray();
  const vtkIdType n = conn->GetNumberOfTuples();
  const auto check_ids = [&](const auto* ids) {
    const auto bad = std::find_if(ids, ids + n, [&](auto id) { return id < 0 || id >= points; });
    if (bad != ids + n)
      g.fail(std::string(what) + ": a cell refers to point " +
             std::to_string(static_cast<long long>(*bad)) + " but there are only " +
             std::to_string(points));
  };
  if (cells->IsStorage64Bit())
    check_ids(cells->GetConnectivityArray64()->GetPointer(0));
  else
    check_ids(cells->GetConnectivityArray32()->GetPointer(0));
  double last = 0.0;
  for (vtkIdType i = 0; i < offsets->GetNumberOfTuples(); ++i) {
    const double o = offsets->GetComponent(i, 0);
    if (o < last || o > static_cast<double>(n)) g.fail(std::string(what) + ": malformed cell list");
    last = o;
  }
}

// Every cell of an unstructured grid has as many points as its type has
// (VTK's surface filter reads a cell's points by its type: a triangle of two
// points crashed it, which fuzzing found), and a type VTK knows.
void check_cell_types(vtkUnstructuredGrid* ug, const std::string& where, const Guard& g) {
  vtkCellArray* cells = ug->GetCells();
  vtkUnsignedCharArray* types = ug->GetCellTypesArray();
  if (!cells || cells->GetNumberOfCells() == 0) return;
  if (!types || types->GetNumberOfTuples() != cells->GetNumberOfCells())
    g.fail(where + ": " + std::to_string(cells->GetNumberOfCells()) + " cells but " +
           std::to_string(types ? types->GetNumberOfTuples() : 0) + " cell types");
  // Points of the fixed-size types; at least that many (negative) for the others.
  static const std::map<int, int> kPoints = {{VTK_EMPTY_CELL, 0},
                                             {VTK_VERTEX, 1},
                                             {VTK_POLY_VERTEX, -1},
                                             {VTK_LINE, 2},
                                             {VTK_POLY_LINE, -2},
                                             {VTK_TRIANGLE, 3},
                                             {VTK_TRIANGLE_STRIP, -3},
                                             {VTK_POLYGON, -3},
                                             {VTK_PIXEL, 4},
                                             {VTK_QUAD, 4},
                                             {VTK_TETRA, 4},
                                             {VTK_VOXEL, 8},
                                             {VTK_HEXAHEDRON, 8},
                                             {VTK_WEDGE, 6},
                                             {VTK_PYRAMID, 5},
                                             {VTK_PENTAGONAL_PRISM, 10},
                                             {VTK_HEXAGONAL_PRISM, 12},
                                             {VTK_QUADRATIC_EDGE, 3},
                                             {VTK_QUADRATIC_TRIANGLE, 6},
                                             {VTK_QUADRATIC_QUAD, 8},
                                             {VTK_QUADRATIC_POLYGON, -6},
                                             {VTK_QUADRATIC_TETRA, 10},
                                             {VTK_QUADRATIC_HEXAHEDRON, 20},
                                             {VTK_QUADRATIC_WEDGE, 15},
                                             {VTK_QUADRATIC_PYRAMID, 13},
                                             {VTK_BIQUADRATIC_QUAD, 9},
                                             {VTK_TRIQUADRATIC_HEXAHEDRON, 27},
                                             {VTK_TRIQUADRATIC_PYRAMID, 19},
                                             {VTK_QUADRATIC_LINEAR_QUAD, 6},
                                             {VTK_QUADRATIC_LINEAR_WEDGE, 12},
                                             {VTK_BIQUADRATIC_QUADRATIC_WEDGE, 18},
                                             {VTK_BIQUADRATIC_QUADRATIC_HEXAHEDRON, 24},
                                             {VTK_BIQUADRATIC_TRIANGLE, 7},
                                             {VTK_CUBIC_LINE, 4},
                                             {VTK_CONVEX_POINT_SET, -1},
                                             {VTK_POLYHEDRON, -4},
                                             {VTK_LAGRANGE_CURVE, -2},
                                             {VTK_LAGRANGE_TRIANGLE, -3},
                                             {VTK_LAGRANGE_QUADRILATERAL, -4},
                                             {VTK_LAGRANGE_TETRAHEDRON, -4},
                                             {VTK_LAGRANGE_HEXAHEDRON, -8},
                                             {VTK_LAGRANGE_WEDGE, -6},
                                             {VTK_LAGRANGE_PYRAMID, -5},
                                             {VTK_BEZIER_CURVE, -2},
                                             {VTK_BEZIER_TRIANGLE, -3},
                                             {VTK_BEZIER_QUADRILATERAL, -4},
                                             {VTK_BEZIER_TETRAHEDRON, -4},
                                             {VTK_BEZIER_HEXAHEDRON, -8},
                                             {VTK_BEZIER_WEDGE, -6},
                                             {VTK_BEZIER_PYRAMID, -5}};
  for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c) {
    const int type = types->GetValue(c);
    const auto it = kPoints.find(type);
    if (it == kPoints.end())
      g.fail(where + ": cell " + std::to_string(c) + " has an unknown cell type, " +
             std::to_string(type));
    const vtkIdType size = cells->GetCellSize(c);
    if (it->second >= 0 ? size != it->second : size < -it->second)
      g.fail(where + ": cell " + std::to_string(c) + " (" +
             vtkCellTypes::GetClassNameFromTypeId(type) + ") has " + std::to_string(size) +
             " points; it needs " + (it->second < 0 ? "at least " : "") +
             std::to_string(std::abs(it->second)));
  }
}

void check_dataset(vtkDataSet* ds, const Block& b, const Guard& g) {
  const vtkIdType n = ds->GetNumberOfPoints();
  const std::string where = b.path.empty() ? std::string("the data") : "block " + b.path;
  if (auto* ps = vtkPointSet::SafeDownCast(ds); ps && ps->GetPoints()) {
    double p[3];
    for (vtkIdType i = 0; i < n; ++i) {
      ps->GetPoints()->GetPoint(i, p);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        g.fail(where + ": point " + std::to_string(i) +
               " has a non-finite coordinate (NaN or infinity)");
    }
  }
  if (auto* pd = vtkPolyData::SafeDownCast(ds)) {
    check_cells(pd->GetVerts(), n, where.c_str(), g);
    check_cells(pd->GetLines(), n, where.c_str(), g);
    check_cells(pd->GetPolys(), n, where.c_str(), g);
    check_cells(pd->GetStrips(), n, where.c_str(), g);
  } else if (auto* ug = vtkUnstructuredGrid::SafeDownCast(ds)) {
    check_cells(ug->GetCells(), n, where.c_str(), g);
    check_cell_types(ug, where, g);
    if (vtkIdTypeArray* faces = ug->GetFaces())
      if (faces->GetNumberOfTuples() > 0) {
        // Polyhedra: [nfaces, (npts, ids...)...] per cell; ids in range.
        const vtkIdType m = faces->GetNumberOfTuples();
        for (vtkIdType i = 0; i < m;) {
          const vtkIdType nf = faces->GetValue(i++);
          for (vtkIdType f = 0; f < nf && i < m; ++f) {
            const vtkIdType np = faces->GetValue(i++);
            for (vtkIdType k = 0; k < np && i < m; ++k, ++i)
              if (faces->GetValue(i) < 0 || faces->GetValue(i) >= n)
                g.fail(where + ": a polyhedron face refers to a point out of range");
          }
        }
      }
  }
}

// Flat arrays: name -> (components, values tuple after tuple).
using Arrays = std::map<std::string, std::pair<int, std::vector<float>>>;

void take_arrays(vtkFieldData* data, vtkIdType tuples, Arrays& out) {
  if (!data) return;
  for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
    vtkDataArray* a = data->GetArray(i);
    if (!a || a->GetNumberOfTuples() != tuples) continue;
    std::string name = a->GetName() ? a->GetName() : "";
    if (name.empty()) name = "array" + std::to_string(i);
    if (name.rfind("vtk", 0) == 0) continue;  // vtkValidPointMask, vtkGhostType, ids
    const int c = a->GetNumberOfComponents();
    std::vector<float> values(static_cast<std::size_t>(tuples) * static_cast<std::size_t>(c));
    if (auto* f = vtkFloatArray::SafeDownCast(a)) {  // the common case: copy as it is
      std::copy_n(f->GetPointer(0), values.size(), values.begin());
      out[name] = {c, std::move(values)};
      continue;
    }
    std::vector<double> tuple(static_cast<std::size_t>(c));
    for (vtkIdType t = 0; t < tuples; ++t) {
      a->GetTuple(t, tuple.data());
      for (int k = 0; k < c; ++k)
        values[static_cast<std::size_t>(t) * static_cast<std::size_t>(c) +
               static_cast<std::size_t>(k)] =
            static_cast<float>(tuple[static_cast<std::size_t>(k)]);
    }
    out[name] = {c, std::move(values)};
  }
}

// One block's surface, triangulated: positions, triangles and both kinds of
// arrays (cell arrays per triangle).
struct Surface {
  std::vector<glm::vec3> positions;
  std::vector<Triangle> triangles;
  Arrays point_arrays, cell_arrays;
};

Surface block_surface(vtkDataSet* ds) {
  vtkSmartPointer<vtkPolyData> poly = vtkPolyData::SafeDownCast(ds);
  if (!poly) {
    vtkNew<vtkDataSetSurfaceFilter> surface;  // the outer surface of a volume
    surface->SetInputData(ds);
    surface->Update();
    poly = surface->GetOutput();
  }
  // Polygons and strips to triangles, lines and vertices dropped; a mesh of
  // triangles alone (most files) is taken as it is (the filter would copy
  // it: a second on six million triangles).
  vtkSmartPointer<vtkPolyData> tri = poly;
  if (poly->GetNumberOfStrips() > 0 || poly->GetPolys()->IsHomogeneous() != 3) {
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputData(poly);
    triangles->PassVertsOff();
    triangles->PassLinesOff();
    triangles->Update();
    tri = triangles->GetOutput();
  }
  Surface s;
  const vtkIdType n = tri->GetNumberOfPoints();
  s.positions.resize(static_cast<std::size_t>(n));
  double p[3];
  for (vtkIdType i = 0; i < n; ++i) {
    tri->GetPoint(i, p);
    s.positions[static_cast<std::size_t>(i)] = glm::vec3(p[0], p[1], p[2]);
  }
  vtkCellArray* polys = tri->GetPolys();
  s.triangles.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()));
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  std::vector<vtkIdType> kept;  // the cells that are triangles (all, from vtkTriangleFilter)
  vtkIdType cell = tri->GetNumberOfVerts() + tri->GetNumberOfLines();
  for (polys->InitTraversal(); polys->GetNextCell(count, ids); ++cell) {
    if (count != 3) continue;
    s.triangles.push_back({static_cast<std::uint32_t>(ids[0]), static_cast<std::uint32_t>(ids[1]),
                           static_cast<std::uint32_t>(ids[2])});
    kept.push_back(cell);
  }
  take_arrays(tri->GetPointData(), n, s.point_arrays);
  Arrays cells;
  take_arrays(tri->GetCellData(), tri->GetNumberOfCells(), cells);
  for (auto& [name, array] : cells) {
    const auto c = static_cast<std::size_t>(array.first);
    std::vector<float> per_triangle(kept.size() * c);
    for (std::size_t t = 0; t < kept.size(); ++t)
      std::copy_n(
          array.second.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(kept[t]) * c),
          c, per_triangle.begin() + static_cast<std::ptrdiff_t>(t * c));
    s.cell_arrays[name] = {array.first, std::move(per_triangle)};
  }
  return s;
}

// Every triangle with three vertices of its own, so that its cells' values
// stay its own (flat, as Surface colours cells) instead of being averaged at
// shared vertices: point arrays and smooth normals (of the welded surface)
// copied to each triangle's corners, `per_triangle` arrays (one tuple per
// triangle) to all three.
TriMesh cells_kept_apart(TriMesh& welded, const Arrays& per_triangle) {
  compute_vertex_normals(welded);
  TriMesh out;
  const std::size_t n = welded.triangles.size();
  const auto gather = [&](const auto& values) {
    std::remove_cvref_t<decltype(values)> v(3 * n);
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t k = 0; k < 3; ++k) v[3 * t + k] = values[welded.triangles[t][k]];
    return v;
  };
  out.positions = gather(welded.positions);
  out.normals = gather(welded.normals);
  for (const auto& [name, v] : welded.scalars) out.scalars[name] = gather(v);
  for (const auto& [name, v] : welded.vector_arrays) out.vector_arrays[name] = gather(v);
  out.other_arrays = welded.other_arrays;
  out.triangles.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto i = static_cast<std::uint32_t>(3 * t);
    out.triangles[t] = {i, i + 1, i + 2};
  }
  for (const auto& [name, a] : per_triangle) {
    const auto c = static_cast<std::size_t>(a.first);
    if (c == 1) {
      std::vector<float>& v = out.scalars[name];
      v.resize(3 * n);
      for (std::size_t t = 0; t < n; ++t) v[3 * t] = v[3 * t + 1] = v[3 * t + 2] = a.second[t];
    } else if (c == 3) {
      std::vector<glm::vec3>& v = out.vector_arrays[name];
      v.resize(3 * n);
      for (std::size_t t = 0; t < n; ++t)
        v[3 * t] = v[3 * t + 1] = v[3 * t + 2] =
            glm::vec3(a.second[3 * t], a.second[3 * t + 1], a.second[3 * t + 2]);
    } else {
      out.other_arrays[name] = a.first;
    }
  }
  return out;
}

// The blocks' surfaces as one mesh: points welded where blocks meet (the
// patches of an OpenFOAM case share their edges), arrays missing from a
// block NaN there, cell arrays carried to the vertices area-weighted.
TriMesh merge_surfaces(std::vector<Surface>& surfaces, const std::vector<std::string>& names,
                       std::vector<std::string>& warnings, const Guard& g, bool cells_apart) {
  TriMesh mesh;
  Arrays per_triangle;  // cells_apart: the cell arrays as they are
  const auto store = [&](const std::string& name, int c, std::vector<float> values, bool cell) {
    if (cell && cells_apart) {
      per_triangle[name] = {c, std::move(values)};
    } else if (c == 1) {
      mesh.scalars[name] = cell ? triangle_to_vertex(mesh, values) : std::move(values);
    } else if (c == 3) {
      std::vector<glm::vec3> v(values.size() / 3);
      for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
      mesh.vector_arrays[name] = cell ? triangle_to_vertex(mesh, v) : std::move(v);
    } else {
      mesh.other_arrays[name] = c;
    }
  };
  if (surfaces.size() == 1) {  // one block: its arrays as they are, no copy per value
    Surface& s = surfaces[0];
    mesh.positions = std::move(s.positions);
    mesh.triangles = std::move(s.triangles);
    for (auto& [name, a] : s.point_arrays) store(name, a.first, std::move(a.second), false);
    for (auto& [name, a] : s.cell_arrays)
      if (cells_apart || (!mesh.scalars.count(name) && !mesh.vector_arrays.count(name)))
        store(name, a.first, std::move(a.second), true);  // point data wins, unless apart
    return cells_apart ? cells_kept_apart(mesh, per_triangle) : mesh;
  }
  std::map<std::string, int> point_comps, cell_comps;
  for (const Surface& s : surfaces) {
    for (const auto& [name, a] : s.point_arrays) point_comps.emplace(name, a.first);
    for (const auto& [name, a] : s.cell_arrays) cell_comps.emplace(name, a.first);
  }
  // A block with an array as cell data where others have it as point data
  // (foamToVTK -one-boundary: the patches' cell data beside the volume's
  // point data) gets it at its vertices, area-weighted, rather than NaN.
  for (Surface& s : surfaces) {
    for (const auto& [name, c] : point_comps) {
      const auto cell = s.cell_arrays.find(name);
      if (s.point_arrays.count(name) || cell == s.cell_arrays.end() || cell->second.first != c)
        continue;
      TriMesh shape;
      shape.positions = s.positions;
      shape.triangles = s.triangles;
      const auto n = static_cast<std::size_t>(c);
      std::vector<float> at_vertices(s.positions.size() * n);
      for (std::size_t k = 0; k < n; ++k) {
        std::vector<float> component(s.triangles.size());
        for (std::size_t t = 0; t < component.size(); ++t)
          component[t] = cell->second.second[t * n + k];
        const std::vector<float> v = triangle_to_vertex(shape, component);
        for (std::size_t i = 0; i < v.size(); ++i) at_vertices[i * n + k] = v[i];
      }
      s.point_arrays[name] = {c, std::move(at_vertices)};
    }
  }
  Arrays points, cells;
  for (const auto& [name, c] : point_comps) points[name].first = c;
  for (const auto& [name, c] : cell_comps) cells[name].first = c;
  const bool weld = surfaces.size() > 1;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> by_position;
  const auto key = [](const glm::vec3& p) {
    std::uint32_t b[3];
    std::memcpy(b, &p, sizeof b);
    return (static_cast<std::uint64_t>(b[0]) * 0x9E3779B97F4A7C15ull) ^
           (static_cast<std::uint64_t>(b[1]) * 0xC2B2AE3D27D4EB4Full) ^ b[2];
  };
  for (std::size_t si = 0; si < surfaces.size(); ++si) {
    Surface& s = surfaces[si];
    std::vector<std::uint32_t> index(s.positions.size());
    for (std::size_t i = 0; i < s.positions.size(); ++i) {
      std::optional<std::uint32_t> same;
      if (weld)
        for (const std::uint32_t j : by_position[key(s.positions[i])])
          if (mesh.positions[j] == s.positions[i]) {
            same = j;
            break;
          }
      if (same) {
        index[i] = *same;
        continue;
      }
      index[i] = static_cast<std::uint32_t>(mesh.positions.size());
      if (weld) by_position[key(s.positions[i])].push_back(index[i]);
      mesh.positions.push_back(s.positions[i]);
      for (auto& [name, a] : points) {
        const auto c = static_cast<std::size_t>(a.first);
        const auto it = s.point_arrays.find(name);
        for (std::size_t k = 0; k < c; ++k)
          a.second.push_back(it != s.point_arrays.end() && it->second.first == a.first
                                 ? it->second.second[i * c + k]
                                 : std::nanf(""));
      }
    }
    for (const Triangle& t : s.triangles) {
      if (t[0] >= index.size() || t[1] >= index.size() || t[2] >= index.size())
        g.fail("a triangle refers to a point out of range");
      mesh.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
    }
    for (auto& [name, a] : cells) {
      const auto c = static_cast<std::size_t>(a.first);
      const auto it = s.cell_arrays.find(name);
      for (std::size_t t = 0; t < s.triangles.size(); ++t)
        for (std::size_t k = 0; k < c; ++k)
          a.second.push_back(it != s.cell_arrays.end() && it->second.first == a.first
                                 ? it->second.second[t * c + k]
                                 : std::nanf(""));
    }
    for (const auto& [name, c] : point_comps)
      if (!s.point_arrays.count(name) && surfaces.size() > 1)
        warnings.push_back(g.path().string() + ": block " + names[si] + " has no point array '" +
                           name + "' (NaN there)");
    s = Surface{};  // free as we go
  }
  // A face that two blocks share, once: the first block's (a boundary
  // patch's, before a volume's outer surface).
  std::set<std::array<std::uint32_t, 3>> seen;
  std::vector<bool> keep(mesh.triangles.size(), true);
  std::size_t repeated = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<std::uint32_t, 3> k = mesh.triangles[t];
    std::sort(k.begin(), k.end());
    if (!seen.insert(k).second) {
      keep[t] = false;
      ++repeated;
    }
  }
  if (repeated > 0) {
    std::size_t out = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      if (keep[t]) mesh.triangles[out++] = mesh.triangles[t];
    mesh.triangles.resize(out);
    for (auto& [name, a] : cells) {
      const auto c = static_cast<std::size_t>(a.first);
      std::size_t o = 0;
      for (std::size_t t = 0; t < keep.size(); ++t)
        if (keep[t])
          for (std::size_t k = 0; k < c; ++k) a.second[o++] = a.second[t * c + k];
      a.second.resize(o);
    }
  }
  const std::size_t n = mesh.positions.size();
  for (auto& [name, a] : points) {
    if (a.second.size() != n * static_cast<std::size_t>(a.first)) continue;
    store(name, a.first, std::move(a.second), false);
  }
  for (auto& [name, a] : cells) {
    if (!cells_apart && (mesh.scalars.count(name) || mesh.vector_arrays.count(name)))
      continue;  // point data wins, unless apart
    store(name, a.first, std::move(a.second), true);
  }
  return cells_apart ? cells_kept_apart(mesh, per_triangle) : mesh;
}

// Surfaces of the selected blocks of a data object, merged into one mesh.
TriMesh surface_of(vtkDataObject* obj, const std::vector<std::string>& patterns,
                   std::vector<std::string>* block_names, std::vector<std::string>& warnings,
                   const Guard& g, bool patterns_applied, bool cells_apart = false) {
  std::vector<Block> blocks;
  collect_blocks(obj, "", "", blocks);
  std::vector<Block> chosen;
  if (patterns.empty() || patterns_applied) {
    chosen = blocks;
  } else {
    std::vector<bool> used(patterns.size(), false);
    for (const Block& b : blocks) {
      bool on = false;
      for (std::size_t k = 0; k < patterns.size(); ++k)
        if (glob_match(patterns[k], b.name) || glob_match(patterns[k], b.path)) on = used[k] = true;
      if (on) chosen.push_back(b);
    }
    for (std::size_t k = 0; k < patterns.size(); ++k)
      if (!used[k]) {
        std::string known;
        for (const Block& b : blocks) known += (known.empty() ? "" : ", ") + b.path;
        if (blocks.size() == 1 && blocks[0].path.empty())
          g.fail("has no blocks to choose from (blocks '" + patterns[k] + "')");
        g.fail("no block matches '" + patterns[k] +
               "' (blocks: " + (known.empty() ? "none" : known) + ")");
      }
  }
  // Surfaces before volumes: where a volume's outer surface and a boundary
  // block coincide (foamToVTK writes both, internal.vtu and the patches),
  // the boundary's faces and arrays are the ones kept (merge_surfaces).
  std::stable_partition(chosen.begin(), chosen.end(), [](const Block& b) {
    return vtkPolyData::SafeDownCast(b.data) != nullptr;
  });
  std::vector<Surface> surfaces;
  std::vector<std::string> names;
  vtkIdType cells = 0, points = 0;
  for (const Block& b : chosen) {
    check_dataset(b.data, b, g);
    cells += b.data->GetNumberOfCells();
    points += b.data->GetNumberOfPoints();
    Surface s = block_surface(b.data);
    g.check();
    if (s.triangles.empty()) continue;
    surfaces.push_back(std::move(s));
    names.push_back(b.path.empty() ? "(the data)" : b.path);
  }
  if (surfaces.empty())
    g.fail("has no surface to show (" + std::to_string(points) + " points, " +
           std::to_string(cells) + (cells == 1 ? " cell" : " cells") +
           ", none of them a polygon, strip or volume cell" +
           (blocks.empty() ? std::string(", no data set at all") : std::string()) + ")");
  if (block_names) *block_names = names;
  TriMesh mesh = merge_surfaces(surfaces, names, warnings, g, cells_apart);
  return mesh;
}

// A mesh for ibfvs: degenerate triangles dropped, normals, checked.
void finish(TriMesh& mesh, std::vector<std::string>& warnings, const Guard& g) {
  const std::size_t dropped = remove_degenerate_triangles(mesh);
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
// (core/isolation.h), so VTK's own parser is the only one, and nothing here
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

// Step k's surface (the first: with its blocks and what was repaired).
void read_step_bytes(const DatasetRequest& request, std::size_t k, std::size_t vertices_of_first,
                     ByteWriter& out) {
  const Guard g(request.path);
  const Source source = open_source(request, g);
  std::vector<std::string> blocks, warnings;
  TriMesh mesh = surface_of(source.read_step(k, g), request.blocks, &blocks, warnings, g,
                            source.patterns_applied);
  if (k == 0) {
    finish(mesh, warnings, g);
  } else {
    remove_degenerate_triangles(mesh);
    if (mesh.vertex_count() != vertices_of_first)
      g.fail("step " + std::to_string(k) + " has " + std::to_string(mesh.vertex_count()) +
             " vertices, the first step " + std::to_string(vertices_of_first) +
             " (a changing mesh is not supported)");
  }
  put_mesh(out, mesh);
  out.put(blocks);
  out.put(warnings);
  out.put(source.times);
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
  const IsolatedBytes bytes =
      read_in_child(request.path, [&](ByteWriter& out) { read_step_bytes(request, 0, 0, out); });
  ByteReader in(bytes.view(), subject);
  Dataset d;
  d.mesh = get_mesh(in);
  d.blocks = in.get_strings();
  d.warnings = in.get_strings();
  std::vector<double> times = in.get_vector<double>();
  validate_mesh(d.mesh, subject);
  if (times.size() > 1) {
    d.times = std::move(times);
    d.step = [request, vertices = d.mesh.vertex_count()](std::size_t k) {
      const IsolatedBytes step_bytes = read_in_child(
          request.path, [&](ByteWriter& out) { read_step_bytes(request, k, vertices, out); });
      ByteReader step_in(step_bytes.view(), request.path.string());
      TriMesh mesh = get_mesh(step_in);
      if (mesh.vertex_count() != vertices)
        throw InputError(request.path.string() + ": step " + std::to_string(k) +
                         " changed its vertex count");
      return mesh;
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

TriMesh surface_mesh(vtkDataObject* data, const std::string& name, bool cells_apart) {
  if (!data) throw InputError(name + ": no data");
  const Guard g(name, false);
  std::vector<std::string> warnings;
  return surface_of(data, {}, nullptr, warnings, g, true, cells_apart);
}

void install_vtk_io() {
  {
    const std::lock_guard lock(vtk_mutex());
    capture_window();
  }
  install_dataset_io({read, sample, write_polydata});
}

}  // namespace ibfvs::vtk
