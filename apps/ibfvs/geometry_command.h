#pragma once
// `ibfvs geometry`: the preprocessing of paper section 5 on its own: normals,
// curvature and principal directions, Loop subdivision, written to PLY.

#include <string>

namespace CLI {
class App;
}

namespace ibfvs::app {

struct GeometryOptions {
  std::string mesh;   ///< input mesh (required)
  int subdivide = 0;  ///< Loop subdivision levels
  std::string out;    ///< output PLY; empty: only the summary
  bool ascii = false;
  std::string fit =
      "auto";  ///< --curvature-fit: auto, quartic or cubic  ///< ASCII instead of binary PLY
  bool quiet = false;
};

void add_geometry_options(CLI::App& command, GeometryOptions& options);

/// Runs the command; returns the exit status. Throws InputError naming the
/// file or option.
int run_geometry(const GeometryOptions& options);

}  // namespace ibfvs::app
