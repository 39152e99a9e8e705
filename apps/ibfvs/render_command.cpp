#include "ibfvs/render_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <utility>

#include <CLI/CLI.hpp>
#include <glm/trigonometric.hpp>

#include "ibfvs/core/camera.h"
#include "ibfvs/core/colormap.h"
#include "ibfvs/core/curvature.h"
#include "ibfvs/core/displacement.h"
#include "ibfvs/core/error.h"
#include "ibfvs/core/file_names.h"
#include "ibfvs/core/gpu_prep.h"
#include "ibfvs/core/image.h"
#include "ibfvs/core/lonlat_grid.h"
#include "ibfvs/core/mesh_io.h"
#include "ibfvs/core/procedural.h"
#include "ibfvs/core/subdivision.h"
#include "ibfvs/core/vector_field.h"
#include "ibfvs/data_paths.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/mesh_loading.h"
#include "ibfvs/progress.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "ibfvs/video_writer.h"

namespace ibfvs::app {
namespace fs = std::filesystem;

void add_render_options(CLI::App& cmd, RenderOptions& o) {
  // A scene's value comes first on the command line; the user's, later, wins.
  cmd.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  cmd.add_option("--mesh", o.mesh,
                 "Triangle mesh: .off .obj .ply .stl (PLY vertex properties vx vy vz are a "
                 "vector field); or generated: landscape[:SEED[:CONTROLS[:RESOLUTION]]], "
                 "relief:FILE:VAR:BOX[:SCALE[:RES]], globe[:LEVEL], torus[:R,r], "
                 "cylinder[:RADIUS,LENGTH[,COUNT]]. Default: the demo, data/meshes/bunny00.off, "
                 "else cow.off, else a procedural torus");
  cmd.add_option(
      "--field", o.field,
      "Vector field: file (PLY vx vy vz); uniform:X,Y,Z; rotate:X,Y,Z (rotation about axis "
      "X,Y,Z through the bounding-box centre); elements[:X,Y,Z] (uniform flow X,Y,Z plus the "
      "--element list); principal:min|max[:X,Y,Z][:rot90] (principal directions signed along "
      "X,Y,Z, default +Y, optionally turned 90 degrees, paper 4.2); gradient:down|up[:X,Y,Z]"
      "[:normalize] (steepest descent/ascent of the height along X,Y,Z, default +Y). "
      "Default: file when the mesh has vectors, elements with --element, gradient:down on a "
      "landscape, else rotate:0,1,0");
  cmd.add_option("--element", o.elements,
                 "A potential-flow element (paper 4.1), repeatable: the segment A-B and its "
                 "strengths AX,AY,AZ,BX,BY,BZ,ROTATIONAL,RADIAL,TANGENTIAL[,CORE]; rotational "
                 "swirls about A->B, radial > 0 repels and < 0 attracts, tangential flows along "
                 "A->B; speeds fall as 1/distance, clamped within CORE (default 5% of |AB|). "
                 "Implies --field elements")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd.add_option("--tangent", o.tangent,
                 "project: project vectors on the tangent plane; 3d: use them as given (paper 3.8)")
      ->capture_default_str();
  cmd.add_option("--size", o.size, "Image size WxH in pixels")->capture_default_str();
  cmd.add_option("--frames", o.frames, "Number of frames to render")->capture_default_str();
  cmd.add_option(
      "--out", o.out,
      "Output: .mp4/.mkv/.mov/.avi (x264), .webm (VP9), .gif (needs the ffmpeg program), .png "
      "(last frame) or a %04d .png pattern (every frame). Default: <mesh>.mp4, "
      "ibfvs-demo.mp4 for the demo");
  cmd.add_option("--texture-out", o.texture_out,
                 "Also write the raw texture image F_t of the last frame as a 16-bit PNG");
  cmd.add_option("--alpha", o.alpha, "Blend weight of fresh noise (eq. 5/12), 0..1")
      ->capture_default_str();
  cmd.add_option("--beta", o.beta, "Strength of the texture against shading (eq. 11), 0..1")
      ->capture_default_str();
  cmd.add_option("--scale", o.scale, "Noise scale s: pixels per noise grid cell (eq. 6)")
      ->capture_default_str();
  cmd.add_option("--profile", o.profile, "Noise time profile w: square, sawtooth, sine, spike")
      ->capture_default_str();
  cmd.add_option("--vg", o.vg, "Image-change rate v_g: noise periods per frame (eq. 8)")
      ->capture_default_str();
  cmd.add_option("--spike-width", o.spike_width,
                 "Fraction of the period a spike is on (profile spike)")
      ->capture_default_str();
  cmd.add_option("--noise-space", o.noise_space,
                 "image: noise fixed on the screen, constant density there (the paper); object: "
                 "noise on a 3D lattice at the surface point, s pixels apart at the mesh centre, "
                 "constant density on the surface (paper 3.6, figure 3 right)")
      ->capture_default_str();
  cmd.add_option("--seed", o.seed, "Seed of the noise phases")->capture_default_str();
  cmd.add_option("--step", o.step,
                 "Largest image-space displacement per frame in pixels (sets dt); keep it below "
                 "the noise scale")
      ->capture_default_str();
  cmd.add_option("--dt", o.dt, "Time step in world units per frame; overrides --step when > 0")
      ->capture_default_str();
  cmd.add_flag("--image-normalize", o.image_normalize,
               "Normalise the flow in image space: every moving point moves --step pixels per "
               "frame, whatever its speed or its angle to the view (paper figure 2)");
  cmd.add_option("--inject", o.inject,
                 "How noise enters the texture: blend (eq. 10) or add (bright particles with "
                 "--profile spike)")
      ->capture_default_str();
  cmd.add_option("--background", o.background, "Background colour B as R,G,B in 0..1")
      ->capture_default_str();
  cmd.add_option("--surface-color", o.surface_color, "Diffuse colour of the shaded surface, R,G,B")
      ->capture_default_str();
  cmd.add_option("--color-by", o.color_by,
                 "Colour the surface by a per-vertex scalar: a mesh property (PLY scalar; kmin, "
                 "kmax from ibfvs geometry; height of a landscape) or speed, kmin, kmax, x, y, z");
  cmd.add_option("--color-map", o.color_map, "Colour map: viridis, coolwarm (diverging), grey")
      ->capture_default_str();
  cmd.add_option("--color-range", o.color_range,
                 "LO,HI: scalar values at the ends of the colour map, or percentiles pA,pB. "
                 "Default: p1,p99");
  cmd.add_option("--beta-by", o.beta_by,
                 "Modulate the texture strength beta by a per-vertex scalar (names as "
                 "--color-by; paper 3.3 step 7, figures 6 and 9)");
  cmd.add_option("--beta-range", o.beta_range,
                 "LO,HI: beta is 0 at LO and --beta at HI. Default: the 1st and 99th percentile");
  cmd.add_option("--scalar", o.scalars,
                 "NAME=FILE:VAR, repeatable: a per-vertex scalar NAME sampled from the netCDF "
                 "lon/lat grid VAR (at --time when it has a time axis), for --color-by and "
                 "--beta-by; e.g. relief=data/earth/etopo20.cdf:ROSE")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd.add_option("--surface-image", o.surface_image,
                 "A PNG that stands in for the surface colour, e.g. a map: equirectangular, "
                 "longitude -180..180 across, latitude -90..90 up, mapped by the direction from "
                 "the bounding-box centre (+Y north, +Z longitude 0), as on --mesh globe");
  cmd.add_option("--style", o.style,
                 "Defaults for one of the paper's looks, on any mesh (explicit options override "
                 "them): flow, particles, principal, bronze, eroded, topology (see README)");
  cmd.add_option("--default-field", o.default_field,
                 "The field when --field is not given and the mesh has no vectors (styles set "
                 "it). Default: rotate:0,1,0; gradient:down on landscapes and reliefs");
  cmd.add_option("--init", o.init,
                 "F_t at the start: background, or random-cells (a random colour per noise "
                 "cell; with --alpha 0 and a downhill field: topological decomposition, paper "
                 "figure 7)")
      ->capture_default_str();
  cmd.add_option("--lock-at", o.lock_at,
                 "Lock the texture after this many frames (paper 3.7): it stays on the surface "
                 "as an ordinary texture map while the camera moves (-1: never)")
      ->capture_default_str();
  cmd.add_option("--export", o.export_model,
                 "FILE.obj|FILE.gltf|FILE.glb: after the last frame, write the texture F_t as "
                 "FILE.png and the mesh with texture coordinates (OBJ + MTL, glTF + bin, or one "
                 "binary glTF with the image inside) for Blender or ParaView (paper 3.7: one "
                 "view, so parts hidden in it get wrong texture)");
  cmd.add_option("--lock-camera", o.lock_camera,
                 "AZIMUTH,ELEVATION,DISTANCE: the camera for the frames after --lock-at");
  cmd.add_option("--displace", o.displace,
                 "NAME:FACTOR: move every vertex along its normal by FACTOR times the scalar NAME "
                 "(names as --color-by), e.g. relief:0.00002 on the globe for an exaggerated "
                 "relief; normals are recomputed");
  cmd.add_option("--time", o.time,
                 "Time index of netCDF data (wind: and --scalar), from 0, e.g. a month of "
                 "monthly_navy_winds.cdf (0 = January 1980) or of coads_climatology.cdf; or a "
                 "range A:B that the animation plays through, --frames-per-step frames per "
                 "step, interpolating linearly between steps and looping")
      ->capture_default_str();
  cmd.add_option("--field-step", o.field_steps,
                 "A PLY file with vx vy vz on the mesh's vertices: one time step of an unsteady "
                 "field, repeatable, played in order like --time A:B")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd.add_option("--frames-per-step", o.frames_per_step,
                 "Frames from one time step of an unsteady field to the next")
      ->capture_default_str();
  cmd.add_option("--camera", o.camera,
                 "AZIMUTH,ELEVATION,DISTANCE: degrees about +Y and above the horizon, distance in "
                 "bounding-box diagonals (0 fits the mesh). Default 0,0,0: from +Z, +Y up, fitted");
  cmd.add_option("--look-at", o.look_at,
                 "X,Y,Z: the point the camera turns about and looks at, as an offset from the "
                 "bounding-box centre in world units (the viewer's pan). Default 0,0,0");
  cmd.add_flag("--ortho", o.ortho, "Orthographic instead of perspective projection");
  cmd.add_option("--fov", o.fov, "Vertical field of view in degrees")->capture_default_str();
  cmd.add_option("--orbit", o.orbit,
                 "Turn the camera about the vertical axis by this many degrees per frame")
      ->capture_default_str();
  cmd.add_option("--advect-view", o.advect_view,
                 "Transform for texture coordinates: previous (T_{k-1}: texture stays on the "
                 "surface under camera motion) or current (T_k, as the 2003 paper)")
      ->capture_default_str();
  cmd.add_option("--subdivide", o.subdivide, "Loop subdivision levels (0..8)")
      ->capture_default_str();
  cmd.add_option("--fps", o.fps, "Frame rate of the video")->capture_default_str();
  cmd.add_flag("--quiet,-q", o.quiet, "No progress bar and no summary");
}

namespace {

struct Size {
  int width, height;
};

Size parse_size(const std::string& text) {
  const std::size_t x = text.find('x');
  try {
    if (x != std::string::npos) {
      std::size_t used_w = 0, used_h = 0;
      const int w = std::stoi(text.substr(0, x), &used_w);
      const int h = std::stoi(text.substr(x + 1), &used_h);
      if (used_w == x && used_h == text.size() - x - 1 && w > 0 && h > 0 && w <= 16384 &&
          h <= 16384)
        return {w, h};
    }
  } catch (const std::exception&) {
  }
  throw InputError("--size: expected WxH with 1..16384 pixels each, got '" + text + "'");
}

glm::vec3 parse_colour(const std::string& text, const char* option) {
  const glm::vec3 c = parse_vec3(text, option);
  for (int i = 0; i < 3; ++i)
    if (c[i] < 0.0f || c[i] > 1.0f)
      throw InputError(std::string(option) + ": components must be in [0, 1], got '" + text + "'");
  return c;
}

// The default video name for a mesh: its file stem, or for a generated
// surface (landscape:3, globe, relief:...) its name with ':' and ',' made
// safe for file names and for ffmpeg (which reads "a:b" as a protocol).
std::string default_output_stem(const std::string& mesh) {
  std::string stem = fs::exists(mesh) ? fs::path(mesh).stem().string() : mesh;
  if (!fs::exists(mesh)) {
    const std::size_t slash = stem.find_last_of('/');
    if (stem.rfind("relief:", 0) == 0 && slash != std::string::npos)
      stem = "relief-" + stem.substr(slash + 1);
  }
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '-';
  return stem;
}

// "LO,HI": two finite numbers with LO < HI.
glm::vec2 parse_range(const std::string& text, const char* option) {
  const std::vector<float> v = parse_numbers(text, option, 2, "LO,HI");
  if (!(v[1] > v[0]))
    throw InputError(std::string(option) + ": expected LO,HI with LO < HI, got '" + text + "'");
  return {v[0], v[1]};
}

// "A" or "A:B": time indices from 0, A <= B.
std::pair<std::size_t, std::size_t> parse_time_range(const std::string& text) {
  const std::size_t colon = text.find(':');
  const auto index = [&](const std::string& part) {
    std::size_t used = 0;
    long v = -1;
    try {
      v = std::stol(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != part.size() || v < 0)
      throw InputError("--time: expected an index from 0 or a range A:B, got '" + text + "'");
    return static_cast<std::size_t>(v);
  };
  const std::size_t a = index(text.substr(0, colon));
  const std::size_t b = colon == std::string::npos ? a : index(text.substr(colon + 1));
  if (b < a) throw InputError("--time: the range " + text + " runs backwards");
  return {a, b};
}

InjectMode parse_inject(const std::string& text) {
  if (text == "blend") return InjectMode::Blend;
  if (text == "add") return InjectMode::Add;
  throw InputError("--inject: expected blend or add, got '" + text + "'");
}

enum class OutputKind { Video, Png, PngSequence };

OutputKind output_kind(const fs::path& out, const char* option) {
  if (is_video_path(out)) return OutputKind::Video;
  if (lower_extension(out) != ".png")
    throw InputError(std::string(option) + ": unknown output type '" + out.string() +
                     "' (expected .mp4, .mkv, .webm, .mov, .avi, .gif or .png)");
  return out.string().find('%') != std::string::npos ? OutputKind::PngSequence : OutputKind::Png;
}

std::string frame_path(const std::string& pattern, int frame) {
  // Only one integer conversion is allowed in the pattern (checked before rendering).
  std::vector<char> buf(pattern.size() + 32);
  std::snprintf(buf.data(), buf.size(), pattern.c_str(), frame);
  return buf.data();
}

void check_pattern(const std::string& pattern) {
  const std::size_t p = pattern.find('%');
  const std::size_t d = pattern.find_first_of("d", p);
  bool ok = p != std::string::npos && d != std::string::npos &&
            pattern.find('%', p + 1) == std::string::npos;
  for (std::size_t i = p + 1; ok && i < d; ++i)
    ok = std::isdigit(static_cast<unsigned char>(pattern[i]));
  if (!ok)
    throw InputError("--out: a frame pattern needs exactly one %d or %0Nd, got '" + pattern + "'");
}

void ensure_parent(const fs::path& out, const char* option) {
  const fs::path parent = out.parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw InputError(std::string(option) + ": the folder '" + parent.string() + "' does not exist");
}

}  // namespace

PreparedScene prepare_scene(const RenderOptions& o) {
  // ---- options that need no file
  PreparedScene scene;
  const Size size = parse_size(o.size);
  scene.width = size.width;
  scene.height = size.height;
  if (o.frames < 1 || o.frames > 1000000)
    throw InputError("--frames: must be between 1 and 1000000");
  scene.frames = static_cast<int>(o.frames);
  if (!(o.step > 0.0f) || !std::isfinite(o.step))
    throw InputError("--step: must be a positive number of pixels");
  if (!(o.dt >= 0.0f) || !std::isfinite(o.dt))
    throw InputError("--dt: must be a non-negative number");
  if (o.image_normalize && o.dt > 0.0f)
    throw InputError("--image-normalize: moves every point --step pixels; it takes no --dt");
  if (!std::isfinite(o.orbit) || std::abs(o.orbit) > 360.0f)
    throw InputError("--orbit: must be within -360..360 degrees per frame");
  if (!(o.fps > 0.0) || o.fps > 1000.0) throw InputError("--fps: must be in (0, 1000]");
  if (o.subdivide < 0 || o.subdivide > 8)
    throw InputError("--subdivide: levels must be between 0 and 8");

  RenderSettings& settings = scene.settings;
  settings.width = size.width;
  settings.height = size.height;
  settings.alpha = o.alpha;
  settings.beta = o.beta;
  settings.image_step = o.image_normalize ? o.step : 0.0f;
  settings.noise.scale = o.scale;
  settings.noise.profile = parse_noise_profile(o.profile);
  settings.noise.rate = o.vg;
  settings.noise.seed = o.seed;
  settings.noise.spike_width = o.spike_width;
  settings.inject = parse_inject(o.inject);
  settings.background = parse_colour(o.background, "--background");
  settings.surface_color = parse_colour(o.surface_color, "--surface-color");
  settings.advect_view = parse_advect_view(o.advect_view);
  settings.validate();
  const TangentMode tangent = parse_tangent_mode(o.tangent);
  std::optional<FieldSpec> field_spec;
  if (!o.field.empty()) field_spec = FieldSpec::parse(o.field);
  if (!field_spec && !o.elements.empty()) field_spec = FieldSpec::parse("elements");
  if (!o.elements.empty() && field_spec->kind != FieldKind::Elements)
    throw InputError("--element: needs --field elements (or no --field), got --field " + o.field);
  if (field_spec)
    for (const std::string& e : o.elements) field_spec->elements.push_back(FlowElement::parse(e));
  const auto [time_first, time_last] = parse_time_range(o.time);
  if (o.noise_space != "image" && o.noise_space != "object")
    throw InputError("--noise-space: expected image or object, got '" + o.noise_space + "'");
  settings.object_noise = o.noise_space == "object";
  if (o.init != "background" && o.init != "random-cells")
    throw InputError("--init: expected background or random-cells, got '" + o.init + "'");
  if (o.lock_at < -1) throw InputError("--lock-at: must be a frame number, or -1 for never");
  std::optional<CameraParams>& lock_cam = scene.lock_camera;
  if (!o.lock_camera.empty()) {
    const glm::vec3 c = parse_vec3(o.lock_camera, "--lock-camera");
    if (c.z < 0.0f) throw InputError("--lock-camera: the distance must not be negative");
    lock_cam = CameraParams{c.x, c.y, c.z, o.ortho, o.fov};
  }
  if (field_spec) field_spec->time = time_first;
  if (o.frames_per_step < 1 || o.frames_per_step > 100000)
    throw InputError("--frames-per-step: must be between 1 and 100000");
  if (!o.field_steps.empty() && o.subdivide > 0)
    throw InputError("--field-step: cannot be combined with --subdivide");
  if (!o.field_steps.empty() && field_spec && field_spec->kind != FieldKind::File)
    throw InputError("--field-step: needs --field file (or no --field), got --field " + o.field);
  if (time_last > time_first && (!field_spec || field_spec->kind != FieldKind::Wind))
    throw InputError("--time: a range A:B needs --field wind:...");
  CameraParams& cam = scene.camera;
  if (!o.camera.empty()) {
    const glm::vec3 c = parse_vec3(o.camera, "--camera");
    cam.azimuth_deg = c.x;
    cam.elevation_deg = c.y;
    cam.distance = c.z;
    if (c.z < 0.0f) throw InputError("--camera: the distance must not be negative");
  }
  cam.orthographic = o.ortho;
  if (!o.look_at.empty()) cam.target = parse_vec3(o.look_at, "--look-at");
  cam.fov_deg = o.fov;

  // ---- mesh
  LoadedMesh loaded = load_mesh(o.mesh, o.subdivide);
  auto mesh_ptr = std::make_shared<TriMesh>(std::move(loaded.mesh));
  TriMesh& mesh = *mesh_ptr;
  const std::string mesh_name = loaded.demo ? loaded.name : fs::path(o.mesh).filename().string();
  const bool demo = loaded.demo;

  // ---- scalars sampled from netCDF grids
  for (const std::string& spec : o.scalars) {
    const std::size_t eq = spec.find('='), colon = spec.rfind(':');
    if (eq == std::string::npos || colon == std::string::npos || colon < eq || eq == 0 ||
        colon == eq + 1 || colon + 1 == spec.size())
      throw InputError("--scalar: expected NAME=FILE:VAR, got '" + spec + "'");
    const std::string name = spec.substr(0, eq), path = spec.substr(eq + 1, colon - eq - 1);
    const std::string var = spec.substr(colon + 1);
    LonLatGrid grid = read_lonlat_grid(path, var, 0);
    if (grid.time_steps > 1) grid = read_lonlat_grid(path, var, time_first);
    mesh.scalars[name] = lonlat_scalars(mesh, grid);
  }

  // ---- curvature, once, when the field or a scalar needs it
  {
    const auto wants = [](const std::string& name) {
      const std::string n = !name.empty() && name[0] == '-' ? name.substr(1) : name;
      return n == "kmin" || n == "kmax";
    };
    const bool principal = (field_spec && field_spec->kind == FieldKind::Principal) ||
                           (!field_spec && o.default_field.rfind("principal", 0) == 0);
    if ((principal || wants(o.color_by) || wants(o.beta_by) ||
         wants(o.displace.substr(0, o.displace.rfind(':')))) &&
        !mesh.scalars.count("kmax"))
      store_curvature(mesh, compute_curvature(mesh), false);
  }

  // ---- displacement along the normals (the vertical scale of a relief)
  if (!o.displace.empty()) {
    const std::size_t colon = o.displace.rfind(':');
    float factor = 0.0f;
    std::size_t used = 0;
    if (colon != std::string::npos && colon > 0) {
      try {
        factor = std::stof(o.displace.substr(colon + 1), &used);
      } catch (const std::exception&) {
        used = 0;
      }
    }
    if (colon == std::string::npos || colon == 0 || used == 0 ||
        used != o.displace.size() - colon - 1 || !std::isfinite(factor))
      throw InputError("--displace: expected NAME:FACTOR, got '" + o.displace + "'");
    std::vector<float> amount;
    try {
      amount = vertex_scalar(mesh, {}, o.displace.substr(0, colon));
    } catch (const InputError& e) {
      throw InputError("--displace: " + mesh_name + ": " + e.what());
    }
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
      if (std::isfinite(amount[i])) mesh.positions[i] += factor * amount[i] * mesh.normals[i];
    compute_vertex_normals(mesh);
  }

  // ---- field
  if (!field_spec) {
    field_spec = mesh.vectors.size() == mesh.positions.size() ? FieldSpec::parse("file")
                 : !o.default_field.empty()                   ? FieldSpec::parse(o.default_field)
                 : loaded.generated_landscape                 ? FieldSpec::parse("gradient:down")
                                                              : FieldSpec::parse("rotate:0,1,0");
  }
  // An unsteady field: its steps, evaluated when the animation reaches them.
  std::size_t& step_count = scene.step_count;
  auto& step_field = scene.step_field;
  if (!o.field_steps.empty()) {
    step_count = o.field_steps.size();
    step_field = [files = o.field_steps, expected = loaded.file_vertices,
                  order = loaded.vertex_order, mesh_ptr, tangent](std::size_t s) {
      const std::string& file = files[s];
      const TriMesh step = read_mesh(file);
      if (step.vertex_count() != expected)
        throw InputError("--field-step: " + file + ": " + std::to_string(step.vertex_count()) +
                         " vertices, the mesh has " + std::to_string(expected));
      if (step.vectors.empty()) throw InputError("--field-step: " + file + ": has no vx vy vz");
      TriMesh on_mesh;
      on_mesh.positions = mesh_ptr->positions;
      on_mesh.normals = mesh_ptr->normals;
      on_mesh.triangles = mesh_ptr->triangles;
      on_mesh.vectors = remap_vertex_data(step.vectors, order);
      return evaluate_field(on_mesh, FieldSpec::parse("file"), tangent);
    };
  } else if (time_last > time_first) {
    step_count = time_last - time_first + 1;
    read_lonlat_grid(field_spec->path, field_spec->east, time_last);  // the range exists
    step_field = [spec = *field_spec, first = time_first, mesh_ptr, tangent](std::size_t s) {
      FieldSpec at = spec;
      at.time = first + s;
      return evaluate_field(*mesh_ptr, at, tangent);
    };
  }
  FieldReport field_report;
  std::vector<glm::vec3>& field = scene.field;
  try {
    field = step_field ? step_field(0) : evaluate_field(mesh, *field_spec, tangent, &field_report);
  } catch (const InputError& e) {
    throw InputError((demo ? mesh_name : o.mesh) + ": " + e.what());
  }
  if (field_report.non_finite_zeroed > 0)
    std::fprintf(stderr,
                 "ibfvs: warning: %s: %zu vectors were NaN or infinite and are set to zero\n",
                 (demo ? mesh_name : o.mesh).c_str(), field_report.non_finite_zeroed);

  // ---- camera and displacement
  const Bounds bounds = mesh_bounds(mesh);
  Camera camera(bounds, cam, static_cast<float>(size.width) / static_cast<float>(size.height));
  // Pixels per unit of dt at the fastest vertex: sets dt from --step, and
  // says how far the fastest vertex moves with a given --dt.
  const float speed =
      max_pixel_speed(mesh.positions, field, camera.view_projection(), size.width, size.height);
  const float dt = scene.dt = o.dt > 0.0f ? o.dt : (speed > 0.0f ? o.step / speed : 0.0f);
  const float max_px = scene.max_px = o.image_normalize && speed > 0.0f ? o.step : speed * dt;
  if (speed == 0.0f)
    std::fprintf(stderr,
                 "ibfvs: warning: the field does not move any vertex in the image (zero after "
                 "projection?); the texture will stand still\n");
  if (max_px > settings.noise.scale)
    std::fprintf(stderr,
                 "ibfvs: warning: the largest displacement is %.1f pixels per frame, more than "
                 "the noise scale %.1f: expect broken streaks (lower --step or --dt)\n",
                 max_px, settings.noise.scale);

  // ---- scalars for colour and beta
  std::vector<float>&color_scalar = scene.color_scalar, &beta_scalar = scene.beta_scalar;
  // The named scalar, and its range: given as LO,HI or the 1st to 99th percentile.
  const auto scalar_range = [&](const std::string& name, const char* option,
                                const std::string& range_text, const char* range_option,
                                std::vector<float>& values) {
    try {
      values = vertex_scalar(mesh, field, name);
    } catch (const InputError& e) {
      throw InputError(std::string(option) + ": " + mesh_name + ": " + e.what());
    }
    if (range_text.empty()) return quantile_range(values);
    // "pA,pB": the A-th and B-th percentiles of the values.
    if (range_text[0] == 'p') {
      const std::size_t comma = range_text.find(",p");
      const glm::vec2 q =
          comma == std::string::npos
              ? glm::vec2(-1.0f)
              : parse_range(range_text.substr(1, comma - 1) + "," + range_text.substr(comma + 2),
                            range_option);
      if (!(q.x >= 0.0f && q.y <= 100.0f))
        throw InputError(std::string(range_option) +
                         ": expected percentiles pA,pB with 0 <= A < B <= 100, got '" + range_text +
                         "'");
      return quantile_range(values, q.x / 100.0f, q.y / 100.0f);
    }
    return parse_range(range_text, range_option);
  };
  settings.color_map = parse_color_map(o.color_map);
  if (!o.color_by.empty()) {
    settings.use_color = true;
    settings.color_range =
        scalar_range(o.color_by, "--color-by", o.color_range, "--color-range", color_scalar);
  }
  if (!o.beta_by.empty()) {
    settings.use_beta = true;
    settings.beta_range =
        scalar_range(o.beta_by, "--beta-by", o.beta_range, "--beta-range", beta_scalar);
  }
  settings.validate();

  if (settings.object_noise) {
    // s pixels at the distance of the mesh centre, in world units.
    const float world_per_pixel = 2.0f * camera.distance_world() *
                                  std::tan(glm::radians(cam.fov_deg) * 0.5f) /
                                  static_cast<float>(size.height);
    settings.object_cell = settings.noise.scale * world_per_pixel;
  }
  scene.mesh = std::move(mesh_ptr);
  scene.mesh_name = mesh_name;
  scene.demo = demo;
  scene.field_spec = *field_spec;
  return scene;
}

void load_scene(IbfvsRenderer& renderer, const PreparedScene& scene, const RenderOptions& o) {
  renderer.set_mesh(*scene.mesh, scene.field);
  if (scene.settings.use_color || scene.settings.use_beta)
    renderer.set_scalars(scene.color_scalar, scene.beta_scalar);
  if (!o.surface_image.empty())
    renderer.set_surface_image(read_png(o.surface_image), mesh_bounds(*scene.mesh).centre());
  if (o.init == "random-cells") renderer.fill_texture_with_cell_colors(o.seed);
}

FieldPlayer::FieldPlayer(const PreparedScene& scene, IbfvsRenderer& renderer) : scene_(scene) {
  if (scene.step_count < 2) return;
  field_ = scene.field;
  next_ = scene.step_field(1 % scene.step_count);
  renderer.set_field_steps(field_, next_);
}

void FieldPlayer::seek(double t, IbfvsRenderer& renderer) {
  const std::size_t n = scene_.step_count;
  if (n < 2) return;
  t = std::fmod(std::max(t, 0.0), static_cast<double>(n));
  const auto s = static_cast<std::size_t>(t) % n;
  if (s != step_) {
    // Playing on, the next step is already at hand; a jump evaluates both.
    field_ = s == (step_ + 1) % n ? std::move(next_) : scene_.step_field(s);
    next_ = scene_.step_field((s + 1) % n);
    step_ = s;
    renderer.set_field_steps(field_, next_);
  }
  renderer.set_field_mix(static_cast<float>(t - std::floor(t)));
}

int run_render(const RenderOptions& o) {
  // ---- output paths (checked before anything is loaded)
  const bool demo = o.mesh.empty();
  const fs::path out = !o.out.empty() ? fs::path(o.out)
                       : demo         ? fs::path("ibfvs-demo.mp4")
                                      : fs::path(default_output_stem(o.mesh) + ".mp4");
  const OutputKind kind = output_kind(out, "--out");
  if (kind == OutputKind::PngSequence) check_pattern(out.string());
  ensure_parent(out, "--out");
  const std::string export_ext = lower_extension(o.export_model);
  if (!o.export_model.empty()) {
    if (export_ext != ".obj" && export_ext != ".gltf" && export_ext != ".glb")
      throw InputError("--export: must be a .obj, .gltf or .glb file, got '" + o.export_model +
                       "'");
    ensure_parent(o.export_model, "--export");
  }
  if (!o.texture_out.empty()) {
    if (output_kind(o.texture_out, "--texture-out") != OutputKind::Png)
      throw InputError("--texture-out: must be a .png file, got '" + o.texture_out + "'");
    ensure_parent(o.texture_out, "--texture-out");
  }

  PreparedScene scene = prepare_scene(o);
  const Size size{scene.width, scene.height};
  const int frames = scene.frames;
  const TriMesh& mesh = *scene.mesh;
  const std::string& mesh_name = scene.mesh_name;
  const float dt = scene.dt, max_px = scene.max_px;
  const FieldSpec* field_spec = &scene.field_spec;
  const Bounds bounds = mesh_bounds(mesh);
  Camera camera(bounds, scene.camera,
                static_cast<float>(size.width) / static_cast<float>(size.height));

  // ---- render
  gl::HeadlessContext context;
  IbfvsRenderer renderer(scene.settings);
  load_scene(renderer, scene, o);
  std::unique_ptr<VideoWriter> video;
  if (kind == OutputKind::Video)
    video = std::make_unique<VideoWriter>(out, size.width, size.height, o.fps);
  Progress progress(frames, !o.quiet);
  const auto start = std::chrono::steady_clock::now();
  std::optional<Camera> camera_after_lock;
  if (scene.lock_camera)
    camera_after_lock.emplace(bounds, *scene.lock_camera,
                              static_cast<float>(size.width) / static_cast<float>(size.height));
  // Unsteady: the current and next step live on the GPU, mixed per frame.
  FieldPlayer player(scene, renderer);
  for (int k = 0; k < frames; ++k) {
    if (k == o.lock_at) {
      renderer.lock();
      if (camera_after_lock) camera = *camera_after_lock;
    }
    player.seek(static_cast<double>(k) / o.frames_per_step, renderer);
    if (k > 0 && o.orbit != 0.0f) camera.orbit(o.orbit);
    renderer.render_frame({camera.view(), camera.projection()}, dt);
    if (kind == OutputKind::Video) {
      ImageU8 frame = video->spare();
      renderer.read_output(frame);
      video->write(std::move(frame));
    }
    if (kind == OutputKind::PngSequence)
      write_png(renderer.read_output(), frame_path(out.string(), k));
    progress.update(k + 1);
  }
  renderer.finish();
  context.throw_if_errors();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.finish();
  if (kind == OutputKind::Png) write_png(renderer.read_output(), out);
  if (video) video->close();
  if (!o.texture_out.empty()) {
    write_png16(renderer.read_texture().select_channels(0, 3), o.texture_out);
  }
  if (!o.export_model.empty()) {
    // F_t as an 8-bit RGB image and each vertex's position in it (section 3.7).
    const fs::path model(o.export_model);
    fs::path png = model;
    png.replace_extension(".png");
    const ImageF tex = renderer.read_texture();
    ImageU8 rgb(tex.width, tex.height, 3);
    for (std::size_t i = 0; i < rgb.pixels.size() / 3; ++i)
      for (int c = 0; c < 3; ++c)
        rgb.pixels[i * 3 + c] = static_cast<std::uint8_t>(
            std::lround(std::clamp(tex.pixels[i * 4 + c], 0.0f, 1.0f) * 255.0f));
    write_png(rgb, png);
    std::vector<glm::vec2> uv(mesh.vertex_count());
    std::size_t outside = 0;
    for (std::size_t i = 0; i < uv.size(); ++i) {
      const glm::vec2 px = project_to_pixels(renderer.texture_view_projection(), mesh.positions[i],
                                             size.width, size.height);
      const glm::vec2 t(px.x / static_cast<float>(size.width),
                        px.y / static_cast<float>(size.height));
      uv[i] = glm::clamp(t, glm::vec2(0.0f), glm::vec2(1.0f));
      outside += uv[i] != t;
    }
    std::string written = model.string();
    if (export_ext == ".obj") {
      write_obj_textured(mesh, uv, model, png.filename().string());
      written += ", " + fs::path(model).replace_extension(".mtl").string();
    } else {
      write_gltf_textured(mesh, uv, model, png);
      if (export_ext == ".gltf")
        written += ", " + fs::path(model).replace_extension(".bin").string();
    }
    if (outside > 0)
      std::fprintf(stderr,
                   "ibfvs: warning: %zu vertices lie outside the view that made the texture; "
                   "their texture coordinates are clamped to the image border\n",
                   outside);
    if (!o.quiet) std::printf("ibfvs: exported %s and %s\n", written.c_str(), png.c_str());
  }
  if (!o.quiet) {
    std::printf(
        "ibfvs: wrote %s (%d frames, %dx%d) from %s: %zu vertices, %zu triangles, field %s, "
        "dt %.4g (%s %.2f px/frame), %.1f fps on %s\n",
        out.c_str(), frames, size.width, size.height, mesh_name.c_str(), mesh.vertex_count(),
        mesh.triangle_count(), field_spec->to_string().c_str(), dt,
        o.image_normalize ? "image-normalised, every point" : "max", max_px, frames / seconds,
        context.renderer().c_str());
    if (!o.texture_out.empty())
      std::printf("ibfvs: wrote texture image %s\n", o.texture_out.c_str());
  }
  return 0;
}

}  // namespace ibfvs::app
