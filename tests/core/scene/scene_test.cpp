// The typed scene: every key reads back what it writes, scene files round-trip
// through TOML, styles sit under explicit settings, errors name the key (never
// a command-line flag), and the enum name tables drive parsing and printing.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "ibfvs/core/scene/render_settings.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/names.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {
namespace {

namespace fs = std::filesystem;

fs::path temp_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "ibfvs_scene_test";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

// A scene with every key away from its default.
Scene busy_scene() {
  Scene s;
  const std::vector<std::pair<const char*, const char*>> settings = {
      {"mesh", "data/meshes/cow.off"},
      {"subdivide", "2"},
      {"up", "0,0,1"},
      {"field", "principal:max:1,0,0:rot90:smooth=3"},
      {"default_field", "gradient:up:normalize"},
      {"element", "0,0,0,0,1,0,1,0.5,0.25"},
      {"element", "1,0,0,1,0,1,-1,2,0,0.1"},
      {"tangent", "3d"},
      {"time", "2:5"},
      {"blocks", "motorBike*,wing"},
      {"reverse", "true"},
      {"field_step", "a.ply"},
      {"field_step", "b.ply"},
      {"frames_per_step", "12"},
      {"loop", "true"},
      {"field_frame", "absolute"},
      {"scalar", "relief=data/earth/etopo20.cdf:ROSE"},
      {"displace", "relief:1e-05"},
      {"color_by", "-kmax"},
      {"color_map", "bronze"},
      {"color_range", "p5,p95"},
      {"beta_by", "speed"},
      {"beta_range", "0.25,2"},
      {"surface_image", "map.png"},
      {"alpha", "0.25"},
      {"beta", "0.75"},
      {"scale", "6"},
      {"profile", "spike"},
      {"vg", "0.05"},
      {"spike_width", "0.04"},
      {"seed", "7"},
      {"step", "2.5"},
      {"dt", "0.125"},
      {"resample", "linear"},
      {"filter", "4.5"},
      {"contrast", "0.15"},
      {"image_normalize", "false"},
      {"sharpen", "1.5"},
      {"inject", "add"},
      {"background", "0.1,0.2,0.3"},
      {"surface_color", "1,0.5,0"},
      {"noise_space", "object"},
      {"overlay", "topology"},
      {"feature_scale", "0.02"},
      {"min_strength", "1.5"},
      {"min_length", "3"},
      {"advect_view", "current"},
      {"init", "random-cells"},
      {"camera", "30,15,1.5"},
      {"look_at", "0.1,0,-0.2"},
      {"ortho", "true"},
      {"fov", "45"},
      {"orbit", "1.5"},
      {"lock_at", "40"},
      {"lock_camera", "20,35,0"},
      {"size", "320x200"},
      {"frames", "90"},
      {"fps", "24"},
      {"out", "x.mp4"},
      {"texture_out", "t.png"},
      {"export", "m.glb"},
      {"quiet", "true"},
  };
  for (const auto& [key, value] : settings) apply_setting(s, key, value);
  return s;
}

TEST(SceneKeys, EveryKeyIsSetByTheBusySceneAndReadsBack) {
  const Scene busy = busy_scene();
  for (const SceneKey& key : scene_keys()) {
    if (key.name == "style") continue;  // its effect is in the other values
    const std::vector<std::string> texts = key.get(busy);
    EXPECT_FALSE(texts.empty()) << key.name << " not covered by the busy scene";
    EXPECT_NE(texts, key.get(Scene{})) << key.name;
    // Setting the printed text on a fresh scene prints the same text.
    Scene again;
    for (const std::string& t : texts) key.set(again, t);
    EXPECT_EQ(key.get(again), texts) << key.name;
    EXPECT_FALSE(key.help.empty()) << key.name;
  }
}

// The rules for changing a key on a running animation (key_effect): every
// key is in the table; each live key is one that scene_settings carries to
// the renderer (its busy value gives other settings), and each key that
// scene_settings carries is live, a step or the noise grid.
TEST(SceneKeys, EveryKeyHasItsEffectAndTheLiveOnesReachTheRenderer) {
  const Scene busy = busy_scene();
  const RenderSettings plain = scene_settings(Scene{}, RenderSettings{});
  for (const SceneKey& key : scene_keys()) {
    Scene one;
    for (const std::string& t : key.get(busy)) key.set(one, t);
    const RenderSettings settings = scene_settings(one, RenderSettings{});
    const KeyEffect effect = key_effect(key.name);
    const bool percentile = (key.name == "color_range" || key.name == "beta_range") &&
                            key.get(busy).front().front() == 'p';
    if (effect == KeyEffect::Live && !percentile) {
      EXPECT_NE(settings, plain) << key.name << " is live but the renderer does not take it";
    } else if (effect != KeyEffect::Step && effect != KeyEffect::Noise) {
      EXPECT_EQ(settings, plain) << key.name << " reaches the renderer but is not live";
    }
  }
  EXPECT_EQ(key_effect("mesh"), KeyEffect::Prepare);
  EXPECT_EQ(key_effect("alpha"), KeyEffect::Live);
  EXPECT_EQ(key_effect("no such key"), KeyEffect::Prepare);
  Scene a, b;
  apply_setting(b, "filter", "8");
  apply_setting(b, "mesh", "torus");
  EXPECT_EQ(changed_keys(a, b), (std::vector<std::string_view>{"mesh", "filter"}));
}

// A change's effect: a range of values is live, a percentile range (or
// none, p1,p99) takes the scalars again; a tangent mode keeps a steady
// field's texture but an unsteady field's steps are evaluated again.
TEST(SceneKeys, APercentileRangeOrAnUnsteadyTangentPreparesAgain) {
  Scene s;
  apply_setting(s, "color_range", "0,2");
  EXPECT_EQ(change_effect("color_range", s, false), KeyEffect::Live);
  apply_setting(s, "color_range", "p5,p95");
  EXPECT_EQ(change_effect("color_range", s, false), KeyEffect::Prepare);
  EXPECT_EQ(change_effect("beta_range", Scene{}, false), KeyEffect::Prepare);  // unset: p1,p99
  EXPECT_EQ(change_effect("tangent", s, false), KeyEffect::Tangent);
  EXPECT_EQ(change_effect("tangent", s, true), KeyEffect::Prepare);
  EXPECT_EQ(change_effect("alpha", s, true), KeyEffect::Live);
}

// A host (ParaView) sets a key by its host name with a number: kept to the
// key's span, an enumeration's nearest value, a flag, an integer; the key's
// own check still refuses what it refuses. Host names are unique and each
// host key takes a number.
TEST(SceneKeys, AHostSetsAKeyByItsNumber) {
  std::set<std::string_view> hosts;
  for (const SceneKey& k : scene_keys()) {
    if (k.host.empty()) continue;
    EXPECT_TRUE(hosts.insert(k.host).second) << k.host;
    EXPECT_EQ(find_host_key(k.host), &k);
    Scene s;
    EXPECT_NO_THROW(apply_setting(s, k.name, host_setting(k, 1.0))) << k.name;
  }
  EXPECT_GE(hosts.size(), 13u);
  EXPECT_EQ(find_host_key(""), nullptr);
  EXPECT_EQ(find_host_key("alpha"), nullptr);  // a host name, not the key's
  const auto text = [](std::string_view host, double v) {
    return host_setting(*find_host_key(host), v);
  };
  EXPECT_EQ(text("Alpha", 0.25), "0.25");
  EXPECT_EQ(text("Alpha", 7.0), format_number(key_range("alpha")->max));
  EXPECT_EQ(text("StepPixels", -3.0), "0");  // 0 stops the texture
  int last = 0;  // an enumeration beyond its values: the nearest, its last
  for (const KeyChoice& c : find_host_key("TimeProfile")->choices) last = std::max(last, c.value);
  EXPECT_EQ(text("TimeProfile", 99.0), text("TimeProfile", last));
  EXPECT_EQ(text("ImageNormalize", 2.0), "true");
  EXPECT_EQ(text("ImageNormalize", 0.0), "false");
  EXPECT_EQ(text("Seed", 41.6), "42");
  Scene s;
  apply_setting(s, "profile", text("TimeProfile", static_cast<double>(NoiseProfile::Random)));
  EXPECT_EQ(s.profile, NoiseProfile::Random);
  EXPECT_THROW(apply_setting(s, "seed", text("Seed", -1.0)), SettingError);
  EXPECT_THROW(apply_setting(s, "seed", text("Seed", 1e30)), SettingError);
  EXPECT_THROW(apply_setting(s, "alpha", text("Alpha", std::nan(""))), SettingError);
  EXPECT_THROW(static_cast<void>(host_setting(*find_scene_key("mesh"), 1.0)), InputError);
}

TEST(SceneKeys, TomlRoundTrip) {
  const Scene busy = busy_scene();
  const std::string text = scene_toml(busy);
  const Scene back = read_scene(temp_file("busy.toml", text));
  for (const SceneKey& key : scene_keys())
    EXPECT_EQ(key.get(back), key.get(busy)) << key.name << "\n" << text;
  // A default scene writes no key.
  EXPECT_EQ(scene_toml(Scene{}).find('='), std::string::npos) << scene_toml(Scene{});
}

TEST(SceneKeys, ErrorsNameTheKeyAndNeverAFlag) {
  Scene s;
  const auto problem = [&](const char* key, const char* value) -> std::string {
    try {
      apply_setting(s, key, value);
    } catch (const SettingError& e) {
      EXPECT_EQ(e.key(), key);
      EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
      return e.problem();
    }
    ADD_FAILURE() << key << " = " << value << " was accepted";
    return "";
  };
  EXPECT_EQ(problem("alpha", "1.5"), "must be between 0 and 1");
  EXPECT_EQ(problem("profile", "triangle"),
            "expected square, sawtooth, sine, spike or random, got 'triangle'");
  EXPECT_EQ(problem("filter", "40"), "must be between 0 and 32 pixels");
  EXPECT_EQ(problem("resample", "nearest"), "expected compensated, cubic or linear, got 'nearest'");
  EXPECT_EQ(problem("color_map", "jet"), "expected viridis, coolwarm, grey or bronze, got 'jet'");
  EXPECT_NE(problem("size", "-5x10").find("expected WxH"), std::string::npos);
  EXPECT_NE(problem("field", "vortex:1").find("unknown field 'vortex:1'"), std::string::npos);
  EXPECT_NE(problem("element", "0,0,0,0,0,0,1,0,0").find("zero length"), std::string::npos);
  EXPECT_NE(problem("background", "2,0,0").find("[0, 1]"), std::string::npos);
  EXPECT_NE(problem("color_range", "p5,95").find("percentiles"), std::string::npos);
  EXPECT_NE(problem("time", "5:2").find("backwards"), std::string::npos);
  EXPECT_EQ(problem("alpah", "0.2"), "unknown setting");
  EXPECT_EQ(s.alpha, Scene{}.alpha);  // a refused value leaves the scene as it was
}

TEST(SceneKeys, StylesSitUnderExplicitSettings) {
  // The style comes first whatever its position; explicit keys win.
  Scene s;
  apply_settings(s, {{"beta", "0.3", ""}, {"style", "bronze", ""}});
  EXPECT_EQ(s.beta, 0.3f);
  EXPECT_EQ(s.color_map, ColorMap::Bronze);
  EXPECT_EQ(s.color_by, "kmax");
  ASSERT_TRUE(s.style);
  EXPECT_EQ(*s.style, Style::Bronze);
  // Every style has defaults that differ from a plain scene.
  for (const EnumName<Style>& style : enum_entries<Style>()) {
    Scene t;
    apply_style(t, style.value);
    if (style.value != Style::Flow) {
      EXPECT_NE(scene_toml(t), scene_toml(Scene{})) << style.name;
    }
  }
}

TEST(SceneFiles, BadFilesNameTheLine) {
  const auto message = [](const std::string& name, const std::string& text) -> std::string {
    try {
      apply_settings(*std::make_unique<Scene>(), read_scene_settings(temp_file(name, text)));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(
      message("u.toml", "mesh = \"a.off\"\n\nalpah = 0.2\n").find("u.toml:3: unknown key 'alpah'"),
      std::string::npos);
  EXPECT_NE(message("t.toml", "frames = \"many\"\n").find("t.toml:1: 'frames' must be an integer"),
            std::string::npos);
  EXPECT_EQ(message("v.toml", "alpha = 3\n").rfind("alpha: must be between 0 and 1 (", 0), 0u)
      << message("v.toml", "alpha = 3\n");
  EXPECT_NE(message("v.toml", "alpha = 3\n").find("/v.toml:1)"), std::string::npos)
      << message("v.toml", "alpha = 3\n");
  EXPECT_NE(message("e.toml", "[[element]]\na = [0, 0]\nb = [0, 0, 1]\n")
                .find("e.toml:1: element 'a' must be [x, y, z]"),
            std::string::npos)
      << message("e.toml", "[[element]]\na = [0, 0]\nb = [0, 0, 1]\n");
  EXPECT_THROW(read_scene_settings("/no/such/scene.toml"), InputError);
}

TEST(SceneFiles, PlaceholdersExpand) {
  const fs::path p = temp_file("place.toml", "mesh = \"${scene}/m.off\"\n");
  const Scene s = read_scene(p);
  EXPECT_EQ(s.mesh, p.parent_path().string() + "/m.off");
}

TEST(EnumNames, ParsePrintAndListComeFromOneTable) {
  EXPECT_EQ(parse_enum<ColorMap>("diverging"), ColorMap::CoolWarm);  // an alias
  EXPECT_EQ(enum_name(ColorMap::CoolWarm), "coolwarm");
  EXPECT_EQ(enum_name_list<ColorMap>(), "viridis, coolwarm, grey or bronze");
  EXPECT_EQ(enum_entries<Style>().size(), 8u);
  EXPECT_EQ(enum_index(NoiseProfile::Spike), 3);
  for (const EnumName<NoiseProfile>& e : enum_entries<NoiseProfile>())
    EXPECT_EQ(parse_enum<NoiseProfile>(e.name), e.value);
  // The keys' help lists every name of their enum, bronze included.
  EXPECT_NE(find_scene_key("color_map")->help.find("bronze"), std::string::npos);
  EXPECT_NE(find_scene_key("style")->help.find("topology"), std::string::npos);
}

}  // namespace
}  // namespace ibfvs
