// The frame plan (frame_plan.h) against the passes' GLSL: every sampler a
// pass's sources declare is planned, at the unit the sources bind it to,
// and every planned read is a sampler of some feature set's sources.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "helpers.h"
#include "ibfvs/render/frame_plan.h"
#include "ibfvs/render/pass_settings.h"
#include "ibfvs/render/shaders.h"

namespace ibfvs {
namespace {

using shaders::ShaderFeatures;

// The samplers a pass's sources declare, with the units they bind them
// to: the sources preprocessed as the GLSL compiler would (the C
// preprocessor, without #version: GLSL's preprocessor is C's), so that a
// sampler under a feature that is off does not count.
std::map<std::string, int> samplers(const std::vector<std::string>& sources) {
  static int count = 0;
  const test::TempDir dir;
  std::map<std::string, int> out;
  for (const std::string& s : sources) {
    const std::filesystem::path in = dir.path() / ("s" + std::to_string(++count) + ".c");
    const std::filesystem::path pre = dir.path() / "pre.txt";
    std::ofstream(in) << std::regex_replace(s, std::regex("#(version|extension)[^\n]*"), "");
    const std::string command =
        "cpp -P -undef -nostdinc '" + in.string() + "' > '" + pre.string() + "' 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << test::read_file(pre);
    const std::string text = test::read_file(pre);
    const std::regex binding(R"(layout\(binding = (\d+)\)\s+uniform\s+\w+\s+(\w+))");
    for (std::sregex_iterator it(text.begin(), text.end(), binding), end; it != end; ++it)
      out[(*it)[2].str()] = std::stoi((*it)[1].str());
  }
  return out;
}

// Feature sets that between them use every sampler: grey and colour F_t,
// with and without a surface image, the tap texture (filter, sharpening),
// the contrast stage, a moving surface and colour by a scalar.
std::vector<ShaderFeatures> feature_sets() {
  std::vector<ShaderFeatures> out;
  for (int bits = 0; bits < 64; ++bits) {
    ShaderFeatures f;
    f.mono_texture = bits & 1;
    f.surface_image = bits & 2;
    f.sharpen = f.contrast = bits & 4;
    f.filter_taps = bits & 8 ? 8 : 0;
    f.moving = bits & 16;
    f.color_scalar = bits & 32;
    f.image_step = f.cubic = true;
    out.push_back(f);
  }
  return out;
}

TEST(FramePlan, EverySamplerOfEveryPassIsPlannedAtItsUnit) {
  std::map<std::string, std::set<std::string>> seen;  // pass -> samplers some source declares
  const auto check = [&](std::string_view pass, const std::vector<std::string>& sources) {
    const PlannedPass& plan = planned_pass(pass);
    for (const auto& [sampler, unit] : samplers(sources)) {
      const auto read =
          std::find_if(plan.reads.begin(), plan.reads.end(),
                       [&, name = sampler](const PlannedRead& r) { return r.sampler == name; });
      ASSERT_NE(read, plan.reads.end()) << pass << " reads " << sampler << ", not in the plan";
      EXPECT_EQ(read->unit, unit) << pass << " " << sampler;
      seen[std::string(pass)].insert(sampler);
    }
  };
  check("grid", {shaders::grid_vertex_source(), shaders::grid_fragment_source()});
  for (const bool grey : {false, true})
    check("stats", {shaders::grid_vertex_source(), shaders::stats_fragment_source(grey)});
  check("host", {shaders::grid_vertex_source(), shaders::host_fragment_source()});
  for (const ShaderFeatures& f : feature_sets()) {
    const std::string vertex = shaders::ibfvs_vertex_source(f);
    check("ibfvs", {vertex, shaders::ibfvs_fragment_source(f)});
    if (shaders::deferred_pass(f)) {
      check("ibfvs", {vertex, shaders::gbuffer_fragment_source(f)});
      check("resolve", {shaders::display_vertex_source(), shaders::resolve_fragment_source(f)});
    }
    if (shaders::tap_texture(f))
      check("display", {shaders::display_vertex_source(), shaders::display_fragment_source(f)});
  }
  // No planned read that no source declares.
  for (const PlannedPass& pass : frame_plan())
    for (const PlannedRead& r : pass.reads)
      EXPECT_TRUE(seen[std::string(pass.name)].count(std::string(r.sampler)))
          << pass.name << " plans " << r.sampler << ", which none of its sources declares";
}

TEST(FramePlan, PassesRunInTheOrderOfTheFrame) {
  std::vector<std::string_view> names;
  for (const PlannedPass& p : frame_plan()) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string_view>{"grid", "ibfvs", "resolve", "display", "stats",
                                                  "host"}));
  EXPECT_THROW((void)planned_pass("nothing"), std::out_of_range);
}

// When a pass runs is one rule over the look's facts (the renderer's frame
// and the page's runtime both follow it): which passes a frame runs for the
// default look, the solid noise, a look without the display filter, and the
// contrast statistics' frames.
TEST(FramePlan, APassRunsWhereItsWhenHoldsForTheLook) {
  const auto runs = [](const PassFacts& facts) {
    std::vector<std::string_view> out;
    for (const PlannedPass& p : frame_plan())
      if (pass_runs(p.when, facts)) out.push_back(p.name);
    return out;
  };
  RenderSettings settings;  // grey, the display filter and sharpening on: a tap texture
  settings.filter_length = 6.0f;
  settings.sharpen = 0.5f;
  settings.contrast = 0.2f;
  const shaders::ShaderFeatures look = shaders::features_for(settings, false, false, false);
  ASSERT_TRUE(shaders::tap_texture(look));
  EXPECT_EQ(runs(pass_facts(look, true, 8)),
            (std::vector<std::string_view>{"grid", "ibfvs", "resolve", "display", "stats"}));
  EXPECT_EQ(runs(pass_facts(look, false, 9)),
            (std::vector<std::string_view>{"grid", "ibfvs", "display"}));
  settings.object_noise = true;
  settings.filter_length = 0.0f;
  settings.contrast = 0.0f;
  EXPECT_EQ(runs(pass_facts(shaders::features_for(settings, false, false, false), false, 8)),
            (std::vector<std::string_view>{"ibfvs"}));
  // No condition the plan names is unknown to the rule (an unknown one never runs).
  for (const PlannedPass& p : frame_plan())
    EXPECT_TRUE(p.when.empty() || p.when == "image_noise" || p.when == "deferred" ||
                p.when == "taps" || p.when == "contrast" || p.when == "host")
        << p.when;
}

}  // namespace
}  // namespace ibfvs
