// VTK's messages caught, the lock every VTK call takes, and the file
// helpers the readers share (src/vtk/internal.h).
#include "internal.h"

#include <algorithm>
#include <cctype>
#include <mutex>
#include <string>
#include <vector>

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/isolation.h"

namespace ibfvs::vtk::detail {
namespace fs = std::filesystem;

// VTK reports problems through its output window (standard error by
// default) and carries on with an empty output. All our VTK calls run under
// one lock with this window installed, so that each read can turn the first
// error into the one line the user sees.

std::recursive_mutex*& vtk_mutex_slot() {
  static auto* m = new std::recursive_mutex;
  return m;
}

std::recursive_mutex& vtk_mutex() {
  return *vtk_mutex_slot();
}

namespace {

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

}  // namespace

void install_messages() {
  const std::lock_guard lock(vtk_mutex());
  capture_window();
}

Guard::Guard(fs::path path, bool capture) : path_(std::move(path)), capture_(capture) {
  if (!capture_) return;
  lock_ = std::unique_lock<std::recursive_mutex>(vtk_mutex());
  capture_window()->errors.clear();
  capture_window()->warnings.clear();
}

void Guard::check() const {
  if (!capture_) return;
  const auto& errors = capture_window()->errors;
  if (!errors.empty()) fail(errors.front());
  // The legacy reader only warns when data runs short ("Error reading
  // ascii data. Possible mismatch of datasize with declaration.").
  for (const std::string& w : capture_window()->warnings)
    if (w.find("rror") != std::string::npos) fail(w);
}

void Guard::fail(std::string problem) const {
  // One line, whatever VTK or the file put into it.
  std::replace_if(
      problem.begin(), problem.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  throw InputError(path_.string() + ": " + problem);
}

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

}  // namespace ibfvs::vtk::detail
