#include "ibfvs/styles.h"

#include "ibfvs/core/error.h"

namespace ibfvs::app {

const char* style_names() {
  return "flow, particles, principal, bronze, eroded, topology";
}

std::vector<std::string> style_arguments(const std::string& name) {
  // flow (figures 1, 5): dense moving texture, beta 0.5, grey background.
  if (name == "flow") return {"--beta", "0.5", "--background", "0.5,0.5,0.5"};
  // particles (figure 8a): short spikes so that few grid values are bright,
  // added rather than blended, along kappa_min where the mesh has no field.
  if (name == "particles")
    return {"--profile",       "spike",
            "--spike-width",   "0.04",
            "--inject",        "add",
            "--alpha",         "0.08",
            "--background",    "0.05,0.05,0.08",
            "--beta",          "0.7",
            "--default-field", "principal:min:smooth=10"};
  // principal (figure 8b): dense texture along the principal directions,
  // signed along +Y (section 4.2's sign rule), smoothed over about three
  // edges so that scanned meshes give coherent strokes.
  if (name == "principal")
    return {"--default-field", "principal:min:0,1,0:smooth=10", "--beta", "0.6"};
  // bronze (figure 9): "a dirty surface has superficially been cleaned":
  // colour by kappa_max (patina in the hollows, metal on the ridges) and the
  // texture (the dirt) only in the more concave half (-kappa_max from its
  // median to its 98th percentile), so the rest shows clean metal.
  if (name == "bronze") {
    return {"--default-field", "principal:min:smooth=10",
            "--color-by",      "kmax",
            "--color-map",     "bronze",
            "--color-range",   "p5,p95",
            "--beta-by",       "-kmax",
            "--beta-range",    "p50,p98",
            "--beta",          "0.7"};
  }
  // eroded stone (section 4.2): the same, parametrised by kappa_min.
  if (name == "eroded") {
    return {"--default-field", "principal:max:smooth=10",
            "--color-by",      "kmin",
            "--color-map",     "grey",
            "--color-range",   "p5,p95",
            "--beta-by",       "-kmin",
            "--beta-range",    "p50,p98",
            "--beta",          "0.7"};
  }
  // topology (figure 7): alpha 0, random colours per noise cell, flow
  // downhill; after 40 frames each pixel holds its summit's colour; then the
  // texture is locked and the camera moves to an oblique view.
  if (name == "topology")
    return {"--alpha",         "0",
            "--init",          "random-cells",
            "--default-field", "gradient:down:normalize",
            "--camera",        "0,90,0",
            "--lock-at",       "40",
            "--lock-camera",   "20,35,0",
            "--frames",        "100",
            "--beta",          "0.85",
            "--scale",         "6"};
  throw InputError("--style: unknown style '" + name + "' (expected " + style_names() + ")");
}

}  // namespace ibfvs::app
