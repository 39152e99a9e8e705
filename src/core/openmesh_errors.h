#pragma once
// Internal to the core: OpenMesh's error stream, captured.

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <OpenMesh/Core/System/omstream.hh>

namespace ibfvs {

// OpenMesh reports problems on its global omerr stream and then carries on with
// what it could read. Capture those lines for the duration of one read, so they
// can be classified (fatal: an index out of range; repairable: a face with
// repeated vertices) instead of being lost on stderr.
class OmErrCapture {
 public:
  OmErrCapture() {
    omerr().disconnect(std::cerr);
    omerr().connect(buffer_);
  }
  ~OmErrCapture() {
    omerr().flush();
    omerr().disconnect(buffer_);
    omerr().connect(std::cerr);
  }
  OmErrCapture(const OmErrCapture&) = delete;
  OmErrCapture& operator=(const OmErrCapture&) = delete;
  std::vector<std::string> lines() {
    omerr().flush();
    std::vector<std::string> out;
    std::istringstream in(buffer_.str());
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) out.push_back(line);
    return out;
  }

 private:
  std::ostringstream buffer_;
};

}  // namespace ibfvs
