#include "ibfvs/vtk/vtk_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <iomanip>
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
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProbeFilter.h>
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
#include <vtkXMLPolyDataWriter.h>

#include "ibfvs/core/error.h"
#include "ibfvs/core/file_names.h"
#include "ibfvs/core/text.h"

namespace ibfvs::vtk {
namespace fs = std::filesystem;

namespace {

// ------------------------------------------------------------ VTK's messages
// VTK reports problems through its output window (standard error by
// default) and carries on with an empty output. All our VTK calls run under
// one lock with this window installed, so that each read can turn the first
// error into the one line the user sees.

std::recursive_mutex& vtk_mutex() {
  static std::recursive_mutex m;
  return m;
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
  void DisplayErrorText(const char* text) override { errors.push_back(clean_message(text)); }
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

// ------------------------------------------------------------ counts before reading
// VTK's readers allocate what a header declares before reading the data, and
// abort the process when that fails (POINTS 400000000000). So the counts are
// checked first against what the file could hold.

// A count as a header gives it; fails on a negative or unreadable one.
long double header_count(const std::string& word, const std::string& where, const Guard& g) {
  if (!word.empty() && word[0] == '-') g.fail(where + ": negative count " + word);
  try {
    std::size_t used = 0;
    const long double v = std::stold(word, &used);
    if (used != word.size() || !std::isfinite(static_cast<double>(v)) || v < 0) throw 0;
    return v;
  } catch (...) {
    g.fail(where + ": " + excerpt(word) + " is not a count");
  }
}

// A count for a message, whatever its size (a header may say 1e299).
std::string count_text(long double v) {
  if (v < 1e18L) return std::to_string(static_cast<long long>(v));
  char text[32];
  std::snprintf(text, sizeof text, "%.3Lg", v);
  return text;
}

void check_values(long double values, long double capacity, const std::string& where,
                  const Guard& g) {
  if (values > capacity)
    g.fail(where + " declares " + count_text(values) + " values, more than the file can hold (" +
           count_text(capacity) + ")");
}

// The keyword VTK's legacy readers take a word for: they compare its
// beginning, in any case, with each keyword ("FIELDS" is FIELD, "POINTSx"
// POINTS). Another word comes back in capitals.
std::string legacy_keyword(const std::string& word) {
  static const std::vector<std::string> kKeywords = {"TEXTURE_COORDINATES",
                                                     "TRIANGLE_STRIPS",
                                                     "COLOR_SCALARS",
                                                     "X_COORDINATES",
                                                     "Y_COORDINATES",
                                                     "Z_COORDINATES",
                                                     "LOOKUP_TABLE",
                                                     "CONNECTIVITY",
                                                     "ASPECT_RATIO",
                                                     "PEDIGREE_IDS",
                                                     "POINT_DATA",
                                                     "CELL_TYPES",
                                                     "DIMENSIONS",
                                                     "GLOBAL_IDS",
                                                     "EDGE_FLAGS",
                                                     "CELL_DATA",
                                                     "TENSORS6",
                                                     "VERTICES",
                                                     "POLYGONS",
                                                     "METADATA",
                                                     "SCALARS",
                                                     "VECTORS",
                                                     "NORMALS",
                                                     "TENSORS",
                                                     "OFFSETS",
                                                     "DATASET",
                                                     "SPACING",
                                                     "POINTS",
                                                     "ORIGIN",
                                                     "FIELD",
                                                     "CELLS",
                                                     "LINES"};
  std::string upper = word;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  for (const std::string& k : kKeywords)
    if (upper.compare(0, k.size(), k) == 0) return k;
  return upper;
}

// Legacy files: every count is at most the file's size in values (a value
// takes at least a byte in binary, two characters in ASCII).
void precheck_legacy(const Guard& g) {
  std::error_code ec;
  const auto size = static_cast<long double>(fs::file_size(g.path(), ec));
  std::ifstream in(g.path(), std::ios::binary);
  std::string line;
  long double tuples = 0;  // of the current POINT_DATA / CELL_DATA section
  long double field_arrays = 0;
  int cells_line = 0;  // CELLS without CELL_TYPES: VTK 9.2 dereferences null
  bool cell_types = false;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    key = legacy_keyword(key);
    const std::string where = "line " + std::to_string(number) + " (" + one_line(key) + ")";
    std::vector<std::string> rest;
    for (std::string w; words >> w && rest.size() < 4;) rest.push_back(w);
    const auto count = [&](std::size_t i) {
      if (i >= rest.size()) g.fail(where + ": a count is missing");
      return header_count(rest[i], where, g);
    };
    // A FIELD's array: NAME COMPONENTS TUPLES TYPE. Only a line of exactly
    // that form counts (binary data or "nan" values may start with a letter).
    const auto digits = [](const std::string& w) {
      return !w.empty() && w.size() < 19 &&
             std::all_of(w.begin(), w.end(), [](unsigned char c) { return std::isdigit(c); });
    };
    static const std::set<std::string, std::less<>> kTypes = {
        "bit",          "unsigned_char", "char",        "signed_char",   "unsigned_short",
        "short",        "unsigned_int",  "int",         "unsigned_long", "long",
        "vtktypeint64", "vtktypeuint64", "float",       "double",        "vtkIdType",
        "vtkidtype",    "string",        "utf8_string", "variant"};
    if (field_arrays > 0 && rest.size() == 3 && digits(rest[0]) && digits(rest[1]) &&
        kTypes.count(rest[2])) {
      --field_arrays;
      check_values(header_count(rest[0], where, g) * header_count(rest[1], where, g), size, where,
                   g);
      continue;
    }
    if (key == "CELLS" && cells_line == 0) cells_line = number;
    if (key == "POINTS") {
      check_values(3 * count(0), size, where, g);
    } else if (key == "POLYGONS" || key == "LINES" || key == "VERTICES" ||
               key == "TRIANGLE_STRIPS" || key == "CELLS") {
      check_values(count(0) + count(1), size + 2, where, g);
    } else if (key == "CELL_TYPES") {
      cell_types = true;
      check_values(count(0), size, where, g);
    } else if (key == "POINT_DATA" || key == "CELL_DATA") {
      tuples = count(0);
      check_values(tuples, size, where, g);
    } else if (key == "SCALARS") {
      check_values(tuples * (rest.size() > 2 ? count(2) : 1), size, where, g);
    } else if (key == "VECTORS" || key == "NORMALS") {
      check_values(3 * tuples, size, where, g);
    } else if (key == "TENSORS") {
      check_values(9 * tuples, size, where, g);
    } else if (key == "TEXTURE_COORDINATES" || key == "COLOR_SCALARS") {
      check_values(tuples * count(1), size, where, g);
    } else if (key == "FIELD") {
      field_arrays = count(1);
      check_values(field_arrays, size, where, g);
    } else if (key == "DIMENSIONS") {
      // Structured data: the points are implied; their surface must fit.
      const long double nx = count(0), ny = count(1), nz = count(2);
      if (nx * ny * nz > 2147483647.0L || 2 * (nx * ny + ny * nz + nx * nz) > 268435456.0L)
        g.fail(where + ": a grid of " + rest[0] + " x " + rest[1] + " x " + rest[2] +
               " points is too large to show");
    }
  }
  if (cells_line > 0 && !cell_types)
    g.fail("line " + std::to_string(cells_line) +
           " (CELLS): an unstructured grid's cells need CELL_TYPES");
}

// Base64 (as VTK's XML files encode binary data): the bytes of `text`
// from its start, up to `bytes` of them; whitespace is skipped.
std::string decode_base64(std::string_view text, std::size_t bytes) {
  static const std::string kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned bits = 0;
  int count = 0;
  for (const char c : text) {
    if (out.size() >= bytes || c == '=' || c == '<') break;
    const std::size_t v = kAlphabet.find(c);
    if (v == std::string::npos) continue;
    bits = (bits << 6) | static_cast<unsigned>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xFF);
    }
  }
  return out;
}

// The attributes of an XML start tag (from its '<' to its '>') as an XML
// parser reads them: whitespace around '=', either quote, the five named
// entities and numeric ones decoded (as bytes below 256; enough to compare).
std::map<std::string, std::string> xml_attributes(std::string_view tag) {
  std::map<std::string, std::string> out;
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  std::size_t i = tag.find_first_of(" \t\n\r");
  while (i < tag.size()) {
    while (i < tag.size() && space(tag[i])) ++i;
    const std::size_t name_begin = i;
    while (i < tag.size() && !space(tag[i]) && tag[i] != '=' && tag[i] != '>' && tag[i] != '/') ++i;
    const std::string name(tag.substr(name_begin, i - name_begin));
    while (i < tag.size() && space(tag[i])) ++i;
    if (name.empty() || i >= tag.size() || tag[i] != '=') break;
    ++i;
    while (i < tag.size() && space(tag[i])) ++i;
    if (i >= tag.size() || (tag[i] != '"' && tag[i] != '\'')) break;
    const std::size_t end = tag.find(tag[i], i + 1);
    if (end == std::string_view::npos) break;
    std::string value;
    for (std::size_t k = i + 1; k < end; ++k) {
      const std::size_t semi = tag.find(';', k);
      if (tag[k] != '&' || semi == std::string_view::npos || semi > end) {
        value += tag[k];
        continue;
      }
      const std::string_view entity = tag.substr(k + 1, semi - k - 1);
      static const std::map<std::string_view, char> kNamed = {
          {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
      if (const auto it = kNamed.find(entity); it != kNamed.end()) {
        value += it->second;
      } else if (entity.size() > 1 && entity[0] == '#') {
        const bool hex = entity[1] == 'x';
        value += static_cast<char>(
            std::strtol(std::string(entity.substr(hex ? 2 : 1)).c_str(), nullptr, hex ? 16 : 10));
      } else {
        value += '&';
        continue;
      }
      k = semi;
    }
    out[name] = value;
    i = end + 1;
  }
  return out;
}

// One attribute of an XML start tag, read as xml_attributes reads them.
std::optional<std::string> xml_attribute(std::string_view tag, std::string_view name) {
  const auto attributes = xml_attributes(tag);
  const auto it = attributes.find(std::string(name));
  if (it == attributes.end()) return std::nullopt;
  return it->second;
}

// One piece's CellData or PointData with two arrays of one name: VTK 9.2's
// XML readers crash on a second cell array of a name (fuzzing found it), and
// a name given to --field must pick one array.
void check_xml_array_names(const Guard& g, const std::string& head) {
  for (const std::string section : {"CellData", "PointData"}) {
    for (std::size_t at = head.find("<" + section); at != std::string::npos;
         at = head.find("<" + section, at + 1)) {
      const std::size_t tag_end = head.find('>', at);
      if (tag_end == std::string::npos) break;
      if (head[tag_end - 1] == '/') continue;  // <CellData/>
      const std::size_t end = std::min(head.find("</" + section, tag_end), head.size());
      std::set<std::string> names;
      for (std::size_t a = head.find("<DataArray", tag_end); a < end;
           a = head.find("<DataArray", a + 1)) {
        const std::size_t close = head.find('>', a);
        if (close == std::string::npos) break;
        const auto attributes = xml_attributes(std::string_view(head).substr(a, close - a + 1));
        const auto name = attributes.find("Name");
        const std::string text = name == attributes.end() ? "" : name->second;
        if (!names.insert(text).second)
          g.fail("the " + section + " of a piece has two arrays named " + excerpt(text));
      }
    }
  }
}

// XML files' binary data (inline base64, appended raw or base64): the header
// VTK reads before each array (its byte count; for compressed data its block
// count and sizes), and the last cell offset, by which VTK 9.2 sizes the
// connectivity. VTK allocates what these say before reading: fuzzing found
// 12 GB asked for by a 6 KB file (a block count) and an abort (an offset
// of 2^61). Compressed offsets are left to VTK.
void precheck_xml_data(const Guard& g, const std::string& head, long double capacity) {
  const std::size_t file_at = head.find("<VTKFile");
  if (file_at == std::string::npos) return;
  const std::string_view file_tag =
      std::string_view(head).substr(file_at, head.find('>', file_at) - file_at);
  const std::size_t word = xml_attribute(file_tag, "header_type") == "UInt64" ? 8 : 4;
  const bool big_endian = xml_attribute(file_tag, "byte_order") == "BigEndian";
  const bool compressed = !xml_attribute(file_tag, "compressor").value_or("").empty();
  std::error_code ec;
  const std::uint64_t size = fs::file_size(g.path(), ec);
  std::ifstream in(g.path(), std::ios::binary);
  // The appended data start after the "_" that follows <AppendedData ...>;
  // `head` ends where that element's line begins.
  std::uint64_t appended = 0;
  bool appended_base64 = false;
  {
    std::string tail(4096, '\0');
    in.seekg(static_cast<std::streamoff>(head.size()));
    in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
    tail.resize(static_cast<std::size_t>(in.gcount()));
    in.clear();
    const std::size_t at = tail.find("<AppendedData");
    const std::size_t close = at == std::string::npos ? at : tail.find('>', at);
    const std::size_t underscore = close == std::string::npos ? close : tail.find('_', close);
    if (underscore != std::string::npos) {
      appended = head.size() + underscore + 1;
      appended_base64 =
          xml_attribute(std::string_view(tail).substr(at, close - at), "encoding") != "raw";
    }
  }
  // `bytes` bytes of an array's binary data from `offset` in its encoding
  // (base64 text encodes the header and the data separately).
  const auto read_appended = [&](std::uint64_t pos, std::uint64_t offset, std::size_t bytes) {
    std::string out;
    if (!appended_base64) {
      if (pos + offset + bytes > size) return out;
      out.resize(bytes);
      in.seekg(static_cast<std::streamoff>(pos + offset));
      in.read(out.data(), static_cast<std::streamsize>(bytes));
      if (!in) out.clear();
      in.clear();
      return out;
    }
    std::string text(4 * (bytes / 3 + 2), '\0');
    in.seekg(static_cast<std::streamoff>(pos + offset / 3 * 4));
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    in.clear();
    out = decode_base64(text, offset % 3 + bytes);
    return out.size() == offset % 3 + bytes ? out.substr(offset % 3) : std::string();
  };
  const auto number = [&](const std::string& bytes, std::size_t at, std::size_t n) {
    std::uint64_t v = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const auto b = static_cast<unsigned char>(bytes[big_endian ? at + k : at + n - 1 - k]);
      v = (v << 8) | b;
    }
    return v;
  };
  static const std::map<std::string, std::size_t, std::less<>> kTypeBytes = {
      {"Int8", 1},   {"UInt8", 1}, {"Int16", 2},  {"UInt16", 2},  {"Int32", 4},
      {"UInt32", 4}, {"Int64", 8}, {"UInt64", 8}, {"Float32", 4}, {"Float64", 8}};
  for (std::size_t at = head.find("<DataArray"); at != std::string::npos;
       at = head.find("<DataArray", at + 1)) {
    const std::size_t close = head.find('>', at);
    if (close == std::string::npos) break;
    const std::string_view tag = std::string_view(head).substr(at, close - at);
    const std::string format = xml_attribute(tag, "format").value_or("ascii");
    const std::string name = excerpt(xml_attribute(tag, "Name").value_or(""));
    if (format == "ascii") continue;
    // Where the array's header is, and how many bytes could follow it.
    const bool inline_data = format == "binary";
    std::uint64_t pos = 0, available = 0;
    std::string_view text;
    if (inline_data) {
      text = std::string_view(head).substr(close + 1);
      text = text.substr(0, text.find('<'));
      available = text.size() / 4 * 3;
    } else {
      const auto offset = xml_attribute(tag, "offset");
      if (!offset || appended == 0) continue;  // VTK reports it
      const long double o = header_count(*offset, "DataArray " + name + " offset", g);
      if (o > static_cast<long double>(size - appended))
        g.fail("DataArray " + name + ": its offset " + *offset + " is past the end of the file");
      pos = appended + static_cast<std::uint64_t>(o);
      available = appended_base64 ? (size - pos) / 4 * 3 : size - pos;
    }
    const std::size_t header_words = compressed ? 3 : 1;
    const auto read = [&](std::uint64_t offset, std::size_t bytes) {
      return inline_data ? decode_base64(text, offset + bytes)
                               .substr(std::min<std::size_t>(
                                   offset, decode_base64(text, offset + bytes).size()))
                         : read_appended(pos, offset, bytes);
    };
    const std::string header = read(0, header_words * word);
    if (header.size() < header_words * word)
      g.fail("DataArray " + name + ": its binary data are cut short");
    if (compressed) {
      const long double blocks = static_cast<long double>(number(header, 0, word));
      const long double block = static_cast<long double>(number(header, word, word));
      const long double last = static_cast<long double>(number(header, 2 * word, word));
      if ((3 + blocks) * word > available)
        g.fail("DataArray " + name + ": its compressed data declare " + count_text(blocks) +
               " blocks, more than the file holds");
      // VTK reads past its block table when these disagree (an empty table
      // with a partial last block, a last block larger than a block).
      if ((blocks == 0 && last != 0) || last > block || (blocks > 0 && block == 0))
        g.fail("DataArray " + name + ": its compressed data's header is inconsistent (" +
               count_text(blocks) + " blocks of " + count_text(block) + " bytes, the last " +
               count_text(last) + ")");
      const long double total = blocks > 0 ? (blocks - 1) * block + (last > 0 ? last : block) : 0;
      check_values(total, capacity, "DataArray " + name + " (uncompressed bytes)", g);
      continue;
    }
    const std::uint64_t bytes = number(header, 0, word);
    if (bytes > available)
      g.fail("DataArray " + name + ": its data declare " +
             count_text(static_cast<long double>(bytes)) + " bytes, more than the file holds");
    // The last cell offset: the connectivity's length, which VTK allocates.
    const auto type = kTypeBytes.find(xml_attribute(tag, "type").value_or(""));
    if (xml_attribute(tag, "Name") != "offsets" || type == kTypeBytes.end() || bytes == 0 ||
        bytes % type->second != 0)
      continue;
    // Uncompressed, the data follow the header in one stream (raw or base64).
    const std::uint64_t data_at = word;
    const std::string value = read(data_at + bytes - type->second, type->second);
    if (value.size() != type->second) g.fail("DataArray " + name + ": its data are cut short");
    std::uint64_t last = number(value, 0, type->second);
    const bool is_signed = xml_attribute(tag, "type").value_or("").rfind("Int", 0) == 0;
    if (is_signed && type->second < 8 && (last >> (8 * type->second - 1)) != 0) last = UINT64_MAX;
    if (last > size)
      g.fail("DataArray " + name + ": its last offset, " +
             (last == UINT64_MAX || (is_signed && (last >> 63) != 0)
                  ? std::string("a negative number")
                  : std::to_string(last)) +
             ", is more connectivity than the file holds");
  }
}

// XML files: the counts in the attributes (NumberOfPoints, NumberOfCells,
// NumberOfTuples..., extents) at most what the file could hold compressed
// (zlib's best ratio is about 1000:1).
void precheck_xml(const Guard& g) {
  std::error_code ec;
  const auto size = static_cast<long double>(fs::file_size(g.path(), ec));
  const long double capacity = 1100.0L * size + 1e6L;
  std::ifstream in(g.path(), std::ios::binary);
  std::string head;
  // The XML part: the whole file, up to appended binary data.
  for (std::string line; std::getline(in, line);) {
    if (line.find("<AppendedData") != std::string::npos) break;
    head += line;
    head += '\n';
    if (head.size() > (std::size_t{64} << 20)) break;
  }
  for (std::size_t at = head.find("Number"); at != std::string::npos;
       at = head.find("Number", at + 1)) {
    const std::size_t eq = head.find("=\"", at);
    if (eq == std::string::npos || eq - at > 32) continue;
    const std::string name = head.substr(at, eq - at);
    if (name.find_first_of(" <>/") != std::string::npos) continue;
    const std::size_t end = head.find('"', eq + 2);
    if (end == std::string::npos) break;
    const std::string value = head.substr(eq + 2, end - eq - 2);
    if (name == "NumberOfComponents") {
      check_values(header_count(value, name, g), 1e6L, name, g);
      continue;
    }
    check_values(header_count(value, name, g), capacity, name, g);
  }
  precheck_xml_data(g, head, capacity);
  check_xml_array_names(g, head);
  for (const char* attribute : {"WholeExtent=\"", " Extent=\""}) {
    for (std::size_t at = head.find(attribute); at != std::string::npos;
         at = head.find(attribute, at + 1)) {
      const std::size_t begin = at + std::strlen(attribute);
      std::istringstream words(head.substr(begin, head.find('"', begin) - begin));
      long double points = 1;
      for (int axis = 0; axis < 3; ++axis) {
        long long lo = 0, hi = 0;
        if (!(words >> lo >> hi) || hi < lo) g.fail("a malformed extent");
        points *= static_cast<long double>(hi - lo + 1);
      }
      check_values(points, capacity, "an extent", g);
    }
  }
}

// The number types of legacy files (VTK reads them in any case) and their
// sizes in BINARY files; points must have one of them.
const std::map<std::string, int, std::less<>> kLegacyTypeBytes = {
    {"unsigned_char", 1}, {"char", 1},         {"signed_char", 1},   {"unsigned_short", 2},
    {"short", 2},         {"unsigned_int", 4}, {"int", 4},           {"unsigned_long", 8},
    {"long", 8},          {"vtktypeint64", 8}, {"vtktypeuint64", 8}, {"float", 4},
    {"double", 8},        {"vtkidtype", 4}};

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// Whether VTK's legacy readers take `word` for `keyword` (lower case): they
// compare its beginning, in any case.
bool is_keyword(const std::string& word, std::string_view keyword) {
  return lower(word).compare(0, keyword.size(), keyword) == 0;
}

// Whether a legacy file stores cells as OFFSETS and CONNECTIVITY (version 5
// and later), by VTK's rule: "# vtk DataFile Version M.N" with both numbers
// read, or else version 0 (cell records).
bool stores_offsets(const std::string& first_line) {
  constexpr std::string_view kPrefix = "# vtk DataFile Version";
  int major = 0, minor = 0;
  if (first_line.compare(0, kPrefix.size(), kPrefix) != 0 ||
      std::sscanf(first_line.c_str() + kPrefix.size(), "%d.%d", &major, &minor) != 2)
    return false;
  return major >= 5;
}

// ASCII legacy files: every section's values are there, as many as its
// header declares, before the next keyword. VTK 9.2's legacy readers crash
// (a null cell array) on a section cut short, which fuzzing found.
void precheck_legacy_ascii(const Guard& g) {
  std::ifstream in(g.path(), std::ios::binary);
  std::string line;
  std::vector<std::string> head;
  for (int k = 0; k < 3 && std::getline(in, line); ++k) head.push_back(line);
  const auto trimmed = [](std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
  };
  // VTK's rule: the third line's first word begins with "ascii", in any case.
  if (head.size() < 3 || lower(trimmed(head[2])).rfind("ascii", 0) != 0) return;
  const bool v5 = stores_offsets(head[0]);
  const auto numeric = [](const std::string& w) {
    char* end = nullptr;
    std::strtod(w.c_str(), &end);
    return end && end != w.c_str() && *end == '\0';
  };
  long double pending = 0, tuples = 0, field_arrays = 0;
  long double cells_left = -1, record_left = 0;  // the cell list being read, if any
  std::string section;
  int section_line = 0;
  std::deque<std::pair<std::string, long double>> next;  // keyword, then its values
  bool metadata = false;
  int number = 3;
  const auto expect = [&](const std::string& key, long double values, int at) {
    pending = values;
    section = key;
    section_line = at;
  };
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string t; words >> t;) w.push_back(t);
    if (metadata) {  // METADATA ... up to a blank line
      metadata = !w.empty();
      continue;
    }
    std::size_t i = 0;
    for (; i < w.size() && pending > 0; ++i, --pending) {
      if (!numeric(w[i]))
        g.fail("line " + std::to_string(number) + ": " + excerpt(w[i]) + " where the " + section +
               " of line " + std::to_string(section_line) + " has " + count_text(pending) +
               " values to go");
      if (cells_left < 0) continue;  // not a cell list
      // A cell list before version 5: records "n i1 ... in", `cells` of them,
      // filling the declared size exactly (VTK reads past its array otherwise).
      const long double v = std::stold(w[i]);
      if (record_left == 0) {
        if (cells_left == 0 || v < 0 || v + 1 > pending)
          g.fail("line " + std::to_string(number) + ": the " + section + " of line " +
                 std::to_string(section_line) + " does not add up to its declared size");
        record_left = v;
        --cells_left;
      } else {
        --record_left;
      }
    }
    if (pending == 0 && cells_left > 0)
      g.fail("the " + section + " of line " + std::to_string(section_line) + " declares " +
             count_text(cells_left) + " more cells than it holds");
    if (pending == 0) cells_left = -1;
    if (i > 0 || w.empty()) continue;
    const std::string key = legacy_keyword(w[0]);
    const auto count = [&](std::size_t k) -> long double {
      return k < w.size() && numeric(w[k]) ? std::stold(w[k]) : 0.0L;
    };
    if (!next.empty()) {
      if (key != next.front().first)
        g.fail("line " + std::to_string(number) + ": expected " + next.front().first + ", got " +
               excerpt(w[0]));
      expect(key, next.front().second, number);
      next.pop_front();
      continue;
    }
    if (field_arrays > 0 && w.size() == 4 && numeric(w[1]) && numeric(w[2])) {
      --field_arrays;
      const std::string type = w[3];
      if (type != "string" && type != "utf8_string" && type != "variant")
        expect("array " + excerpt(w[0]), count(1) * count(2), number);
      continue;
    }
    if (key == "POINTS") {
      if (w.size() < 3 || !kLegacyTypeBytes.count(lower(w[2])))
        g.fail("line " + std::to_string(number) + " (POINTS): points of type " +
               excerpt(w.size() < 3 ? "" : w[2]) + " (float, double or an integer type)");
      expect(key, 3 * count(1), number);
    } else if (key == "POLYGONS" || key == "LINES" || key == "VERTICES" ||
               key == "TRIANGLE_STRIPS" || key == "CELLS") {
      if (v5) {
        next.emplace_back("OFFSETS", count(1));
        next.emplace_back("CONNECTIVITY", count(2));
      } else {
        expect(key, count(2), number);
        cells_left = count(1);
        record_left = 0;
      }
    } else if (key == "CELL_TYPES") {
      expect(key, count(1), number);
    } else if (key == "POINT_DATA" || key == "CELL_DATA") {
      tuples = count(1);
    } else if (key == "SCALARS") {
      next.emplace_back("LOOKUP_TABLE", tuples * (w.size() > 3 ? count(3) : 1));
    } else if (key == "VECTORS" || key == "NORMALS") {
      expect(key, 3 * tuples, number);
    } else if (key == "TENSORS") {
      expect(key, 9 * tuples, number);
    } else if (key == "TEXTURE_COORDINATES") {
      expect(key, count(2) * tuples, number);
    } else if (key == "COLOR_SCALARS") {
      expect(key, count(2) * tuples, number);
    } else if (key == "LOOKUP_TABLE") {
      expect(key, 4 * count(2), number);
    } else if (key == "X_COORDINATES" || key == "Y_COORDINATES" || key == "Z_COORDINATES") {
      expect(key, count(1), number);
    } else if (key == "FIELD") {
      // FIELD NAME ARRAYS: VTK 9.2 crashes on a FIELD it cannot read.
      if (w.size() < 3 || !numeric(w[2]))
        g.fail("line " + std::to_string(number) + " (FIELD): " +
               (w.size() < 3 ? std::string("no array count") : excerpt(w[2]) + " is not a count"));
      field_arrays = count(2);
    } else if (key == "METADATA") {
      metadata = true;
    }
  }
  if (pending > 0)
    g.fail("truncated: the " + section + " of line " + std::to_string(section_line) + " has " +
           count_text(pending) + " values missing");
  if (!next.empty()) g.fail("truncated: " + next.front().first + " is missing");
}

// BINARY legacy files: the mesh sections walked word by word as VTK reads
// them (keywords matched by their beginning, in any case; a binary block
// after the rest of its header line), each block skipped by its size. VTK
// 9.2 crashes where a pre-5 cell list's records ("n i1 ... in", big-endian
// ints) do not fill its declared size, on points of a type that is no
// number, and on an unstructured grid with CELL_TYPES but no CELLS, all
// found by fuzzing; a word that is no section of a polydata or unstructured
// grid means a block before it was cut short or overran. METADATA is taken
// where VTK takes it: right after an array's data. The data attributes are
// left to precheck_legacy's counts and to VTK.
void precheck_legacy_binary(const Guard& g) {
  std::ifstream in(g.path(), std::ios::binary);
  std::error_code ec;
  const auto size = static_cast<long double>(fs::file_size(g.path(), ec));
  std::string first, title;
  if (!std::getline(in, first) || !std::getline(in, title)) return;
  int number = 3;  // the line being read, for messages
  const auto word = [&] {
    while (std::isspace(in.peek())) {
      if (in.get() == '\n') ++number;
    }
    std::string w;
    while (w.size() < 255 && in.peek() != std::char_traits<char>::eof() && !std::isspace(in.peek()))
      w += static_cast<char>(in.get());
    return w;
  };
  if (!is_keyword(word(), "binary") || !is_keyword(word(), "dataset")) return;
  const std::string dataset = lower(word());
  const bool poly = is_keyword(dataset, "polydata"),
             grid = is_keyword(dataset, "unstructured_grid");
  if (!poly && !grid) return;  // other datasets: left to VTK
  const std::string kind = poly ? "POLYDATA" : "UNSTRUCTURED_GRID";
  const bool v5 = stores_offsets(first);
  const auto count = [&](const std::string& what) {
    return header_count(word(), "line " + std::to_string(number) + " (" + what + ")", g);
  };
  // The rest of the header line; the binary block follows it.
  const auto end_line = [&] {
    std::string rest;
    std::getline(in, rest);
    ++number;
  };
  // After an array's data VTK skips spaces and line ends, and reads a
  // METADATA section if the next line begins with that word, up to a blank
  // line; fuzzing found VTK 9.2 crashing (a null cell array) after a
  // section that began so but was no such section. VTK writes "METADATA"
  // alone on its line, then lines of text.
  const auto array_end = [&] {
    for (int c = in.peek(); c == ' ' || c == '\n'; c = in.peek())
      if (in.get() == '\n') ++number;
    const auto at = in.tellg();
    std::string head(8, '\0');
    if (!in.read(head.data(), 8)) {
      in.clear();
      in.seekg(at);
      return;
    }
    in.seekg(at);
    if (lower(head) != "metadata") return;
    const auto text = [](std::string line) {
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      return line;
    };
    std::string line;
    std::getline(in, line);
    if (lower(text(line)) != "metadata")
      g.fail("line " + std::to_string(number) + ": " + excerpt(line) +
             " is not a METADATA line (METADATA alone)");
    ++number;
    while (std::getline(in, line)) {
      ++number;
      line = text(line);
      if (line.empty()) break;
      for (const char c : line)
        if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
          g.fail("line " + std::to_string(number) + ": METADATA with a control character");
    }
  };
  // Skips `values` values of `type`, then any METADATA after them; false
  // for a type this walk does not size.
  const auto skip = [&](long double values, const std::string& type, const std::string& what) {
    const auto it = kLegacyTypeBytes.find(lower(type));
    if (it == kLegacyTypeBytes.end()) return false;
    const int line = number;
    end_line();
    const long double bytes = values * it->second;
    const auto at = static_cast<long double>(in.tellg());
    if (in.tellg() < 0 || bytes > size - at)
      g.fail("truncated: the " + what + " of line " + std::to_string(line) + " needs " +
             count_text(bytes) + " bytes, " + count_text(in.tellg() < 0 ? 0 : size - at) +
             " are left");
    in.seekg(static_cast<std::streamoff>(bytes), std::ios::cur);
    array_end();
    return true;
  };
  bool cell_lists = false, types = false;
  for (std::string w = word(); !w.empty(); w = word()) {
    const std::string where = "line " + std::to_string(number) + " (" + one_line(w) + ")";
    if (is_keyword(w, "point_data") || is_keyword(w, "cell_data")) break;
    if (is_keyword(w, "field")) {
      word();  // its name
      const long double arrays = count("FIELD");
      for (long double a = 0; a < arrays; ++a) {
        word();  // the array's name
        const long double components = count("FIELD array");
        const long double tuples = count("FIELD array");
        if (!skip(components * tuples, word(), "array")) return;
      }
    } else if (is_keyword(w, "points")) {
      const long double points = count("POINTS");
      const std::string type = word();
      // VTK 9.2 reads points of another type as none, and then crashes.
      if (kLegacyTypeBytes.count(lower(type)) == 0)
        g.fail(where + ": points of type " + excerpt(type) + " (float, double or an integer type)");
      skip(3 * points, type, "POINTS");
    } else if (grid && is_keyword(w, "cell_types")) {
      types = true;
      skip(count("CELL_TYPES"), "int", "CELL_TYPES");
    } else if ((poly && (is_keyword(w, "vertices") || is_keyword(w, "lines") ||
                         is_keyword(w, "polygons") || is_keyword(w, "triangle_strips"))) ||
               (grid && is_keyword(w, "cells"))) {
      cell_lists = true;
      const long double cells = count(w), values = count(w);
      if (v5) {
        // OFFSETS TYPE, its block; CONNECTIVITY TYPE, its block.
        if (!is_keyword(word(), "offsets") || !skip(cells, word(), "OFFSETS")) return;
        if (!is_keyword(word(), "connectivity") || !skip(values, word(), "CONNECTIVITY")) return;
        continue;
      }
      end_line();
      const auto at = static_cast<long double>(in.tellg());
      if (in.tellg() < 0 || 4 * values > size - at)
        g.fail("truncated: the " + where + " needs " + count_text(4 * values) + " bytes, " +
               count_text(in.tellg() < 0 ? 0 : size - at) + " are left");
      std::vector<unsigned char> bytes(static_cast<std::size_t>(4 * values));
      in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
      const auto value = [&](std::size_t i) {
        const unsigned char* b = bytes.data() + 4 * i;
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(b[0]) << 24 |
                                         static_cast<std::uint32_t>(b[1]) << 16 |
                                         static_cast<std::uint32_t>(b[2]) << 8 | b[3]);
      };
      const auto n = static_cast<std::size_t>(values);
      std::size_t i = 0;
      for (long double c = 0; c < cells; ++c) {
        const std::int32_t points = i < n ? value(i) : -1;
        if (points < 0 || static_cast<std::size_t>(points) >= n - i)
          g.fail(where + ": cell " + count_text(c) + " does not fit the list's declared size");
        i += 1 + static_cast<std::size_t>(points);
      }
      if (i != n) g.fail(where + ": the cells do not add up to the list's declared size");
    } else {
      // What VTK would take for a keyword: a block before was cut short or
      // overran.
      g.fail("line " + std::to_string(number) + ": " + excerpt(w) + " is not a section of " + kind +
             " (is the section before it cut short?)");
    }
  }
  if (grid && cell_lists != types)
    g.fail(std::string("an unstructured grid with ") +
           (types ? "CELL_TYPES but no CELLS" : "CELLS but no CELL_TYPES"));
}

// Legacy structured grids: VTK 9.2's vtkStructuredGridReader, looking for
// the dimensions before it reads, takes every word of the file in turn,
// binary data included, and reads a FIELD section wherever a word begins
// with "field" (any case); where that section cannot be read, it
// dereferences null. Fuzzing found it on "FieldD" inside binary points. So
// each such word must begin a FIELD section that VTK reads whole: a name, a
// count of arrays, and each array's name, components, tuples, number type
// and values (in BINARY, after the rest of that line).
void precheck_structured_grid(const Guard& g) {
  std::ifstream in(g.path(), std::ios::binary);
  std::error_code ec;
  const auto size = static_cast<long double>(fs::file_size(g.path(), ec));
  std::string first, title, type_line;
  if (!std::getline(in, first) || !std::getline(in, title) || !std::getline(in, type_line)) return;
  const auto word = [&in] {
    std::string w;
    in >> std::setw(255) >> w;  // as VTK's ReadString
    return w;
  };
  if (!is_keyword(word(), "dataset") || !is_keyword(word(), "structured_grid")) return;
  const bool binary = is_keyword(type_line, "binary");
  const auto fail = [&](const std::string& what) {
    // The line where the scan is, for the message.
    const auto at = in.tellg() < 0 ? std::streamoff(size) : std::streamoff(in.tellg());
    std::ifstream again(g.path(), std::ios::binary);
    long line = 1;
    for (std::streamoff i = 0; i < at && again; ++i)
      if (again.get() == '\n') ++line;
    g.fail("line " + std::to_string(line) + ": " + what +
           " (VTK 9.2's structured grid reader would crash on it)");
  };
  const auto number = [](const std::string& w) {
    return !w.empty() && w.find_first_not_of("0123456789+-.eE") == std::string::npos &&
           w.find_first_of("0123456789") != std::string::npos;
  };
  const auto count = [&](const std::string& w, const std::string& what) {
    if (w.empty() || w.find_first_not_of("0123456789") != std::string::npos || w.size() > 12)
      fail("a FIELD section whose " + what + " is " + excerpt(w) + ", not a count");
    return std::stold(w);
  };
  for (std::string w = word(); !w.empty(); w = word()) {
    if (!is_keyword(w, "field")) continue;
    word();  // the section's name
    const long double arrays = count(word(), "count of arrays");
    for (long double a = 0; a < arrays; ++a) {
      const std::string name = word();
      if (name == "NULL_ARRAY") continue;
      const long double values = count(word(), "array " + excerpt(name) + "'s components") *
                                 count(word(), "array " + excerpt(name) + "'s tuples");
      const std::string type = word();
      const auto it = kLegacyTypeBytes.find(lower(type));
      if (it == kLegacyTypeBytes.end())
        fail("a FIELD array " + excerpt(name) + " of type " + excerpt(type) +
             ", which is no number type");
      if (binary) {
        std::string rest;
        std::getline(in, rest);
        const long double bytes = values * it->second;
        const auto at = in.tellg();
        if (at < 0 || bytes > size - static_cast<long double>(at))
          fail("a FIELD array " + excerpt(name) + " cut short (" + count_text(bytes) +
               " bytes declared)");
        in.seekg(static_cast<std::streamoff>(bytes), std::ios::cur);
      } else {
        if (values > size / 2) fail("a FIELD array " + excerpt(name) + " cut short");
        for (long double v = 0; v < values; ++v)
          if (!number(word()))
            fail("a FIELD array " + excerpt(name) + " cut short or with a value that is no number");
      }
    }
  }
}

// A single VTK file (legacy or XML, any dataset kind).
vtkSmartPointer<vtkDataObject> read_vtk_file(const Guard& g) {
  require_file(g);
  if (lower_extension(g.path()) == ".vtk") {
    precheck_legacy(g);
    precheck_legacy_ascii(g);
    precheck_legacy_binary(g);
    precheck_structured_grid(g);
  } else {
    precheck_xml(g);
  }
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
    vtkNew<vtkXMLGenericDataObjectReader> reader;
    reader->SetFileName(g.path().string().c_str());
    reader->Update();
    g.check();
    out = reader->GetOutput();
  }
  if (!out) g.fail("VTK could not read it (not a VTK file?)");
  return out;
}

// ------------------------------------------------------------ .pvd series

struct PvdEntry {
  double time = 0.0;
  fs::path file;
};

// The steps of a .pvd collection: for each distinct time, its files (parts).
std::vector<std::pair<double, std::vector<fs::path>>> read_pvd(const Guard& g) {
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
  std::vector<PvdEntry> entries;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = collection->GetNestedElement(i);
    if (std::strcmp(e->GetName(), "DataSet") != 0) continue;
    const char* file = e->GetAttribute("file");
    if (!file || !*file) g.fail("a <DataSet> without a file attribute");
    PvdEntry entry;
    if (const char* t = e->GetAttribute("timestep")) {
      try {
        entry.time = parse_number(t);
      } catch (const InputError&) {
        g.fail(std::string("timestep '") + t + "' is not a number");
      }
    }
    entry.file = fs::path(file).is_absolute() ? fs::path(file) : g.path().parent_path() / file;
    entries.push_back(entry);
  }
  if (entries.empty()) g.fail("the collection lists no data sets");
  std::stable_sort(entries.begin(), entries.end(),
                   [](const PvdEntry& a, const PvdEntry& b) { return a.time < b.time; });
  std::vector<std::pair<double, std::vector<fs::path>>> steps;
  for (const PvdEntry& e : entries) {
    if (steps.empty() || steps.back().first != e.time) steps.push_back({e.time, {}});
    steps.back().second.push_back(e.file);
  }
  return steps;
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

// The blocks' surfaces as one mesh: points welded where blocks meet (the
// patches of an OpenFOAM case share their edges), arrays missing from a
// block NaN there, cell arrays carried to the vertices area-weighted.
TriMesh merge_surfaces(std::vector<Surface>& surfaces, const std::vector<std::string>& names,
                       std::vector<std::string>& warnings, const Guard& g) {
  TriMesh mesh;
  const auto store = [&](const std::string& name, int c, std::vector<float> values, bool cell) {
    if (c == 1) {
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
      if (!mesh.scalars.count(name) && !mesh.vector_arrays.count(name))  // point data wins
        store(name, a.first, std::move(a.second), true);
    return mesh;
  }
  std::map<std::string, int> point_comps, cell_comps;
  for (const Surface& s : surfaces) {
    for (const auto& [name, a] : s.point_arrays) point_comps.emplace(name, a.first);
    for (const auto& [name, a] : s.cell_arrays) cell_comps.emplace(name, a.first);
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
  const std::size_t n = mesh.positions.size();
  for (auto& [name, a] : points) {
    if (a.second.size() != n * static_cast<std::size_t>(a.first)) continue;
    store(name, a.first, std::move(a.second), false);
  }
  for (auto& [name, a] : cells) {
    if (mesh.scalars.count(name) || mesh.vector_arrays.count(name)) continue;  // point data wins
    store(name, a.first, std::move(a.second), true);
  }
  return mesh;
}

// Surfaces of the selected blocks of a data object, merged into one mesh.
TriMesh surface_of(vtkDataObject* obj, const std::vector<std::string>& patterns,
                   std::vector<std::string>* block_names, std::vector<std::string>& warnings,
                   const Guard& g, bool patterns_applied) {
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
  TriMesh mesh = merge_surfaces(surfaces, names, warnings, g);
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

// What one step of a dataset reads as a surface.
using StepReader = std::function<vtkSmartPointer<vtkDataObject>(std::size_t, const Guard&)>;

Dataset read_steps(const DatasetRequest& request, std::vector<double> times, StepReader reader,
                   bool patterns_applied) {
  Dataset d;
  {
    const Guard g(request.path);
    vtkSmartPointer<vtkDataObject> first = reader(0, g);
    d.mesh = surface_of(first, request.blocks, &d.blocks, d.warnings, g, patterns_applied);
    finish(d.mesh, d.warnings, g);
  }
  if (times.size() > 1) {
    d.times = std::move(times);
    const std::size_t vertices = d.mesh.vertex_count();
    d.step = [request, reader, patterns_applied, vertices](std::size_t k) {
      const Guard g(request.path);
      std::vector<std::string> ignored;
      TriMesh mesh =
          surface_of(reader(k, g), request.blocks, nullptr, ignored, g, patterns_applied);
      remove_degenerate_triangles(mesh);
      if (mesh.vertex_count() != vertices)
        g.fail("step " + std::to_string(k) + " has " + std::to_string(mesh.vertex_count()) +
               " vertices, the first step " + std::to_string(vertices) +
               " (a changing mesh is not supported)");
      return mesh;
    };
  }
  return d;
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

// ------------------------------------------------------------ volumes for sampling

struct CachedVolume {
  std::string key;
  vtkSmartPointer<vtkDataSet> data;
};

vtkSmartPointer<vtkDataSet> read_volume(const fs::path& path, std::size_t step, const Guard& g) {
  static CachedVolume cache;
  std::error_code ec;
  const auto stamp = fs::last_write_time(path, ec).time_since_epoch().count();
  const std::string key = path.string() + "|" + std::to_string(step) + "|" + std::to_string(stamp);
  if (cache.key == key && cache.data) return cache.data;
  vtkSmartPointer<vtkDataObject> obj;
  if (is_openfoam(path)) {
    if (!fs::exists(path, ec)) g.fail("no such file");
    auto reader = openfoam_reader(g, true, {});
    obj = read_openfoam_step(reader, openfoam_times(reader), step, g);
  } else if (lower_extension(path) == ".pvd") {
    const auto steps = read_pvd(g);
    if (step >= steps.size())
      g.fail("has " + std::to_string(steps.size()) + " time steps, asked for step " +
             std::to_string(step));
    vtkNew<vtkMultiBlockDataSet> all;
    unsigned i = 0;
    for (const fs::path& file : steps[step].second) {
      const Guard part(file);
      all->SetBlock(i++, read_vtk_file(part));
    }
    obj = all;
  } else {
    if (step > 0) g.fail("is one file, one time step; asked for step " + std::to_string(step));
    obj = read_vtk_file(g);
  }
  std::vector<Block> blocks;
  collect_blocks(obj, "", "", blocks);
  if (blocks.empty()) g.fail("holds no data set");
  vtkSmartPointer<vtkDataSet> volume;
  for (const Block& b : blocks) check_dataset(b.data, b, g);
  if (blocks.size() == 1) {
    volume = blocks[0].data;
  } else {
    vtkNew<vtkAppendFilter> append;
    for (const Block& b : blocks) append->AddInputData(b.data);
    append->Update();
    g.check();
    volume = append->GetOutput();
  }
  cache = {key, volume};
  return volume;
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

}  // namespace

// ------------------------------------------------------------ public

std::string vtk_version() {
  return vtkVersion::GetVTKVersionFull();
}

Dataset read(const DatasetRequest& request) {
  return guarded(request.path, [&] {
    const fs::path& path = request.path;
    if (is_openfoam(path)) {
      const Guard g(path);
      require_file(g);
      vtkSmartPointer<vtkOpenFOAMReader> reader = openfoam_reader(g, false, request.blocks);
      const std::vector<double> times = openfoam_times(reader);
      return read_steps(
          request, times,
          [reader, times](std::size_t k, const Guard& guard) {
            return read_openfoam_step(reader, times, k, guard);
          },
          true);
    }
    if (lower_extension(path) == ".pvd") {
      std::vector<std::pair<double, std::vector<fs::path>>> steps;
      {
        const Guard g(path);
        steps = read_pvd(g);
      }
      std::vector<double> times;
      for (const auto& s : steps) times.push_back(s.first);
      return read_steps(
          request, times,
          [steps](std::size_t k, const Guard& guard) -> vtkSmartPointer<vtkDataObject> {
            try {
              if (steps[k].second.size() == 1) {
                const Guard part(steps[k].second[0]);
                return read_vtk_file(part);
              }
              vtkNew<vtkMultiBlockDataSet> parts;  // parts of one time: blocks named by file
              unsigned i = 0;
              for (const fs::path& file : steps[k].second) {
                const Guard part(file);
                parts->SetBlock(i, read_vtk_file(part));
                parts->GetMetaData(i++)->Set(vtkCompositeDataSet::NAME(),
                                             file.stem().string().c_str());
              }
              return parts;
            } catch (const InputError& e) {
              guard.fail(e.what());  // the collection's name first, then the part's
            }
          },
          false);
    }
    return read_steps(
        request, {}, [](std::size_t, const Guard& guard) { return read_vtk_file(guard); }, false);
  });
}

VolumeSample sample(const fs::path& path, const std::string& array, std::size_t step,
                    const std::vector<glm::vec3>& points) {
  return guarded(path, [&] {
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
  });
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

TriMesh surface_mesh(vtkDataObject* data, const std::string& name) {
  if (!data) throw InputError(name + ": no data");
  const Guard g(name, false);
  std::vector<std::string> warnings;
  return surface_of(data, {}, nullptr, warnings, g, true);
}

void install_vtk_io() {
  {
    const std::lock_guard lock(vtk_mutex());
    capture_window();
  }
  install_dataset_io({read, sample, write_polydata});
}

}  // namespace ibfvs::vtk
