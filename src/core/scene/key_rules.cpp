// The scene keys' rules beyond parsing (scene.h): what a running animation
// does when a key changes, and the number keys' ranges, each read from the
// key's entry in the one table (scene_keys(), scene_keys.cpp).
#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {

std::string_view key_label(std::string_view name) {
  const SceneKey* key = find_scene_key(name);
  return key ? key->label : name;
}

KeyEffect key_effect(std::string_view name) {
  const SceneKey* key = find_scene_key(name);
  return key ? key->effect : KeyEffect::Prepare;
}

KeyEffect change_effect(std::string_view name, const Scene& next, bool unsteady) {
  const auto by_percentile = [](const std::optional<ScalarRange>& r) {
    return !r || r->percentile;
  };
  const KeyEffect effect = key_effect(name);
  if ((name == "color_range" && by_percentile(next.color_range)) ||
      (name == "beta_range" && by_percentile(next.beta_range)) ||
      (effect == KeyEffect::Tangent && unsteady))
    return KeyEffect::Prepare;
  return effect;
}

std::vector<std::string_view> changed_keys(const Scene& before, const Scene& after) {
  std::vector<std::string_view> out;
  for (const SceneKey& key : scene_keys())
    if (key.get(before) != key.get(after)) out.push_back(key.name);
  return out;
}

ChangePlan plan_change(const Scene& now, const Scene& next, bool unsteady) {
  ChangePlan plan;
  for (const std::string_view key : changed_keys(now, next)) {
    switch (change_effect(key, next, unsteady)) {
      case KeyEffect::Live:
        plan.live = true;
        break;
      case KeyEffect::Step:
        plan.step = true;
        break;
      case KeyEffect::Noise:
        (key == "seed" ? plan.reseed : plan.regrid) = true;
        break;
      case KeyEffect::Tangent:
        plan.tangent = true;
        break;
      case KeyEffect::Camera:
        plan.camera = true;
        break;
      case KeyEffect::Size:
        plan.size = true;
        break;
      case KeyEffect::None:
        break;
      case KeyEffect::Prepare:
        plan.prepare = true;
        break;
    }
  }
  return plan;
}

std::optional<KeyRange> key_range(std::string_view name) {
  const SceneKey* key = find_scene_key(name);
  return key ? key->range : std::nullopt;
}

float clamp_to_key_range(std::string_view name, float value) {
  const std::optional<KeyRange> r = key_range(name);
  return r ? std::clamp(value, r->min, r->max) : value;
}

std::string host_setting(const SceneKey& key, double value) {
  if (!key.choices.empty()) {
    const auto by_distance = [&](const KeyChoice& a, const KeyChoice& b) {
      return std::abs(a.value - value) < std::abs(b.value - value);
    };
    return std::string(std::min_element(key.choices.begin(), key.choices.end(), by_distance)->name);
  }
  switch (key.kind) {
    case KeyKind::Flag:
      return value != 0.0 ? "true" : "false";
    case KeyKind::Integer:
      return std::abs(value) < 9.0e18 ? std::to_string(std::llround(value)) : format_number(value);
    case KeyKind::Number:
      return format_number(clamp_to_key_range(key.name, static_cast<float>(value)));
    default:
      throw InputError(std::string(key.name) + ": not a number a host sets");
  }
}

}  // namespace ibfvs
