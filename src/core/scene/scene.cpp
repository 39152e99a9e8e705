#include "ibfvs/core/scene/scene.h"

// Sections: the key table | settings | scene files | styles. The value
// types (GridScalar, Displacement, ScalarRange, TimeRange): scene_values.cpp.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>

#include <toml++/toml.h>

#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/core/support/data_paths.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/limits.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {

// ------------------------------------------------------------ the key table
namespace {

using Texts = std::vector<std::string>;

Texts one(std::string s) {
  return {std::move(s)};
}
Texts none() {
  return {};
}

float number(std::string_view t) {
  const double v = parse_number(t);
  if (!std::isfinite(static_cast<float>(v)))
    throw InputError("'" + std::string(t) + "' is out of range");
  return static_cast<float>(v);
}

bool flag(std::string_view t) {
  if (t == "true" || t == "1" || t.empty()) return true;
  if (t == "false" || t == "0") return false;
  throw InputError("expected true or false, got '" + std::string(t) + "'");
}

glm::vec3 colour(std::string_view t) {
  const glm::vec3 c = parse_vec3(t);
  for (int i = 0; i < 3; ++i)
    if (!(c[i] >= 0.0f && c[i] <= 1.0f))
      throw InputError("components must be in [0, 1], got '" + std::string(t) + "'");
  return c;
}

}  // namespace

// A default Scene, for "is this value the default?".
static const Scene& defaults() {
  static const Scene d;
  return d;
}

namespace {

// Shorthands for the table: a number member, an enum member.
#define IBFVS_NUMBER_KEY(NAME, HELP, CHECK, ...)                                     \
  SceneKey {                                                                         \
#NAME, KeyKind::Number, HELP,                                                      \
        [](Scene& s, std::string_view t) {                                             \
          const float v = number(t);                                                   \
          CHECK;                                                                       \
          s.NAME = v;                                                                  \
        },                                                                             \
        [](const Scene& s) {                                                           \
          return one(format_number(s.NAME));                                              \
        }, __VA_ARGS__ \
  }
#define IBFVS_ENUM_KEY(NAME, TYPE, HELP, ...)                                             \
  with_choices<TYPE>(                                                                     \
      SceneKey{#NAME, KeyKind::String, std::string(HELP) + ": " + enum_name_list<TYPE>(), \
               [](Scene& s, std::string_view t) { s.NAME = parse_enum<TYPE>(t); },        \
               [](const Scene& s) { return one(std::string(enum_name(s.NAME))); }, __VA_ARGS__})

// An enumeration key with its values from the enum's name table.
template <class E>
SceneKey with_choices(SceneKey key) {
  for (const EnumName<E>& e : enum_entries<E>())
    key.choices.push_back({static_cast<int>(e.value), e.name});
  return key;
}

void require(bool ok, const char* problem) {
  if (!ok) throw InputError(problem);
}

// Refuses a value outside the key's enforced range: "must be between MIN
// and MAX" (with " (off)" after a minimum that turns the effect off, and
// the unit after the maximum).
void require_in_range(std::string_view name, float v, bool min_is_off = false,
                      std::string_view unit = "") {
  const KeyRange r = *key_range(name);
  if (!(v >= r.min && v <= r.max))
    throw InputError("must be between " + format_number(r.min) + (min_is_off ? " (off)" : "") +
                     " and " + format_number(r.max) + std::string(unit));
}

std::vector<SceneKey> make_keys() {
  return {
      // ---- mesh
      {"mesh", KeyKind::String,
       "mesh file (.off .obj .ply .stl; " + dataset_extensions_text() +
           ", an OpenFOAM .foam or case folder; NAME_*.EXT a numbered series) or generated: "
           "landscape[:SEED[:CONTROLS[:RESOLUTION]]], "
           "relief:FILE:VAR:BOX[:SCALE[:RES]], globe[:LEVEL], torus[:R,r], "
           "cylinder[:RADIUS,LENGTH[,COUNT]]; empty: the demo",
       [](Scene& s, std::string_view t) { s.mesh = t; },
       [](const Scene& s) { return s.mesh.empty() ? none() : one(s.mesh); }},
      {"blocks", KeyKind::String,
       "NAME,NAME,...: blocks of a .vtm or patches of an OpenFOAM case, names or patterns with "
       "* and ?; default: all (OpenFOAM: every boundary patch)",
       [](Scene& s, std::string_view t) {
         s.blocks.clear();
         std::string text(t);
         for (std::size_t b = 0; b <= text.size();) {
           const std::size_t e = std::min(text.find(',', b), text.size());
           if (e > b) s.blocks.push_back(text.substr(b, e - b));
           b = e + 1;
         }
         require(!s.blocks.empty(), "expected NAME[,NAME...]");
       },
       [](const Scene& s) {
         std::string text;
         for (const std::string& b : s.blocks) text += (text.empty() ? "" : ",") + b;
         return s.blocks.empty() ? none() : one(text);
       }},
      {"subdivide", KeyKind::Integer, "Loop subdivision levels, 0..12 (as many as memory holds)",
       [](Scene& s, std::string_view t) {
         s.subdivide = static_cast<int>(parse_integer(t, 0, 12));
       },
       [](const Scene& s) { return one(std::to_string(s.subdivide)); }},
      {"up", KeyKind::Vector,
       "X,Y,Z or auto: the height axis (camera azimuth about it, elevation along it, gradient "
       "fields down it); auto: the mesh's thinnest axis. Default +Y",
       [](Scene& s, std::string_view t) {
         s.up_auto = t == "auto";
         if (s.up_auto) {
           s.up.reset();
           return;
         }
         const glm::vec3 v = parse_vec3(t);
         require(v != glm::vec3(0.0f), "the axis must not be zero");
         s.up = v;
       },
       [](const Scene& s) {
         return s.up_auto ? one("auto") : s.up ? one(format_vec3(*s.up)) : none();
       }},
      // ---- field
      {"field", KeyKind::String,
       "file[:ARRAY] | uniform:X,Y,Z | rotate:X,Y,Z | elements[:X,Y,Z] | "
       "principal:min|max[:X,Y,Z][:rot90][:smooth=K] | gradient:down|up[:X,Y,Z][:normalize] | "
       "wind:FILE[:UVAR:VVAR] | sample:FILE:ARRAY[:OFFSET]; default: file when the mesh has "
       "vectors, else default_field",
       [](Scene& s, std::string_view t) { s.field = FieldSpec::parse(t); },
       [](const Scene& s) { return s.field ? one(s.field->text()) : none(); }},
      {"default_field", KeyKind::String,
       "the field when none is given and the mesh has none (styles set it); default: "
       "gradient:down on landscapes and reliefs, else rotate:0,1,0",
       [](Scene& s, std::string_view t) { s.default_field = FieldSpec::parse(t); },
       [](const Scene& s) { return s.default_field ? one(s.default_field->text()) : none(); }},
      {"element", KeyKind::Elements,
       "repeatable: a potential-flow element AX,AY,AZ,BX,BY,BZ,ROTATIONAL,RADIAL,TANGENTIAL"
       "[,CORE] (4.1); implies field elements",
       [](Scene& s, std::string_view t) { s.elements.push_back(FlowElement::parse(t)); },
       [](const Scene& s) {
         Texts out;
         for (const FlowElement& e : s.elements) out.push_back(e.to_string());
         return out;
       }},
      IBFVS_ENUM_KEY(tangent, TangentMode, "how vectors with a normal part are used (3.8)",
                     KeyEffect::kTangent),
      {"time", KeyKind::Time,
       "time step from 0 (netCDF, a series: .pvd, OpenFOAM times, numbered files), or a range "
       "A:B played through, frames_per_step each; default: 0, or a whole series",
       [](Scene& s, std::string_view t) { s.time = TimeRange::parse(t); },
       [](const Scene& s) { return s.time ? one(s.time->to_string()) : none(); }},
      {"reverse", KeyKind::Flag,
       "negate the field: OpenFOAM's wallShearStress points against the near-wall flow",
       [](Scene& s, std::string_view t) { s.reverse = flag(t); },
       [](const Scene& s) { return s.reverse ? one("true") : none(); }},
      {"field_step", KeyKind::StringList,
       "repeatable: a mesh file (PLY vx vy vz, or a dataset with the field's array) that is one "
       "step of an unsteady field",
       [](Scene& s, std::string_view t) { s.field_steps.emplace_back(t); },
       [](const Scene& s) { return s.field_steps; }},
      {"frames_per_step", KeyKind::Integer, "frames from one time step to the next, 1..100000",
       [](Scene& s, std::string_view t) {
         s.frames_per_step = static_cast<int>(parse_integer(t, 1, 100000));
       },
       [](const Scene& s) { return one(std::to_string(s.frames_per_step)); }, KeyEffect::kNone},
      {"loop", KeyKind::Flag,
       "a series plays on from its last step back to its first; else it ends at its last step "
       "and holds it",
       [](Scene& s, std::string_view t) { s.loop = flag(t); },
       [](const Scene& s) { return s.loop ? one("true") : none(); }, KeyEffect::kNone},
      IBFVS_ENUM_KEY(field_frame, FieldFrame,
                     "what the field on a moving surface is relative to (docs/cfd.md)",
                     KeyEffect::kLive),
      // ---- scalars and colour
      {"scalar", KeyKind::StringList,
       "repeatable: NAME=FILE:VAR, a per-vertex scalar sampled from a netCDF lon/lat grid",
       [](Scene& s, std::string_view t) { s.scalars.push_back(GridScalar::parse(t)); },
       [](const Scene& s) {
         Texts out;
         for (const GridScalar& g : s.scalars) out.push_back(g.to_string());
         return out;
       }},
      {"displace", KeyKind::String, "NAME:FACTOR: move vertices along their normals",
       [](Scene& s, std::string_view t) { s.displace = Displacement::parse(t); },
       [](const Scene& s) { return s.displace ? one(s.displace->to_string()) : none(); }},
      {"color_by", KeyKind::String,
       "colour the surface by a per-vertex scalar: a mesh property or array (a vector array: its "
       "magnitude), speed, kmin, kmax, x, y, z (a leading - negates)",
       [](Scene& s, std::string_view t) { s.color_by = t; },
       [](const Scene& s) { return s.color_by.empty() ? none() : one(s.color_by); }},
      IBFVS_ENUM_KEY(color_map, ColorMap, "colour map for color_by", KeyEffect::kLive),
      {"color_range", KeyKind::Vector, "LO,HI or percentiles pA,pB; default p1,p99",
       [](Scene& s, std::string_view t) { s.color_range = ScalarRange::parse(t); },
       [](const Scene& s) { return s.color_range ? one(s.color_range->to_string()) : none(); },
       KeyEffect::kLive},
      {"beta_by", KeyKind::String, "modulate beta by a per-vertex scalar (names as color_by)",
       [](Scene& s, std::string_view t) { s.beta_by = t; },
       [](const Scene& s) { return s.beta_by.empty() ? none() : one(s.beta_by); }},
      {"beta_range", KeyKind::Vector,
       "LO,HI or pA,pB: beta is 0 at LO and beta at HI; default p1,p99",
       [](Scene& s, std::string_view t) { s.beta_range = ScalarRange::parse(t); },
       [](const Scene& s) { return s.beta_range ? one(s.beta_range->to_string()) : none(); },
       KeyEffect::kLive},
      {"surface_image", KeyKind::String,
       "an equirectangular PNG standing in for the surface colour",
       [](Scene& s, std::string_view t) { s.surface_image = t; },
       [](const Scene& s) { return s.surface_image.empty() ? none() : one(s.surface_image); }},
      // ---- texture
      IBFVS_NUMBER_KEY(alpha, "blend weight of fresh noise (eq. 5, 12), 0..1",
                       require_in_range("alpha", v), KeyEffect::kLive, KeyRange{0.0f, 1.0f, true}),
      IBFVS_NUMBER_KEY(beta, "texture against shading (eq. 11), 0..1", require_in_range("beta", v),
                       KeyEffect::kLive, KeyRange{0.0f, 1.0f, true}),
      IBFVS_NUMBER_KEY(scale, "noise grid spacing s in pixels (eq. 6), at least 1",
                       require(v >= 1.0f, "the noise scale must be at least 1 pixel"),
                       KeyEffect::kNoise, KeyRange{1.0f, 64.0f, false}),
      IBFVS_ENUM_KEY(profile, NoiseProfile, "time profile w (eq. 8)", KeyEffect::kLive),
      IBFVS_NUMBER_KEY(vg, "image-change rate v_g, noise periods per frame (eq. 8)", (void)v,
                       KeyEffect::kLive, KeyRange{0.0f, 1.0f, false}),
      IBFVS_NUMBER_KEY(spike_width, "fraction of the period a spike is on",
                       require(v > 0.0f && v <= 1.0f, "must be in (0, 1]"), KeyEffect::kLive),
      {"seed", KeyKind::Integer, "seed of the noise phases",
       [](Scene& s, std::string_view t) {
         s.seed = static_cast<std::uint32_t>(parse_integer(t, 0, 4294967295LL));
       },
       [](const Scene& s) { return one(std::to_string(s.seed)); }, KeyEffect::kNoise},
      IBFVS_NUMBER_KEY(step, "largest image-space displacement per frame in pixels (sets dt)",
                       require(v > 0.0f, "must be a positive number of pixels"), KeyEffect::kStep,
                       KeyRange{0.0f, 64.0f, false}),
      IBFVS_NUMBER_KEY(dt, "time step in world units per frame; > 0 overrides step",
                       require(v >= 0.0f, "must be a non-negative number")),
      {"image_normalize", KeyKind::Flag,
       "every moving point moves step pixels per frame (paper figure 2), whatever its speed; "
       "on by default (--no-image-normalize: the flow's own speeds, the fastest moving step "
       "pixels)",
       [](Scene& s, std::string_view t) { s.image_normalize = flag(t); },
       [](const Scene& s) { return one(s.image_normalize ? "true" : "false"); }, KeyEffect::kLive},
      IBFVS_ENUM_KEY(resample, Resample, "how F_t is sampled at t(x) each frame (eq. 13)",
                     KeyEffect::kLive),
      IBFVS_NUMBER_KEY(filter,
                       "display only: Gaussian filter along the curved streamline over F_t, "
                       "its length in pixels, 0..32 (0 off)",
                       require_in_range("filter", v, false, " pixels"), KeyEffect::kLive,
                       KeyRange{0.0f, 32.0f, true}),
      IBFVS_NUMBER_KEY(sharpen,
                       "display only: each filter tap plus k times its excess over its two "
                       "neighbours 1.5 pixels across the flow, 0..4 (0 off): thinner lines",
                       require_in_range("sharpen", v, true), KeyEffect::kLive,
                       KeyRange{0.0f, 4.0f, true}),
      IBFVS_NUMBER_KEY(contrast,
                       "display only: RMS contrast of the shown texture, mean 0.5, 0..0.5 (0: "
                       "as synthesised; section 3.4)",
                       require_in_range("contrast", v, true), KeyEffect::kLive,
                       KeyRange{0.0f, 0.5f, true}),
      IBFVS_ENUM_KEY(inject, InjectMode, "how noise enters the texture", KeyEffect::kLive),
      {"background", KeyKind::Vector, "background colour B, R,G,B in 0..1",
       [](Scene& s, std::string_view t) { s.background = colour(t); },
       [](const Scene& s) { return one(format_vec3(s.background)); }, KeyEffect::kLive},
      {"surface_color", KeyKind::Vector, "diffuse colour of the shaded surface, R,G,B",
       [](Scene& s, std::string_view t) { s.surface_color = colour(t); },
       [](const Scene& s) { return one(format_vec3(s.surface_color)); }, KeyEffect::kLive},
      IBFVS_ENUM_KEY(noise_space, NoiseSpace, "where the noise lives (3.6)", KeyEffect::kLive),
      IBFVS_ENUM_KEY(advect_view, AdvectView, "which view projects r - v dt (eq. 13)",
                     KeyEffect::kLive),
      IBFVS_ENUM_KEY(init, InitMode, "F_t at the start"),
      // ---- camera
      {"camera", KeyKind::Vector,
       "AZIMUTH,ELEVATION,DISTANCE: degrees about the vertical and above the horizon, distance "
       "in bounding-box diagonals (0 fits the mesh)",
       [](Scene& s, std::string_view t) {
         const glm::vec3 c = parse_vec3(t);
         require(c.z >= 0.0f, "the distance must not be negative");
         s.camera.azimuth_deg = c.x;
         s.camera.elevation_deg = c.y;
         s.camera.distance = c.z;
       },
       [](const Scene& s) {
         const glm::vec3 c(s.camera.azimuth_deg, s.camera.elevation_deg, s.camera.distance);
         return one(format_vec3(c));
       },
       KeyEffect::kCamera},
      {"look_at", KeyKind::Vector, "X,Y,Z: look-at point as an offset from the box centre",
       [](Scene& s, std::string_view t) { s.camera.target = parse_vec3(t); },
       [](const Scene& s) { return one(format_vec3(s.camera.target)); }, KeyEffect::kCamera},
      {"ortho", KeyKind::Flag, "orthographic instead of perspective projection",
       [](Scene& s, std::string_view t) { s.camera.orthographic = flag(t); },
       [](const Scene& s) { return s.camera.orthographic ? one("true") : none(); },
       KeyEffect::kCamera},
      {"fov", KeyKind::Number, "vertical field of view in degrees",
       [](Scene& s, std::string_view t) {
         const float v = number(t);
         require(v > 0.0f && v < 180.0f, "the field of view must be between 0 and 180 degrees");
         s.camera.fov_deg = v;
       },
       [](const Scene& s) { return one(format_number(s.camera.fov_deg)); }, KeyEffect::kCamera},
      IBFVS_NUMBER_KEY(orbit, "degrees per frame the camera turns about the vertical",
                       require(std::abs(v) <= 360.0f, "must be within -360..360 degrees per frame"),
                       KeyEffect::kCamera),
      {"lock_at", KeyKind::Time,
       "lock the texture after this many frames (3.7); -1 never; auto: once the texture has "
       "had time to cross the mesh",
       [](Scene& s, std::string_view t) {
         s.lock_at =
             t == "auto" ? Scene::kLockAuto : static_cast<int>(parse_integer(t, -1, 100000000));
       },
       [](const Scene& s) {
         return s.lock_at == Scene::kLockAuto ? one("auto") : one(std::to_string(s.lock_at));
       }},
      {"lock_camera", KeyKind::Vector, "AZIMUTH,ELEVATION,DISTANCE: the camera once locked",
       [](Scene& s, std::string_view t) {
         const glm::vec3 c = parse_vec3(t);
         require(c.z >= 0.0f, "the distance must not be negative");
         s.lock_camera = c;
       },
       [](const Scene& s) { return s.lock_camera ? one(format_vec3(*s.lock_camera)) : none(); }},
      // ---- output
      {"size", KeyKind::Size,
       "image size WxH (at most the GL implementation's largest image, and what memory holds)",
       [](Scene& s, std::string_view t) {
         const std::string text(t);
         const std::size_t x = text.find('x');
         int width = 0, height = 0;
         try {
           if (x == std::string::npos) throw InputError("");
           width = static_cast<int>(parse_integer(text.substr(0, x), 1, kMaxImageSide));
           height = static_cast<int>(parse_integer(text.substr(x + 1), 1, kMaxImageSide));
         } catch (const InputError&) {
           throw InputError("expected WxH with 1.." + std::to_string(kMaxImageSide) +
                            " pixels each, got " + excerpt(text));
         }
         check_memory(image_bytes(width, height), text + " pixels");
         s.width = width;
         s.height = height;
       },
       [](const Scene& s) { return one(std::to_string(s.width) + "x" + std::to_string(s.height)); },
       KeyEffect::kSize},
      {"frames", KeyKind::Integer,
       "frames to render, 1..1000000; 0: an automatic lock's frame plus 60",
       [](Scene& s, std::string_view t) {
         s.frames = static_cast<int>(parse_integer(t, 0, 1000000));
       },
       [](const Scene& s) { return one(std::to_string(s.frames)); }, KeyEffect::kNone},
      {"fps", KeyKind::Number, "frame rate of the video, (0, 1000]",
       [](Scene& s, std::string_view t) {
         const double v = parse_number(t);
         require(v > 0.0 && v <= 1000.0, "must be in (0, 1000]");
         s.fps = v;
       },
       [](const Scene& s) { return one(format_number(s.fps)); }, KeyEffect::kNone},
      {"out", KeyKind::String,
       "output: .mp4 .mkv .mov .avi .webm .gif, .png (last frame), a %04d .png pattern, or "
       ".html (a web page that animates the scene in the browser: docs/web.md)",
       [](Scene& s, std::string_view t) { s.out = t; },
       [](const Scene& s) { return s.out.empty() ? none() : one(s.out); }, KeyEffect::kNone},
      {"texture_out", KeyKind::String, "the texture F_t of the last frame, 16-bit PNG",
       [](Scene& s, std::string_view t) { s.texture_out = t; },
       [](const Scene& s) { return s.texture_out.empty() ? none() : one(s.texture_out); },
       KeyEffect::kNone},
      {"export", KeyKind::String,
       "FILE.obj|.gltf|.glb|.vtp: the mesh with the final texture (3.7); .vtp for ParaView; "
       "FILE.html: the scene's web page beside the other output",
       [](Scene& s, std::string_view t) { s.export_model = t; },
       [](const Scene& s) { return s.export_model.empty() ? none() : one(s.export_model); },
       KeyEffect::kNone},
      {"quiet", KeyKind::Flag, "no progress bar, no summary",
       [](Scene& s, std::string_view t) { s.quiet = flag(t); },
       [](const Scene& s) { return s.quiet ? one("true") : none(); }, KeyEffect::kNone},
      {"style", KeyKind::String,
       "defaults of one of the paper's looks, any other key overrides them: " +
           enum_name_list<Style>(),
       [](Scene& s, std::string_view t) { apply_style(s, parse_enum<Style>(t)); },
       [](const Scene&) { return none(); }, KeyEffect::kNone},
  };
}

#undef IBFVS_NUMBER_KEY
#undef IBFVS_ENUM_KEY

}  // namespace

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> keys = make_keys();
  return keys;
}

const SceneKey* find_scene_key(std::string_view name) {
  for (const SceneKey& k : scene_keys())
    if (k.name == name) return &k;
  return nullptr;
}

// ------------------------------------------------------------ settings

void apply_setting(Scene& scene, std::string_view key, std::string_view text) {
  const SceneKey* k = find_scene_key(key);
  if (!k) throw SettingError(std::string(key), "unknown setting");
  try {
    k->set(scene, text);
  } catch (const SettingError&) {
    throw;
  } catch (const InputError& e) {
    throw SettingError(std::string(key), e.what());
  }
}

void apply_settings(Scene& scene, const std::vector<Setting>& settings) {
  const auto apply = [&](const Setting& s) {
    try {
      apply_setting(scene, s.key, s.text);
    } catch (const SettingError& e) {
      if (s.where.empty()) throw;
      throw SettingError(s.key, e.problem() + " (" + s.where + ")");
    }
  };
  // The last style given sets the defaults; everything else overrides them.
  const Setting* style = nullptr;
  for (const Setting& s : settings)
    if (s.key == "style") style = &s;
  if (style) apply(*style);
  for (const Setting& s : settings)
    if (s.key != "style") apply(s);
}

// ------------------------------------------------------------ scene files
namespace {

// ${data}: the fetched-data folder; ${scene}: the scene file's folder.
std::string expand(std::string s, const std::filesystem::path& scene) {
  const auto replace = [&s](const std::string& token, const std::string& by) {
    for (std::size_t p = s.find(token); p != std::string::npos; p = s.find(token, p + by.size()))
      s.replace(p, token.size(), by);
  };
  replace("${data}", data_dir().string());
  const std::filesystem::path folder = scene.parent_path();
  replace("${scene}", folder.empty() ? std::string(".") : folder.string());
  return s;
}

std::string number_text(const toml::node& n) {
  if (n.is_integer()) return std::to_string(*n.value<std::int64_t>());
  return format_number(*n.value<double>());
}

// Appends `value` to `list`, with `separator` between items.
void append(std::string& list, const char* separator, const std::string& value) {
  if (!list.empty()) list += separator;
  list += value;
}

// A flow element written as a table {a, b, rotational, radial, tangential, core}.
std::string element_text(const toml::table& t, const std::string& at) {
  std::string text;
  for (const char* end : {"a", "b"}) {
    const toml::array* p = t[end].as_array();
    if (!p || p->size() != 3) throw InputError(at + ": element '" + end + "' must be [x, y, z]");
    for (const toml::node& c : *p) {
      if (!c.is_number()) throw InputError(at + ": element '" + end + "' must be [x, y, z]");
      append(text, ",", number_text(c));
    }
  }
  for (const char* s : {"rotational", "radial", "tangential"}) {
    const auto v = t[s];
    if (v && !v.is_number())
      throw InputError(at + ": element '" + std::string(s) + "' must be a number");
    append(text, ",", v ? number_text(*v.node()) : std::string("0"));
  }
  if (const auto core = t["core"]) {
    if (!core.is_number()) throw InputError(at + ": element 'core' must be a number");
    append(text, ",", number_text(*core.node()));
  }
  for (const auto& [k, unused] : t) {
    const std::string name(k.str());
    if (name != "a" && name != "b" && name != "rotational" && name != "radial" &&
        name != "tangential" && name != "core")
      throw InputError(at + ": unknown element key '" + name + "'");
  }
  return text;
}

}  // namespace

bool is_scene_path(std::string_view path) {
  return path.size() > 5 && path.substr(path.size() - 5) == ".toml";
}

std::vector<Setting> read_scene_settings(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string() + ": no such scene file");
  toml::table table;
  try {
    table = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw InputError(path.string() + ":" + std::to_string(e.source().begin.line) + ": " +
                     one_line(std::string(e.description())));
  }
  std::vector<Setting> out;
  for (const auto& [key_node, value] : table) {
    const std::string key(key_node.str());
    const std::string where = path.string() + ":" + std::to_string(value.source().begin.line);
    const SceneKey* k = find_scene_key(key);
    if (!k) throw InputError(where + ": unknown key " + excerpt(key) + " (see docs/scenes.md)");
    const auto wrong = [&](const char* expected) {
      throw InputError(where + ": " + excerpt(key) + " must be " + expected);
    };
    const auto add = [&](const std::string& text) { out.push_back({key, text, where}); };
    switch (k->kind) {
      case KeyKind::String:
        if (!value.is_string()) wrong("a string");
        add(expand(*value.value<std::string>(), path));
        break;
      case KeyKind::Integer:
        if (!value.is_integer()) wrong("an integer");
        add(number_text(value));
        break;
      case KeyKind::Number:
        if (!value.is_number()) wrong("a number");
        add(number_text(value));
        break;
      case KeyKind::Time:
        if (value.is_integer())
          add(number_text(value));
        else if (value.is_string())
          add(*value.value<std::string>());
        else
          wrong("an integer or a string");
        break;
      case KeyKind::Flag:
        if (!value.is_boolean()) wrong("true or false");
        add(*value.value<bool>() ? "true" : "false");
        break;
      case KeyKind::Vector:
      case KeyKind::Size: {
        if (value.is_string()) {
          add(*value.value<std::string>());
          break;
        }
        const toml::array* a = value.as_array();
        if (!a || a->empty()) wrong("an array of numbers or a string");
        std::string joined;
        for (const toml::node& n : *a) {
          if (!n.is_number()) wrong("an array of numbers or a string");
          append(joined, k->kind == KeyKind::Size ? "x" : ",", number_text(n));
        }
        add(joined);
        break;
      }
      case KeyKind::StringList: {
        if (value.is_string()) {
          add(expand(*value.value<std::string>(), path));
          break;
        }
        const toml::array* a = value.as_array();
        if (!a) wrong("a string or an array of strings");
        for (const toml::node& n : *a) {
          if (!n.is_string()) wrong("a string or an array of strings");
          add(expand(*n.value<std::string>(), path));
        }
        break;
      }
      case KeyKind::Elements: {
        const toml::array* a = value.as_array();
        if (!a) wrong("an array of tables {a, b, rotational, radial, tangential, core}");
        for (const toml::node& n : *a) {
          if (n.is_string()) {
            add(*n.value<std::string>());
            continue;
          }
          const toml::table* t = n.as_table();
          if (!t) wrong("an array of tables {a, b, rotational, radial, tangential, core}");
          add(element_text(*t, path.string() + ":" + std::to_string(n.source().begin.line)));
        }
        break;
      }
    }
  }
  return out;
}

Scene read_scene(const std::filesystem::path& path) {
  Scene scene;
  apply_settings(scene, read_scene_settings(path));
  return scene;
}

std::string scene_toml(const Scene& scene) {
  toml::table table;
  for (const SceneKey& k : scene_keys()) {
    const std::vector<std::string> texts = k.get(scene);
    if (texts.empty() || texts == k.get(defaults())) continue;
    const std::string key(k.name);
    const std::string& text = texts.front();
    switch (k.kind) {
      case KeyKind::Integer:
        table.insert_or_assign(
            key, static_cast<std::int64_t>(parse_integer(text, INT64_MIN + 1, INT64_MAX)));
        break;
      case KeyKind::Number:
        table.insert_or_assign(key, parse_number(text));
        break;
      case KeyKind::Flag:
        table.insert_or_assign(key, text == "true");
        break;
      case KeyKind::Size:
      case KeyKind::Vector: {
        // Numbers as a TOML array; other forms (auto, percentiles) as text.
        toml::array a;
        try {
          for (float v : parse_numbers(text)) a.push_back(static_cast<double>(v));
        } catch (const InputError&) {
          a.clear();
        }
        if (k.kind == KeyKind::Size) {
          const std::size_t x = text.find('x');
          a.clear();
          a.push_back(
              static_cast<std::int64_t>(parse_integer(text.substr(0, x), 1, kMaxImageSide)));
          a.push_back(
              static_cast<std::int64_t>(parse_integer(text.substr(x + 1), 1, kMaxImageSide)));
        }
        if (a.empty())
          table.insert_or_assign(key, text);
        else
          table.insert_or_assign(key, std::move(a));
        break;
      }
      case KeyKind::StringList:
      case KeyKind::Elements: {
        toml::array a;
        for (const std::string& t : texts) a.push_back(t);
        table.insert_or_assign(key, std::move(a));
        break;
      }
      case KeyKind::Time:
        if (text.find_first_not_of("0123456789-") == std::string::npos)
          table.insert_or_assign(key,
                                 static_cast<std::int64_t>(parse_integer(text, -1, INT64_MAX)));
        else
          table.insert_or_assign(key, text);
        break;
      case KeyKind::String:
        table.insert_or_assign(key, text);
        break;
    }
  }
  std::ostringstream out;
  out << "# an ibfvs scene (docs/scenes.md); render it with: ibfvs render THIS.toml\n"
      << table << "\n";
  return out.str();
}

// ------------------------------------------------------------ styles

namespace {

// The bronze and eroded looks: colour by a curvature (p5 to p95), texture
// only where the surface is more concave than its median (to p98).
void curvature_look(Scene& s, const char* field, const char* curvature, ColorMap map) {
  s.default_field = FieldSpec::parse(field);
  s.color_by = curvature;
  s.color_map = map;
  s.color_range = ScalarRange{true, 5.0f, 95.0f};
  s.beta_by = std::string("-") + curvature;
  s.beta_range = ScalarRange{true, 50.0f, 98.0f};
  s.beta = 0.7f;
}

}  // namespace

void apply_style(Scene& s, Style style) {
  s.style = style;
  switch (style) {
    case Style::Flow:
      // Figures 1, 5: dense moving texture, beta 0.5, grey background.
      s.beta = 0.5f;
      s.background = glm::vec3(0.5f);
      break;
    case Style::Crisp:
      // docs/quality.md: longer unbroken lines than the defaults at about
      // 1.3 times their cost per pixel.
      s.filter = 24.0f;  // the defaults' 16 -> 24
      break;
    case Style::Paper:
      // Section 5's look, and Table 1's cost: 4-pixel noise cells, the
      // square profile at v_g 0.02, the flow's own speed, no display stage.
      s.scale = 4.0f;
      s.profile = NoiseProfile::Square;
      s.vg = 0.02f;
      s.beta = 0.5f;
      s.step = 3.0f;
      s.resample = Resample::Linear;
      s.image_normalize = false;
      s.filter = 0.0f;
      s.sharpen = 0.0f;
      s.contrast = 0.0f;
      break;
    case Style::Particles:
      // Figure 8a: short spikes so that few grid values are bright, added
      // rather than blended, along kappa_min where the mesh has no field.
      s.profile = NoiseProfile::Spike;
      s.spike_width = 0.04f;
      s.scale = 4.0f;  // one particle per 4 x 4 pixels, as the paper's
      s.inject = InjectMode::Add;
      s.contrast = 0.0f;  // sparse bright spikes on the dark: no stretch to mean 0.5
      s.filter = 0.0f;    // the comet tails as they are
      s.sharpen = 0.0f;
      s.image_normalize = false;  // faster particles where the flow is faster
      s.step = 3.0f;
      s.resample = Resample::Linear;
      s.alpha = 0.08f;
      s.background = {0.05f, 0.05f, 0.08f};
      s.beta = 0.7f;
      s.default_field = FieldSpec::parse("principal:min:smooth=10");
      break;
    case Style::Principal:
      // Figure 8b: dense texture along the principal directions, signed along
      // +Y (section 4.2's sign rule), smoothed over about three edges so that
      // scanned meshes give coherent strokes.
      s.default_field = FieldSpec::parse("principal:min:0,1,0:smooth=10");
      s.beta = 0.6f;
      break;
    case Style::Bronze:
      // Figure 9, "a dirty surface has superficially been cleaned": colour by
      // kappa_max (patina in the hollows, metal on the ridges) and the dirt
      // texture only in the more concave half (-kappa_max from its median to
      // its 98th percentile), so the rest shows clean metal.
      curvature_look(s, "principal:min:smooth=10", "kmax", ColorMap::Bronze);
      break;
    case Style::Eroded:
      // Eroded stone (section 4.2): the same, parametrised by kappa_min.
      curvature_look(s, "principal:max:smooth=10", "kmin", ColorMap::Grey);
      break;
    case Style::Topology:
      // Figure 7: alpha 0, random colours per noise cell, flow downhill along
      // the mesh's own height axis, seen from straight above it; locked once
      // the colours have had time to travel from the summits to the basin
      // borders, then seen obliquely.
      s.alpha = 0.0f;
      s.init = InitMode::RandomCells;
      s.scale = 4.0f;     // the colour cells of the figure
      s.contrast = 0.0f;  // colours, not a grey texture
      s.filter = 0.0f;
      s.sharpen = 0.0f;
      s.image_normalize = false;
      s.resample = Resample::Linear;
      s.step = 3.0f;
      s.default_field = FieldSpec::parse("gradient:down:normalize");
      s.up_auto = true;
      s.up.reset();
      s.camera.azimuth_deg = 0.0f;
      s.camera.elevation_deg = 90.0f;
      s.camera.distance = 0.0f;
      s.lock_at = Scene::kLockAuto;
      s.lock_camera = glm::vec3(20.0f, 35.0f, 0.0f);
      s.frames = 0;
      s.beta = 0.85f;
      s.scale = 6.0f;
      break;
  }
}

}  // namespace ibfvs
