#include "ibfvs/core/scene/scene.h"

// The scene keys' table (scene_keys(): every key's parsing, text form,
// effect on a running animation, range, choices and label) and settings by
// name. The scene files: scene_file.cpp; the styles: scene_styles.cpp; the
// keys' rules: key_rules.cpp; the value types (GridScalar, Displacement,
// ScalarRange, TimeRange): scene_values.cpp.

#include <algorithm>
#include <cmath>
#include <cstdint>

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

// A number of the topology's options (Scene::topology), checked as
// find_topology checks them; the overlay takes it at its next frame.
template <double TopologyOptions::*Field>
SceneKey topology_key(const char* name, const char* help) {
  return {name,
          KeyKind::Number,
          help,
          [](Scene& s, std::string_view t) {
            TopologyOptions o = s.topology;
            o.*Field = number(t);
            check_topology_options(o);
            s.topology = o;
          },
          [](const Scene& s) { return one(format_number(static_cast<float>(s.topology.*Field))); },
          KeyEffect::None};
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
                     KeyEffect::Tangent),
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
       [](const Scene& s) { return one(std::to_string(s.frames_per_step)); }, KeyEffect::None},
      {"loop", KeyKind::Flag,
       "a series plays on from its last step back to its first; else it ends at its last step "
       "and holds it",
       [](Scene& s, std::string_view t) { s.loop = flag(t); },
       [](const Scene& s) { return s.loop ? one("true") : none(); }, KeyEffect::None},
      IBFVS_ENUM_KEY(field_frame, FieldFrame,
                     "what the field on a moving surface is relative to (docs/cfd.md)",
                     KeyEffect::Live),
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
      IBFVS_ENUM_KEY(color_map, ColorMap, "colour map for color_by", KeyEffect::Live),
      {"color_range", KeyKind::Vector, "LO,HI or percentiles pA,pB; default p1,p99",
       [](Scene& s, std::string_view t) { s.color_range = ScalarRange::parse(t); },
       [](const Scene& s) { return s.color_range ? one(s.color_range->to_string()) : none(); },
       KeyEffect::Live},
      {"beta_by", KeyKind::String, "modulate beta by a per-vertex scalar (names as color_by)",
       [](Scene& s, std::string_view t) { s.beta_by = t; },
       [](const Scene& s) { return s.beta_by.empty() ? none() : one(s.beta_by); }},
      {"beta_range", KeyKind::Vector,
       "LO,HI or pA,pB: beta is 0 at LO and beta at HI; default p1,p99",
       [](Scene& s, std::string_view t) { s.beta_range = ScalarRange::parse(t); },
       [](const Scene& s) { return s.beta_range ? one(s.beta_range->to_string()) : none(); },
       KeyEffect::Live},
      {"surface_image", KeyKind::String,
       "an equirectangular PNG standing in for the surface colour",
       [](Scene& s, std::string_view t) { s.surface_image = t; },
       [](const Scene& s) { return s.surface_image.empty() ? none() : one(s.surface_image); }},
      // ---- texture
      IBFVS_NUMBER_KEY(alpha, "blend weight of fresh noise (eq. 5, 12), 0..1",
                       require_in_range("alpha", v), KeyEffect::Live, KeyRange{0.0f, 1.0f, true}),
      IBFVS_NUMBER_KEY(beta, "texture against shading (eq. 11), 0..1", require_in_range("beta", v),
                       KeyEffect::Live, KeyRange{0.0f, 1.0f, true}),
      IBFVS_NUMBER_KEY(scale, "noise grid spacing s in pixels (eq. 6), at least 1",
                       require(v >= 1.0f, "the noise scale must be at least 1 pixel"),
                       KeyEffect::Noise, KeyRange{1.0f, 64.0f, false}),
      IBFVS_ENUM_KEY(profile, NoiseProfile, "time profile w (eq. 8)", KeyEffect::Live),
      IBFVS_NUMBER_KEY(vg, "image-change rate v_g, noise periods per frame (eq. 8)", (void)v,
                       KeyEffect::Live, KeyRange{0.0f, 1.0f, false}),
      IBFVS_NUMBER_KEY(spike_width, "fraction of the period a spike is on",
                       require(v > 0.0f && v <= 1.0f, "must be in (0, 1]"), KeyEffect::Live),
      {"seed", KeyKind::Integer, "seed of the noise phases",
       [](Scene& s, std::string_view t) {
         s.seed = static_cast<std::uint32_t>(parse_integer(t, 0, 4294967295LL));
       },
       [](const Scene& s) { return one(std::to_string(s.seed)); }, KeyEffect::Noise},
      IBFVS_NUMBER_KEY(step,
                       "largest image-space displacement per frame in pixels (sets dt; 0 stops "
                       "the texture)",
                       require(v >= 0.0f, "must be 0 or a positive number of pixels"),
                       KeyEffect::Step, KeyRange{0.0f, 64.0f, false}),
      IBFVS_NUMBER_KEY(dt, "time step in world units per frame; > 0 overrides step",
                       require(v >= 0.0f, "must be a non-negative number")),
      {"image_normalize", KeyKind::Flag,
       "every moving point moves step pixels per frame (paper figure 2), whatever its speed; "
       "on by default (--no-image-normalize: the flow's own speeds, the fastest moving step "
       "pixels)",
       [](Scene& s, std::string_view t) { s.image_normalize = flag(t); },
       [](const Scene& s) { return one(s.image_normalize ? "true" : "false"); }, KeyEffect::Live},
      IBFVS_ENUM_KEY(resample, Resample, "how F_t is sampled at t(x) each frame (eq. 13)",
                     KeyEffect::Live),
      IBFVS_NUMBER_KEY(filter,
                       "display only: Gaussian filter along the curved streamline over F_t, "
                       "its length in pixels, 0..32 (0 off)",
                       require_in_range("filter", v, false, " pixels"), KeyEffect::Live,
                       KeyRange{0.0f, 32.0f, true}),
      IBFVS_NUMBER_KEY(sharpen,
                       "display only: each filter tap plus k times its excess over its two "
                       "neighbours 1.5 pixels across the flow, 0..4 (0 off): thinner lines",
                       require_in_range("sharpen", v, true), KeyEffect::Live,
                       KeyRange{0.0f, 4.0f, true}),
      IBFVS_NUMBER_KEY(contrast,
                       "display only: RMS contrast of the shown texture, mean 0.5, 0..0.5 (0: "
                       "as synthesised; section 3.4)",
                       require_in_range("contrast", v, true), KeyEffect::Live,
                       KeyRange{0.0f, 0.5f, true}),
      IBFVS_ENUM_KEY(inject, InjectMode, "how noise enters the texture", KeyEffect::Live),
      {"background", KeyKind::Vector, "background colour B, R,G,B in 0..1",
       [](Scene& s, std::string_view t) { s.background = colour(t); },
       [](const Scene& s) { return one(format_vec3(s.background)); }, KeyEffect::Live},
      {"surface_color", KeyKind::Vector, "diffuse colour of the shaded surface, R,G,B",
       [](Scene& s, std::string_view t) { s.surface_color = colour(t); },
       [](const Scene& s) { return one(format_vec3(s.surface_color)); }, KeyEffect::Live},
      IBFVS_ENUM_KEY(overlay, Overlay, "drawn over the texture", KeyEffect::None),
      topology_key<&TopologyOptions::scale>(
          "feature_scale",
          "the topology's significance scale, a fraction of the surface's size (its "
          "bounding box's diagonal): a saddle and a node or focus closer cancel; lines "
          "are measured in it"),
      topology_key<&TopologyOptions::min_strength>(
          "min_strength",
          "keep a topology line whose neighbours converge onto it (diverge from it) by "
          "at least e^N along it"),
      topology_key<&TopologyOptions::min_length>(
          "min_length", "keep a topology line at least this many feature scales long"),
      IBFVS_ENUM_KEY(noise_space, NoiseSpace, "where the noise lives (3.6)", KeyEffect::Live),
      IBFVS_ENUM_KEY(advect_view, AdvectView, "which view projects r - v dt (eq. 13)",
                     KeyEffect::Live),
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
       KeyEffect::Camera},
      {"look_at", KeyKind::Vector, "X,Y,Z: look-at point as an offset from the box centre",
       [](Scene& s, std::string_view t) { s.camera.target = parse_vec3(t); },
       [](const Scene& s) { return one(format_vec3(s.camera.target)); }, KeyEffect::Camera},
      {"ortho", KeyKind::Flag, "orthographic instead of perspective projection",
       [](Scene& s, std::string_view t) { s.camera.orthographic = flag(t); },
       [](const Scene& s) { return s.camera.orthographic ? one("true") : none(); },
       KeyEffect::Camera},
      {"fov", KeyKind::Number, "vertical field of view in degrees",
       [](Scene& s, std::string_view t) {
         const float v = number(t);
         require(v > 0.0f && v < 180.0f, "the field of view must be between 0 and 180 degrees");
         s.camera.fov_deg = v;
       },
       [](const Scene& s) { return one(format_number(s.camera.fov_deg)); }, KeyEffect::Camera},
      IBFVS_NUMBER_KEY(orbit, "degrees per frame the camera turns about the vertical",
                       require(std::abs(v) <= 360.0f, "must be within -360..360 degrees per frame"),
                       KeyEffect::Camera),
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
       KeyEffect::Size},
      {"frames", KeyKind::Integer,
       "frames to render, 1..1000000; 0: an automatic lock's frame plus 60",
       [](Scene& s, std::string_view t) {
         s.frames = static_cast<int>(parse_integer(t, 0, 1000000));
       },
       [](const Scene& s) { return one(std::to_string(s.frames)); }, KeyEffect::None},
      {"fps", KeyKind::Number, "frame rate of the video, (0, 1000]",
       [](Scene& s, std::string_view t) {
         const double v = parse_number(t);
         require(v > 0.0 && v <= 1000.0, "must be in (0, 1000]");
         s.fps = v;
       },
       [](const Scene& s) { return one(format_number(s.fps)); }, KeyEffect::None},
      {"out", KeyKind::String,
       "output: .mp4 .mkv .mov .avi .webm .gif, .png (last frame), a %04d .png pattern, or "
       ".html (a web page that animates the scene in the browser: docs/web.md)",
       [](Scene& s, std::string_view t) { s.out = t; },
       [](const Scene& s) { return s.out.empty() ? none() : one(s.out); }, KeyEffect::None},
      {"texture_out", KeyKind::String, "the texture F_t of the last frame, 16-bit PNG",
       [](Scene& s, std::string_view t) { s.texture_out = t; },
       [](const Scene& s) { return s.texture_out.empty() ? none() : one(s.texture_out); },
       KeyEffect::None},
      {"export", KeyKind::String,
       "FILE.obj|.gltf|.glb|.vtp: the mesh with the final texture (3.7); .vtp for ParaView; "
       "FILE.html: the scene's web page beside the other output",
       [](Scene& s, std::string_view t) { s.export_model = t; },
       [](const Scene& s) { return s.export_model.empty() ? none() : one(s.export_model); },
       KeyEffect::None},
      {"quiet", KeyKind::Flag, "no progress bar, no summary",
       [](Scene& s, std::string_view t) { s.quiet = flag(t); },
       [](const Scene& s) { return s.quiet ? one("true") : none(); }, KeyEffect::None},
      {"style", KeyKind::String,
       "defaults of one of the paper's looks, any other key overrides them: " +
           enum_name_list<Style>(),
       [](Scene& s, std::string_view t) { apply_style(s, parse_enum<Style>(t)); },
       [](const Scene&) { return none(); }, KeyEffect::None},
  };
}

#undef IBFVS_NUMBER_KEY
#undef IBFVS_ENUM_KEY

}  // namespace

namespace {

// The labels of the keys a control shows where the name alone would not
// say what it is (its unit, the paper's symbol).
// The labels and host names (SceneKey::label, host) of the keys that have them.
std::vector<SceneKey> named(std::vector<SceneKey> keys) {
  constexpr std::pair<std::string_view, std::string_view> kLabels[] = {
      {"scale", "noise scale (pixels)"},   {"step", "step (pixels)"},
      {"vg", "noise rate (v_g)"},          {"filter", "filter length (pixels)"},
      {"field_frame", "field frame"},      {"noise_space", "noise space"},
      {"profile", "time profile"},         {"color_map", "colour map"},
      {"surface_color", "surface colour"}, {"image_normalize", "normalize in image space"},
  };
  // ParaView's property names (and its representation's Set<Name>).
  constexpr std::pair<std::string_view, std::string_view> kHosts[] = {
      {"alpha", "Alpha"},
      {"beta", "Beta"},
      {"scale", "NoiseScale"},
      {"step", "StepPixels"},
      {"profile", "TimeProfile"},
      {"vg", "NoiseRate"},
      {"image_normalize", "ImageNormalize"},
      {"filter", "FilterLength"},
      {"contrast", "Contrast"},
      {"sharpen", "Sharpen"},
      {"resample", "Resample"},
      {"field_frame", "FieldFrame"},
      {"seed", "Seed"},
      {"overlay", "Overlay"},
  };
  for (SceneKey& key : keys) {
    key.label = key.name;
    for (const auto& [name, label] : kLabels)
      if (key.name == name) key.label = label;
    for (const auto& [name, host] : kHosts)
      if (key.name == name) key.host = host;
  }
  return keys;
}

}  // namespace

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> keys = named(make_keys());
  return keys;
}

const SceneKey* find_scene_key(std::string_view name) {
  for (const SceneKey& k : scene_keys())
    if (k.name == name) return &k;
  return nullptr;
}

const SceneKey* find_host_key(std::string_view host) {
  if (host.empty()) return nullptr;
  for (const SceneKey& k : scene_keys())
    if (k.host == host) return &k;
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

}  // namespace ibfvs
