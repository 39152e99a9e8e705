#pragma once
// A scene: everything one IBFVS run needs, typed. Mesh source, field
// source(s), scalars, camera and its motion, texture settings, unsteady
// steps, the style it started from, outputs. Every front end fills one: the
// command line parses its flags into it, scene files (TOML) are read straight
// into it and written from it, Python and ParaView set it field by field.
//
// Sections: enums and small value types | Scene | keys (the one list of
// settings, with their text forms) | scene files | styles.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/fields/potential_flow.h"
#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/render_settings.h"
#include "ibfvs/core/support/names.h"
#include "ibfvs/core/texture/noise.h"
#include "ibfvs/core/texture/reference.h"

namespace ibfvs {

// ------------------------------------------------------------ enums and small value types

/// Where the fresh noise G lives (section 3.6).
enum class NoiseSpace {
  Image,   ///< fixed on the screen, constant density there (the paper)
  Object,  ///< on a 3D lattice at the surface point, attached to it
};
template <>
struct EnumNames<NoiseSpace> {
  static constexpr EnumName<NoiseSpace> table[] = {
      {NoiseSpace::Image, "image", "fixed on the screen (the paper)"},
      {NoiseSpace::Object, "object", "on a 3D lattice at the surface point (3.6, figure 3)"},
  };
};

/// What is drawn over the texture.
enum class Overlay {
  None,      ///< the texture alone
  Topology,  ///< the field's critical points and separation and attachment lines (issue 64)
};
template <>
struct EnumNames<Overlay> {
  static constexpr EnumName<Overlay> table[] = {
      {Overlay::None, "none", "the texture alone"},
      {Overlay::Topology, "topology",
       "the field's critical points, separation and attachment lines, with a legend "
       "(docs/cfd.md)"},
  };
};

/// F_t at the start.
enum class InitMode {
  Background,   ///< the background colour B
  RandomCells,  ///< a random colour per noise cell (topological decomposition, figure 7)
};
template <>
struct EnumNames<InitMode> {
  static constexpr EnumName<InitMode> table[] = {
      {InitMode::Background, "background", "the background colour"},
      {InitMode::RandomCells, "random-cells", "a random colour per noise cell (figure 7)"},
  };
};

/// The paper's looks (section 5: "for standard cases ... default settings").
enum class Style { Flow, Crisp, Paper, Particles, Principal, Bronze, Eroded, Topology };
template <>
struct EnumNames<Style> {
  static constexpr EnumName<Style> table[] = {
      {Style::Flow, "flow", "dense moving texture (figures 1, 5)"},
      {Style::Crisp, "crisp",
       "the longest unbroken streaks: a display filter of 24 px (the defaults' 16)"},
      {Style::Paper, "paper",
       "the 2003 paper's look and cost (Table 1): scale 4, square profile, no display stage"},
      {Style::Particles, "particles", "bright particles along kappa_min (figure 8a)"},
      {Style::Principal, "principal", "dense texture along kappa_min (figure 8b)"},
      {Style::Bronze, "bronze", "patina in the hollows, dirt texture (figure 9)"},
      {Style::Eroded, "eroded", "the same by kappa_min, grey (4.2)"},
      {Style::Topology, "topology", "basins coloured by their summits, locked (figure 7)"},
  };
};

/// A per-vertex scalar sampled from a netCDF lon/lat grid: NAME=FILE:VAR.
struct GridScalar {
  std::string name, path, variable;
  static GridScalar parse(std::string_view text);  ///< throws InputError
  [[nodiscard]] std::string to_string() const;
};

/// Vertices moved along their normals by factor times a scalar: NAME:FACTOR.
struct Displacement {
  std::string scalar;
  float factor = 0.0f;
  static Displacement parse(std::string_view text);  ///< throws InputError
  [[nodiscard]] std::string to_string() const;
};

/// The scalar values at the two ends of a map: LO,HI, or percentiles pA,pB.
struct ScalarRange {
  bool percentile = false;
  float lo = 0.0f, hi = 1.0f;
  static ScalarRange parse(std::string_view text);  ///< throws InputError
  [[nodiscard]] std::string to_string() const;
};

/// A time step index (netCDF, or a series' step), or a range first..last
/// played through.
struct TimeRange {
  std::size_t first = 0, last = 0;
  static TimeRange parse(std::string_view text);  ///< "A" or "A:B"; throws InputError
  [[nodiscard]] std::string to_string() const;
};

// ------------------------------------------------------------ Scene

/// One run, typed. Defaults are the command's defaults.
struct Scene {
  static constexpr int kLockNever = -1;
  static constexpr int kLockAuto = -2;  ///< once the texture has crossed the mesh (topology)

  // ---- mesh
  std::string mesh;   ///< a file or a generated surface (mesh_source.h); empty: the demo
  int subdivide = 0;  ///< Loop subdivision levels, 0..12 (as many as memory holds)
  /// Blocks of a .vtm or patches of an OpenFOAM case, names or patterns
  /// (dataset_io.h); empty: all.
  std::vector<std::string> blocks;
  /// The height axis: camera azimuth turns about it, elevation rises along it,
  /// gradient fields without their own axis use it. Unset: +Y.
  std::optional<glm::vec3> up;
  bool up_auto = false;  ///< up: the mesh's thinnest bounding-box axis (terrains)

  // ---- field
  std::optional<FieldSpec> field;          ///< unset: default_field, else the mesh's rule
  std::optional<FieldSpec> default_field;  ///< when no field is given and the mesh has none
  std::vector<FlowElement> elements;       ///< potential-flow elements (field elements)
  TangentMode tangent = TangentMode::Project;
  /// netCDF time index or a series' step, or a range played through; unset:
  /// index 0, and a series (.pvd, OpenFOAM times, numbered files) plays all
  std::optional<TimeRange> time;
  bool reverse = false;  ///< the field's vectors negated (OpenFOAM's wallShearStress)
  std::vector<std::string> field_steps;  ///< PLY files: the steps of an unsteady field
  int frames_per_step = 30;              ///< frames from one step to the next
  /// A series plays on from its last step back to its first; else it ends
  /// at its last step and holds it.
  bool loop = false;
  FieldFrame field_frame = FieldFrame::Surface;  ///< see FieldFrame

  // ---- scalars and colour
  std::vector<GridScalar> scalars;       ///< sampled from netCDF grids
  std::optional<Displacement> displace;  ///< vertices moved along their normals
  std::string color_by;                  ///< per-vertex scalar that colours F_s; empty: none
  ColorMap color_map = ColorMap::Viridis;
  std::optional<ScalarRange> color_range;  ///< unset: p1,p99
  std::string beta_by;                     ///< per-vertex scalar that modulates beta
  std::optional<ScalarRange> beta_range;   ///< unset: p1,p99
  std::string surface_image;               ///< equirectangular PNG standing in for F_s

  // ---- texture (paper equations 5-12). The defaults are the look measured
  // on real CFD data in docs/quality.md: flow normalised in image space
  // (shear spans decades), pixel-fine noise that never repeats (the pattern
  // moves with the flow), a display filter along the curved streamline,
  // sharpened across it, a fixed RMS contrast, a bilinear warp whose blur
  // across the flow is taken back (compensated), steps of
  // 1.5 pixels, the texture strong against the shading (beta 0.65). The crisp
  // style adds a longer filter; the paper style is the 2003 look: scale 4,
  // profile square, vg 0.02, beta 0.5, step 3, bilinear warp, no display
  // stage.
  float alpha = 0.1f, beta = 0.65f;
  float scale = 1.0f;  ///< s, pixels per noise cell
  NoiseProfile profile = NoiseProfile::Random;
  float vg = 0.2f, spike_width = 0.1f;
  std::uint32_t seed = 1;
  float step = 1.5f;  ///< pixels per frame of the fastest vertex (sets dt)
  float dt = 0.0f;    ///< world units per frame; > 0 overrides step
  bool image_normalize = true;
  float filter = 16.0f;  ///< display filter length along the flow, pixels (0 off)
  Resample resample = Resample::Compensated;
  float sharpen = 4.0f;    ///< display taps sharpened across the flow (0 off)
  float contrast = 0.35f;  ///< target RMS contrast of the shown texture (0: as synthesised)
  InjectMode inject = InjectMode::Blend;
  glm::vec3 background{0.5f};
  glm::vec3 surface_color{0.82f, 0.80f, 0.76f};
  NoiseSpace noise_space = NoiseSpace::Image;
  AdvectView advect_view = AdvectView::Previous;
  InitMode init = InitMode::Background;

  // ---- camera and its motion
  CameraParams camera;       ///< azimuth, elevation, distance, target (look_at), ortho, fov
  float orbit = 0.0f;        ///< degrees per frame about the vertical
  int lock_at = kLockNever;  ///< frame to lock the texture at (3.7), or kLockNever / kLockAuto
  std::optional<glm::vec3> lock_camera;  ///< AZ,EL,DIST once locked
  Overlay overlay = Overlay::None;       ///< drawn over the texture
  /// What counts as a feature of the topology (the overlay's and `ibfvs
  /// topology`'s): feature_scale, min_strength, min_length.
  TopologyOptions topology;

  // ---- output
  int width = 512, height = 512;
  int frames = 150;  ///< 0: as many as an automatic lock needs, plus 60
  double fps = 30.0;
  std::string out;           ///< empty: <mesh>.mp4
  std::string texture_out;   ///< F_t of the last frame, 16-bit PNG
  std::string export_model;  ///< OBJ/glTF/GLB with the texture (3.7)
  bool quiet = false;
  std::optional<Style> style;  ///< the style whose defaults the scene started from
};

// ------------------------------------------------------------ keys

/// What a key's value is, for scene files (TOML types) and the docs.
enum class KeyKind {
  String,
  Integer,
  Number,
  Flag,        ///< true/false; on the command line a bare flag
  Vector,      ///< numbers, "A,B,C" or a TOML array
  Size,        ///< "WxH" or [W, H]
  StringList,  ///< repeatable: each value adds one
  Elements,    ///< repeatable flow elements, text or TOML tables
  Time,        ///< an integer or "A:B"
};

/// What a running animation does when a key changes (Session::set), for
/// the viewer, Python and the restyling of a page alike.
enum class KeyEffect {
  Live,     ///< a texture or display setting the next frame takes (alpha, filter, colours, ...)
  Step,     ///< dt follows the new step
  Noise,    ///< a new noise grid (scale, seed); the texture goes on (a new seed: afresh)
  Tangent,  ///< the field evaluated again; the texture goes on
  Camera,   ///< the view moves (camera, look_at, ortho, fov, orbit)
  Size,     ///< the texture resampled to the new image size
  None,     ///< read as the animation runs or only by a front end (frames, out, style, ...)
  Prepare,  ///< the scene prepared again (mesh, field, scalars, ...): the texture starts afresh
};
/// The span of a number key, for every front end: the command line's and
/// the scene files' checks, RenderSettings::validate, the viewer's
/// sliders, the page's sliders, the ParaView representation's property
/// domains (generated from it) and its clamps.
struct KeyRange {
  float min = 0.0f;
  float max = 0.0f;
  /// true: values outside are refused; false: the span a slider offers
  /// (a typed value beyond it is valid).
  bool enforced = false;
};
/// One value of an enumeration key: the enum's number and its canonical name.
struct KeyChoice {
  int value = 0;
  std::string_view name;
};
/// One setting of a scene, known by the same name in scene files and (with
/// dashes) on the command line: the one table of parameters (scene_keys())
/// that the command's options, the scene files, the Python keywords, the
/// viewer's sliders, the page's sliders and the ParaView XML's ranges and
/// enumerations come from.
struct SceneKey {
  std::string_view name;  ///< snake_case
  KeyKind kind;
  std::string help;  ///< one line: form and meaning (enum keys list their names)
  /// Sets the value from its text form. Throws InputError (the caller adds the key).
  void (*set)(Scene&, std::string_view text);
  /// The value's text forms (several for a repeatable key; none for an unset
  /// optional value or a false flag). set() of each gives the same scene.
  std::vector<std::string> (*get)(const Scene&);
  /// What a running animation does when the key changes.
  KeyEffect effect = KeyEffect::Prepare;
  /// A number key's span (none: any value its check takes).
  std::optional<KeyRange> range = std::nullopt;
  /// An enumeration key's values, in its name table's order (else empty).
  std::vector<KeyChoice> choices = {};
  /// What a control of it is called (the viewer's panel, the page's
  /// sliders, ParaView's properties, title-cased): its name, with its unit.
  std::string_view label = {};
  /// Its name as a host's property (ParaView's, CamelCase: the plugin's XML
  /// property and its representation's Set<Host>, host_setting); empty:
  /// not one.
  std::string_view host = {};
};

/// Every key, in documentation order.
const std::vector<SceneKey>& scene_keys();
/// The key named `name`, or nullptr.
const SceneKey* find_scene_key(std::string_view name);
/// The key a host calls `host` (SceneKey::host), or nullptr.
const SceneKey* find_host_key(std::string_view host);
/// A host's number for `key` as the key's text form (set() takes it): a
/// number kept to the key's range (clamp_to_key_range), an enumeration's
/// number to the nearest of its values, a flag true where not 0, an integer
/// rounded. The key's own check still applies when set() reads it.
std::string host_setting(const SceneKey& key, double value);

/// Key `name`'s label (SceneKey::label; its name where the key has none,
/// or for a name that is no key).
std::string_view key_label(std::string_view name);
/// The effect of changing key `name` (Prepare for a name that is no key).
KeyEffect key_effect(std::string_view name);
/// The effect of a change of key `name` to its value in `next`: key_effect,
/// but a percentile range (or an unset one, p1,p99) needs the scalars again,
/// and a tangent mode an unsteady field's steps (`unsteady`): Prepare. One
/// rule for Session::set and the page's restyling.
KeyEffect change_effect(std::string_view name, const Scene& next, bool unsteady);
/// The keys whose values differ between two scenes, in table order.
std::vector<std::string_view> changed_keys(const Scene& before, const Scene& after);

/// What taking the scene `next` in place of `now` asks of a running
/// animation: the union of its changed keys' effects (change_effect). The
/// one rule every front end's change goes by (Session::set, HostFlow,
/// restyled, the page's header).
struct ChangePlan {
  bool prepare = false;  ///< a key needs the scene prepared again
  bool live = false;     ///< texture and display settings the next frame takes
  bool step = false;     ///< dt follows a new step
  bool regrid = false;   ///< a new noise scale: a new grid, the texture goes on
  bool reseed = false;   ///< a new seed: the texture starts afresh
  bool tangent = false;  ///< the field evaluated again
  bool camera = false;   ///< the view moves
  bool size = false;     ///< the image size
  /// Whether anything but keys read only as the animation runs changed.
  [[nodiscard]] bool any() const {
    return prepare || live || step || regrid || reseed || tangent || camera || size;
  }
  /// Whether the running animation can take it (nothing needs preparing).
  [[nodiscard]] bool takes() const { return !prepare; }
};
ChangePlan plan_change(const Scene& now, const Scene& next, bool unsteady);

/// The range of number key `name`; nullopt for a key that has none.
std::optional<KeyRange> key_range(std::string_view name);
/// `value` clamped to the range of `name` (a key that has one).
float clamp_to_key_range(std::string_view name, float value);

/// Sets one key from text. Throws SettingError(key, problem) for an unknown key
/// or a bad value.
void apply_setting(Scene& scene, std::string_view key, std::string_view text);

/// One key = value, as a scene file or a command line gives it.
struct Setting {
  std::string key;
  std::string text;   ///< the value's text form (${data} and ${scene} expanded)
  std::string where;  ///< "FILE:LINE" for a scene file's setting, empty otherwise
};

/// Applies settings in order; a `style` among them is applied first (its
/// defaults under everything else). Errors: SettingError, with `where` before
/// the key when the setting has one ("FILE:LINE: key: problem").
void apply_settings(Scene& scene, const std::vector<Setting>& settings);

// ------------------------------------------------------------ scene files

/// Reads a scene file's settings (TOML: every key a scene key, docs/scenes.md).
/// "${data}" is the fetched-data folder, "${scene}" the file's folder. Throws
/// InputError "FILE:LINE: ..." for a syntax error, an unknown key or a value of
/// the wrong type.
std::vector<Setting> read_scene_settings(const std::filesystem::path& path);

/// A scene from a file: its style's defaults, then its keys.
Scene read_scene(const std::filesystem::path& path);

/// The scene as TOML: every key whose value differs from a default Scene's (the
/// style is not written: its effect is in the values). read_scene of the text
/// gives the same scene.
std::string scene_toml(const Scene& scene);

/// True for a path ending in .toml.
bool is_scene_path(std::string_view path);

// ------------------------------------------------------------ styles

/// Sets the style's defaults on `scene` (and records it in scene.style).
void apply_style(Scene& scene, Style style);

}  // namespace ibfvs
