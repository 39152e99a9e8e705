// The scene keys' rules beyond parsing (scene.h): the number keys' ranges,
// and what a running animation does when a key changes.
#include <algorithm>
#include <map>
#include <optional>
#include <string_view>
#include <vector>

#include "ibfvs/core/scene/scene.h"

namespace ibfvs {
namespace {

// The number keys' ranges (scene.h, KeyRange).
struct NamedRange {
  std::string_view name;
  KeyRange range;
};
constexpr NamedRange kKeyRanges[] = {
    {"alpha", {0.0f, 1.0f, true}},   {"beta", {0.0f, 1.0f, true}},
    {"scale", {1.0f, 64.0f, false}}, {"vg", {0.0f, 1.0f, false}},
    {"step", {0.0f, 64.0f, false}},  {"filter", {0.0f, 32.0f, true}},
    {"sharpen", {0.0f, 4.0f, true}}, {"contrast", {0.0f, 0.5f, true}},
};

}  // namespace

KeyEffect key_effect(std::string_view name) {
  using E = KeyEffect;
  static const std::map<std::string_view, KeyEffect> effects = {
      {"alpha", E::kLive},         {"beta", E::kLive},        {"vg", E::kLive},
      {"profile", E::kLive},       {"spike_width", E::kLive}, {"background", E::kLive},
      {"surface_color", E::kLive}, {"color_map", E::kLive},   {"color_range", E::kLive},
      {"beta_range", E::kLive},    {"advect_view", E::kLive}, {"inject", E::kLive},
      {"noise_space", E::kLive},   {"filter", E::kLive},      {"contrast", E::kLive},
      {"resample", E::kLive},      {"sharpen", E::kLive},     {"image_normalize", E::kLive},
      {"step", E::kStep},          {"scale", E::kNoise},      {"seed", E::kNoise},
      {"tangent", E::kTangent},    {"camera", E::kCamera},    {"look_at", E::kCamera},
      {"ortho", E::kCamera},       {"fov", E::kCamera},       {"orbit", E::kCamera},
      {"size", E::kSize},          {"frames", E::kNone},      {"frames_per_step", E::kNone},
      {"fps", E::kNone},           {"out", E::kNone},         {"texture_out", E::kNone},
      {"export", E::kNone},        {"quiet", E::kNone},       {"style", E::kNone},
  };
  const auto it = effects.find(name);
  return it == effects.end() ? E::kPrepare : it->second;
}

std::vector<std::string_view> changed_keys(const Scene& before, const Scene& after) {
  std::vector<std::string_view> out;
  for (const SceneKey& key : scene_keys())
    if (key.get(before) != key.get(after)) out.push_back(key.name);
  return out;
}

std::optional<KeyRange> key_range(std::string_view name) {
  for (const NamedRange& r : kKeyRanges)
    if (r.name == name) return r.range;
  return std::nullopt;
}

float clamp_to_key_range(std::string_view name, float value) {
  const std::optional<KeyRange> r = key_range(name);
  return r ? std::clamp(value, r->min, r->max) : value;
}

}  // namespace ibfvs
