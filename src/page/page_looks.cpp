// The page's looks: for each style over the same data, what the pass is
// compiled with (the GLSL ES 3.00 sources of its features) and set to.

#include <algorithm>
#include <optional>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/texture/noise.h"
#include "ibfvs/render/frame_plan.h"
#include "ibfvs/render/pass_settings.h"
#include "ibfvs/render/shaders.h"
#include "page_json.h"

namespace ibfvs::page {
namespace {

using T = shaders::UniformValue::Type;

Json uniforms_json(const std::vector<shaders::UniformValue>& uniforms) {
  Json out = Json::array();
  for (const auto& u : uniforms) {
    Json values = Json::array();
    for (const double v : u.values) {
      // Integers as integers: a uint32 seed stays exact.
      if (u.type == T::Float)
        values.push_back(static_cast<float>(v));
      else
        values.push_back(static_cast<std::int64_t>(v));
    }
    Json j = {{"name", u.name},
              {"type", u.type == T::Float ? "float"
                       : u.type == T::Int ? "int"
                                          : "uint"},
              {"values", std::move(values)}};
    if (u.array) j["array"] = true;
    out.push_back(std::move(j));
  }
  return out;
}

// What the plan's `when` reads of a look (frame_plan.h: pass_runs); the
// page never splits the IBFVS pass.
Json facts_json(const PassFacts& facts) {
  return {{"image_noise", facts.image_noise}, {"taps", facts.taps}, {"contrast", facts.contrast}};
}

// The look's own controls: four keys chosen here, the ones a page can take
// live (alpha and beta set their uniforms; the step sets the image-space
// step where the look normalises, else the speed scales its dt; the noise
// scale makes a coarser grid, the phases covering the look's own and finer
// ones only). They are not derived from the change plan (plan_change):
// the runtime takes these four alone. Each spans its key's range and is
// named by its label (the keys' table).
Json controls(const PreparedScene& q, const std::vector<shaders::UniformValue>& uniforms) {
  const auto has = [&](std::string_view name) {
    return std::any_of(uniforms.begin(), uniforms.end(),
                       [&](const auto& u) { return u.name == name; });
  };
  const auto control = [](std::string_view key, std::string_view acts, double value, double min,
                          double max, bool log) {
    return Json{{"key", key},   {"label", key_label(key)},
                {"acts", acts}, {"value", value},
                {"min", min},   {"max", max},
                {"log", log}};
  };
  Json out = Json::array();
  for (const std::string_view key : {"alpha", "beta"})
    if (has(std::string("u_") + std::string(key))) {
      const KeyRange r = *key_range(key);
      Json c = control(key, "uniform", key == "alpha" ? q.settings.alpha : q.settings.beta, r.min,
                       r.max, false);
      c["uniform"] = "u_" + std::string(key);
      out.push_back(std::move(c));
    }
  const KeyRange step = *key_range("step");
  if (has("u_image_step") && q.settings.image_step > 0.0f) {
    Json c = control("step", "uniform", q.settings.image_step,
                     std::max(step.min, step.max / 256.0f), step.max, true);
    c["uniform"] = "u_image_step";
    out.push_back(std::move(c));
  } else {
    Json c = control("speed", "dt", 1.0, 0.0, 4.0, false);
    c["label"] = "speed";
    out.push_back(std::move(c));
  }
  const float base = q.settings.noise.scale;
  out.push_back(
      control("scale", "grid", base, base, std::min(6.0f * base, key_range("scale")->max), false));
  return out;
}

// One look of the page: what the pass is compiled with and set to for one
// style over the same data. `finest`: the columns and rows of the page's
// noise phases (a coarser grid takes the first of them).
Json look(const PreparedScene& q, std::string_view name, std::string_view description,
          glm::ivec2 finest, glm::vec3 centre, bool moving) {
  const RenderSettings& s = q.settings;
  // Random-cell colours make F_t a colour texture, as in the renderer.
  const bool colour_texture =
      shaders::colour_background(s) || q.scene.init == InitMode::RandomCells;
  shaders::ShaderFeatures f =
      shaders::features_for(s, colour_texture, !q.surface_image.pixels.empty(), false);
  f.moving = moving;
  const NoiseGrid grid(q.width, q.height, s.noise);
  const glm::ivec2 phase_size = glm::min(glm::ivec2(grid.columns(), grid.rows()), finest);
  const std::vector<shaders::UniformValue> grid_uniforms = {
      {"u_profile", T::Int, {static_cast<double>(static_cast<int>(s.noise.profile))}},
      {"u_spike_width", T::Float, {s.noise.spike_width}},
      {"u_seed", T::Uint, {static_cast<double>(s.noise.seed)}}};
  using shaders::Dialect;
  const std::vector<shaders::UniformValue> uniforms =
      shaders::settings_uniforms(s, f, phase_size, centre);
  return {{"name", name},
          {"description", description},
          {"background", vec3(s.background)},
          {"dt", q.dt},
          {"noise_rate", s.noise.rate},
          {"colour_texture", colour_texture},
          {"texture_channels", shaders::texture_channels(f)},
          {"tap_texture", shaders::tap_texture(f)},
          {"facts", facts_json(pass_facts(f, false, 0))},
          {"advect_previous", s.advect_view == AdvectView::Previous},
          {"carry_surface", carries_surface(s.advect_view, s.field_frame)},
          {"phase_size", {phase_size.x, phase_size.y}},
          {"shaders",
           {{"vertex", shaders::ibfvs_vertex_source(f, Dialect::Es300)},
            {"fragment", shaders::ibfvs_fragment_source(f, Dialect::Es300)},
            {"stats_fragment", shaders::stats_fragment_source(!colour_texture, Dialect::Es300)},
            {"display_fragment", shaders::tap_texture(f)
                                     ? shaders::display_fragment_source(f, Dialect::Es300)
                                     : std::string()}}},
          {"uniforms", uniforms_json(uniforms)},
          {"controls", controls(q, uniforms)},
          {"grid_uniforms", uniforms_json(grid_uniforms)}};
}

// Whether two looks draw alike: all but their names.
bool same_look(Json a, Json b) {
  for (Json* j : {&a, &b}) {
    j->erase("name");
    j->erase("description");
  }
  return a == b;
}

}  // namespace

std::vector<Restyle> restyles(const PreparedScene& p) {
  std::vector<Restyle> out;
  for (const auto& e : enum_entries<Style>()) {
    try {
      if (std::optional<PreparedScene> q = restyled(p, e.value)) out.push_back({e, std::move(*q)});
    } catch (const SettingError&) {
      // a setting of the scene that this style's defaults make invalid: left out
    }
  }
  return out;
}

Json looks(const PreparedScene& p, const std::vector<Restyle>& styles, glm::ivec2 finest,
           glm::vec3 centre, bool moving) {
  Json out = Json::array();
  // Named by its style when it is that style's look, else "as rendered".
  const auto pure = std::find_if(styles.begin(), styles.end(), [&](const Restyle& r) {
    return p.scene.style && r.style.value == *p.scene.style;
  });
  Json own =
      look(p, "as rendered", "the settings the page was written with", finest, centre, moving);
  if (pure != styles.end() && same_look(look(pure->scene, "", "", finest, centre, moving), own)) {
    own["name"] = pure->style.name;
    own["description"] = pure->style.description;
  }
  out.push_back(std::move(own));
  // Random cells start F_t from colours of the look's own noise cells: one look.
  if (p.scene.init == InitMode::RandomCells) return out;
  for (const Restyle& r : styles) {
    Json next = look(r.scene, r.style.name, r.style.description, finest, centre, moving);
    if (std::none_of(out.begin(), out.end(), [&](const Json& l) { return same_look(l, next); }))
      out.push_back(std::move(next));
  }
  return out;
}

}  // namespace ibfvs::page
