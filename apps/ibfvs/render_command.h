#pragma once
// `ibfvs render`: headless IBFVS rendering to PNG or video.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/camera.h"
#include "ibfvs/core/mesh.h"
#include "ibfvs/core/vector_field.h"
#include "ibfvs/render/ibfvs_renderer.h"

namespace CLI {
class App;
}

namespace ibfvs::app {

/// The options of `ibfvs render`, as typed (validated by run_render).
struct RenderOptions {
  std::string mesh;   ///< empty: the built-in demo
  std::string field;  ///< empty: see the --field help
  std::vector<std::string>
      elements;  ///< potential-flow elements, AX,AY,AZ,BX,BY,BZ,ROT,RAD,TAN[,CORE]
  std::string tangent = "project";
  std::string size = "512x512";
  std::int64_t frames = 150;  // wide, so that a huge value gets our range message
  std::string out;            ///< empty: <mesh stem>.mp4 (ibfvs-demo.mp4 for the demo)
  std::string texture_out;
  float alpha = 0.1f;
  float beta = 0.5f;
  float scale = 4.0f;
  std::string profile = "square";
  float vg = 0.02f;
  float spike_width = 0.1f;
  std::uint32_t seed = 1;
  float step = 3.0f;             ///< pixels per frame (ignored when dt > 0)
  float dt = 0.0f;               ///< world units per frame; 0: from --step
  bool image_normalize = false;  ///< every vector moves `step` pixels (paper figure 2)
  std::string inject = "blend";
  std::string background = "0.5,0.5,0.5";
  std::string surface_color = "0.82,0.80,0.76";
  std::string color_by;  ///< per-vertex scalar that colours the surface
  std::string color_map = "viridis";
  std::string color_range;            ///< "LO,HI"; empty: 1st to 99th percentile
  std::string beta_by;                ///< per-vertex scalar that modulates beta
  std::string beta_range;             ///< "LO,HI"; empty: 1st to 99th percentile
  std::vector<std::string> scalars;   ///< NAME=FILE:VAR, sampled from netCDF grids
  std::string displace;               ///< NAME:FACTOR, move vertices along their normals
  std::string surface_image;          ///< PNG mapped by longitude/latitude as the surface colour
  std::string init = "background";    ///< F_t at the start: background or random-cells
  int lock_at = -1;                   ///< lock the texture after this frame (-1: never)
  std::string lock_camera;            ///< AZ,EL,DIST: the camera once locked
  std::string style;                  ///< applied in main as default options (styles.h)
  std::string default_field;          ///< the field when none is given and the mesh has none
  std::string export_model;           ///< OBJ + MTL, glTF or GLB, + PNG of the final texture (3.7)
  std::string noise_space = "image";  ///< image (the paper) or object (3D lattice on the surface)
  std::string time = "0";             ///< time index of netCDF data, from 0, or a range A:B
  std::vector<std::string>
      field_steps;           ///< PLY files whose vx vy vz are the steps of an unsteady field
  int frames_per_step = 30;  ///< frames from one time step to the next
  std::string camera;        ///< "AZ,EL,DIST"
  std::string look_at;       ///< "X,Y,Z" offset of the look-at point from the box centre
  bool ortho = false;
  float fov = 30.0f;
  float orbit = 0.0f;
  std::string advect_view = "previous";
  int subdivide = 0;
  double fps = 30.0;
  bool quiet = false;
};

/// Registers the render subcommand's options on `command`, bound to `options`.
void add_render_options(CLI::App& command, RenderOptions& options);

/// What a run needs before a GL context exists: the checked settings, the
/// prepared mesh (subdivided, scalars, curvature, displacement), the field,
/// the colour and beta scalars with their ranges, the camera and dt. Shared by
/// `ibfvs render` and `ibfvs view`.
struct PreparedScene {
  int width = 512, height = 512;  ///< image size in pixels
  int frames = 150;
  RenderSettings settings;
  std::shared_ptr<TriMesh> mesh;
  std::string mesh_name;  ///< what messages call it
  bool demo = false;      ///< no --mesh: the built-in demo
  FieldSpec field_spec;
  std::vector<glm::vec3> field;  ///< the field (at the first time step)
  std::size_t step_count = 1;    ///< > 1: an unsteady field with this many steps
  std::function<std::vector<glm::vec3>(std::size_t)> step_field;  ///< the field at a step
  std::vector<float> color_scalar, beta_scalar;
  CameraParams camera;
  std::optional<CameraParams> lock_camera;
  float dt = 0.0f;      ///< world units per frame
  float max_px = 0.0f;  ///< pixels per frame of the fastest vertex
};

/// Checks the options and prepares the scene (no GL). Prints warnings to
/// stderr. Throws InputError naming the option or file.
PreparedScene prepare_scene(const RenderOptions& options);

/// Uploads the prepared mesh, field, scalars and surface image to `renderer`
/// and initialises F_t (--init).
void load_scene(IbfvsRenderer& renderer, const PreparedScene& scene, const RenderOptions& options);

/// Plays an unsteady field: the current and next steps on the GPU and the mix
/// between them. Does nothing for a steady field.
class FieldPlayer {
 public:
  FieldPlayer(const PreparedScene& scene, IbfvsRenderer& renderer);
  /// Time t in steps (looping); evaluates a step only when t leaves the current one.
  void seek(double t, IbfvsRenderer& renderer);

 private:
  const PreparedScene& scene_;
  std::size_t step_ = 0;
  std::vector<glm::vec3> field_, next_;
};

/// Renders; returns the exit status. Throws InputError / GraphicsError with a
/// message naming the file or option.
int run_render(const RenderOptions& options);

}  // namespace ibfvs::app
