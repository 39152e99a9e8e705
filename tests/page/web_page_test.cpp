// The web page writer (docs/web.md) without a browser: what the page holds
// and what it refuses, in one line each. The browser test (web/test,
// Web.page) runs the pages.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "helpers.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/page/web_page.h"

namespace ibfvs {
namespace {

PreparedScene torus_scene() {
  Scene s;
  s.mesh = "torus";
  s.width = 64;
  s.height = 48;
  return prepare_scene(s);
}

// The page's parts: its header parsed, and its block decoded.
struct PageParts {
  nlohmann::json header;
  std::vector<std::uint8_t> block;
};

std::string between(const std::string& page, const std::string& open, const std::string& close) {
  const std::size_t a = page.find(open);
  if (a == std::string::npos) return {};
  const std::size_t b = page.find(close, a + open.size());
  return page.substr(a + open.size(), b - a - open.size());
}

PageParts parts(const std::string& page) {
  PageParts out;
  out.header = nlohmann::json::parse(
      between(page, "<script type=\"application/json\" id=\"ibfvs-scene\">", "</script>"));
  // RFC 4648 base64, white space between lines.
  const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::uint32_t bits = 0;
  int held = 0;
  for (const char c : between(page, "id=\"ibfvs-data\">", "</script>")) {
    const std::size_t v = digits.find(c);
    if (v == std::string::npos) continue;  // white space and padding
    bits = (bits << 6) | static_cast<std::uint32_t>(v);
    if ((held += 6) >= 8) {
      held -= 8;
      out.block.push_back(static_cast<std::uint8_t>(bits >> held));
    }
  }
  return out;
}

// Every array reference in a header (an object with an offset and a length).
void array_refs(const nlohmann::json& j, std::vector<nlohmann::json>& out) {
  if (j.is_object() && j.contains("offset") && j.contains("length")) out.push_back(j);
  if (j.is_structured())
    for (const auto& item : j) array_refs(item, out);
}

std::string what_throws(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(WebPage, HoldsTheSceneTheShadersAndTheRuntime) {
  const PreparedScene scene = torus_scene();
  if (!has_web_runtime()) {
    EXPECT_NE(what_throws([&] { (void)web_page(scene); }).find("without the browser runtime"),
              std::string::npos);
    GTEST_SKIP() << "built without the browser runtime";
  }
  WebPageReport report;
  const std::string page = web_page(scene, &report);
  EXPECT_EQ(report.page, page.size());
  EXPECT_GT(report.scene, 0u);
  EXPECT_GT(report.runtime, 1000u);
  EXPECT_NE(page.find("\"vertex_count\":" + std::to_string(scene.mesh->vertex_count())),
            std::string::npos);
  EXPECT_NE(page.find("\"index_count\":" + std::to_string(3 * scene.mesh->triangle_count())),
            std::string::npos);
  EXPECT_NE(page.find("\"width\":64,\"height\":48"), std::string::npos);
  EXPECT_NE(page.find("#version 300 es"), std::string::npos);
  EXPECT_NE(page.find("\"name\":\"u_alpha\""), std::string::npos);
  // The looks: the scene's own, then the styles that take the same data.
  EXPECT_NE(page.find("\"looks\":[{\"name\":\"as rendered\""), std::string::npos);
  for (const char* style : {"flow", "crisp", "paper"})
    EXPECT_NE(page.find("{\"name\":\"" + std::string(style) + "\""), std::string::npos) << style;
  for (const char* style : {"bronze", "topology", "particles"})
    EXPECT_EQ(page.find("{\"name\":\"" + std::string(style) + "\""), std::string::npos) << style;
  // One script element each for the header, the data and the runtime: no
  // "</script" inside any of them.
  std::size_t closings = 0;
  for (std::size_t at = page.find("</script"); at != std::string::npos;
       at = page.find("</script", at + 1))
    ++closings;
  EXPECT_EQ(closings, 3u);
}

// The notebook widget's parts are the page's own: its header and block,
// and its module is the runtime's other bundle (an ES module exporting
// anywidget's render), with the page's style sheet.
TEST(WebPage, TheWidgetsPartsAreThePagesHeaderAndBlock) {
  const PreparedScene scene = torus_scene();
  if (!has_web_runtime()) {
    EXPECT_EQ(web_widget_module(), nullptr);
    GTEST_SKIP() << "built without the browser runtime";
  }
  WebPageReport report;
  const WebPageParts widget = web_page_parts(scene, &report);
  const PageParts page = parts(web_page(scene));
  EXPECT_EQ(nlohmann::json::parse(widget.header), page.header);
  EXPECT_EQ(widget.block, page.block);
  EXPECT_EQ(report.scene, widget.block.size());
  EXPECT_EQ(widget.name, "torus");
  const std::string module = web_widget_module();
  EXPECT_NE(module.find("export"), std::string::npos);
  EXPECT_NE(module.find("render"), std::string::npos);
  EXPECT_NE(web_page(scene).find(std::string(web_page_style())), std::string::npos);
}

TEST(WebPage, AMovingSurfaceStoresTheMovingPointsOfEachStepOnce) {
  if (!has_web_runtime()) GTEST_SKIP() << "built without the browser runtime";
  // A square of two halves: the right half (x > 0.05) lifts at steps 2 and 3
  // (the same lift), the left half never moves; steps 0 and 1 are alike.
  const test::TempDir dir;
  for (int k = 0; k < 4; ++k) {
    TriMesh m = make_square(1.0f, 10);
    for (glm::vec3& p : m.positions)
      if (k >= 2 && p.x > 0.05f) p.z = 0.2f * p.x;
    compute_vertex_normals(m);
    m.vectors.assign(m.vertex_count(), glm::vec3(1, 0, 0));
    write_ply(m, dir / ("lift_" + std::to_string(k) + ".ply"));
  }
  Scene s;
  s.mesh = (dir / "lift_*.ply").string();
  s.width = 64;
  s.height = 48;
  const PreparedScene p = prepare_scene(s);
  WebPageReport report;
  const std::string page = web_page(p, &report);
  // The right half's points (x = 0.2, 0.4, ... 1.0) and the column next to
  // them (x = 0: its normals turn), 11 each.
  EXPECT_EQ(report.moving_vertices, 66u);
  EXPECT_EQ(report.motion_sets, 2u);  // steps 0-1 and 2-3
  EXPECT_GT(report.motion, 0u);
  EXPECT_LT(report.motion, 66u * 12u * 2u);  // less than its raw bytes (codec)
  // A screw a moving vertex and step, towards the next (a rigid lift: the
  // right half turns about the y axis at step 1 -> 2 and back at 3 -> 0).
  EXPECT_GT(report.screws, 0u);
  EXPECT_LT(report.screws, 66u * 24u * 4u);
  EXPECT_NE(page.find("\"sets\":[0,0,1,1]"), std::string::npos);
  EXPECT_NE(page.find("#define IBFVS_MOVING"), std::string::npos);
  EXPECT_NE(page.find("\"steps\":4"), std::string::npos);  // of the field
  EXPECT_EQ(page.find("\"scalars\""), std::string::npos);  // not coloured
  // Coloured by height, which changes at step 2: every step's colours, as
  // the session sets them; by x, which never changes: the first step's.
  s.color_by = "z";
  const std::string by_height = web_page(prepare_scene(s));
  EXPECT_NE(by_height.find("\"codec\":\"vertex\",\"stride\":8,\"elements\":" +
                           std::to_string(2 * 4 * p.mesh->vertex_count()) + ",\"steps\":4"),
            std::string::npos);
  s.color_by = "x";
  const std::string by_x = web_page(prepare_scene(s));
  EXPECT_NE(by_x.find("\"codec\":\"vertex\",\"stride\":8,\"elements\":" +
                      std::to_string(2 * p.mesh->vertex_count()) + ",\"steps\":1"),
            std::string::npos);
}

TEST(WebPage, AStyledSceneIsNamedByItsStyle) {
  if (!has_web_runtime()) GTEST_SKIP() << "built without the browser runtime";
  Scene s;
  s.mesh = "torus";
  s.width = 64;
  s.height = 48;
  apply_style(s, Style::Crisp);
  const std::string crisp = web_page(prepare_scene(s));
  EXPECT_NE(crisp.find("\"looks\":[{\"name\":\"crisp\""), std::string::npos);
  EXPECT_EQ(crisp.find("\"as rendered\""), std::string::npos);  // the same as crisp
  s.filter = 12.0f;  // a key crisp sets, changed: the page's own look and crisp's
  const std::string changed = web_page(prepare_scene(s));
  EXPECT_NE(changed.find("\"looks\":[{\"name\":\"as rendered\""), std::string::npos);
  EXPECT_NE(changed.find("{\"name\":\"crisp\""), std::string::npos);
}

TEST(WebPage, TopologyHoldsItsCellColoursAndItsLock) {
  if (!has_web_runtime()) GTEST_SKIP() << "built without the browser runtime";
  Scene s;
  s.mesh = "landscape:2:6";
  apply_style(s, Style::Topology);
  s.width = 64;
  s.height = 48;
  const PreparedScene p = prepare_scene(s);
  const std::string page = web_page(p);
  EXPECT_NE(page.find("\"cells\":{"), std::string::npos);
  EXPECT_NE(page.find("\"lock\":{\"frame\":" + std::to_string(p.lock_at) + ","), std::string::npos);
  // The cells are of the look's own noise scale: no other look.
  EXPECT_NE(page.find("\"looks\":[{\"name\":\"topology\""), std::string::npos);
  EXPECT_EQ(page.find("{\"name\":\"flow\""), std::string::npos);
  EXPECT_NE(web_page(torus_scene()).find("\"lock\":null"), std::string::npos);
}

// The header is JSON (whatever the mesh is called), and the block holds
// every array the header names, each where it says.
TEST(WebPage, TheHeaderIsJsonAndTheBlockHoldsItsArrays) {
  if (!has_web_runtime()) GTEST_SKIP() << "built without the browser runtime";
  PreparedScene scene = torus_scene();
  scene.mesh_name = "dir/b<i>\xff.off";        // markup, and a byte that is not UTF-8
  scene.settings.noise.seed = 4'000'000'001u;  // more digits than a float holds
  const std::string page = web_page(scene);
  const PageParts p = parts(page);
  EXPECT_EQ(p.header["format"], "ibfvs-page");
  EXPECT_EQ(p.header["name"], "b<i>\xEF\xBF\xBD");  // U+FFFD for the odd byte
  EXPECT_EQ(page.find("<i>"), std::string::npos);   // escaped in the title and the header
  EXPECT_NE(page.find("<title>b&lt;i&gt;"), std::string::npos);
  EXPECT_EQ(p.header["width"], 64);
  EXPECT_EQ(p.header["vertex_count"], scene.mesh->vertex_count());
  EXPECT_EQ(p.header["looks"][0]["uniforms"].size() > 0, true);
  // u_seed, an unsigned integer, exactly.
  bool seeded = false;
  for (const auto& u : p.header["looks"][0]["grid_uniforms"]) {
    if (u["name"] != "u_seed") continue;
    EXPECT_EQ(u["values"][0], 4'000'000'001u);
    seeded = true;
  }
  EXPECT_TRUE(seeded);
  // The frame's plan as far as the page runs it: in one piece, no host.
  std::vector<std::string> passes;
  for (const auto& pass : p.header["plan"]) passes.push_back(pass["name"]);
  EXPECT_EQ(passes, (std::vector<std::string>{"grid", "ibfvs", "display", "stats"}));
  EXPECT_EQ(p.header["plan"][1]["reads"][0]["sampler"], "u_previous");
  EXPECT_EQ(p.header["plan"][1]["reads"][0]["image"], "texture.last");
  std::vector<nlohmann::json> refs;
  array_refs(p.header["arrays"], refs);
  ASSERT_EQ(refs.size(), 6u);  // positions, normals, vectors, indices, phases, colours
  for (const auto& r : refs) {
    EXPECT_EQ(r["offset"].get<std::size_t>() % 4, 0u) << r;
    EXPECT_LE(r["offset"].get<std::size_t>() + r["length"].get<std::size_t>(), p.block.size()) << r;
  }
  // The colour map: 256 RGBA colours, stored as they are.
  const auto& colours = p.header["arrays"]["color_map"];
  ASSERT_EQ(colours["length"], 1024);
  EXPECT_EQ(p.block[colours["offset"].get<std::size_t>() + 3], 255);  // opaque
  // The phases: the grid's columns x rows, in 16 bits.
  const auto& phases = p.header["arrays"]["phases"];
  EXPECT_EQ(phases["length"].get<int>(),
            p.header["phase_size"][0].get<int>() * p.header["phase_size"][1].get<int>());
}

// The page's sliders come from its header: each look's controls, by the
// library's rules (the step is image-space where the look normalises, else
// a speed on its dt), named and spanned by the keys' table.
TEST(WebPage, EachLookCarriesItsControlsByTheKeysTable) {
  if (!has_web_runtime()) GTEST_SKIP() << "built without the browser runtime";
  const PageParts normalised = parts(web_page(torus_scene()));
  Scene s;
  s.mesh = "torus";
  s.width = 64;
  s.height = 48;
  s.image_normalize = false;
  const PageParts by_dt = parts(web_page(prepare_scene(s)));
  const auto keys = [](const nlohmann::json& look) {
    std::vector<std::string> out;
    for (const auto& c : look["controls"]) {
      out.push_back(c["key"]);
      if (c["key"] == "speed") continue;  // a factor, not a key
      const std::string key = c["key"];
      EXPECT_EQ(c["label"], std::string(key_label(key))) << key;
      EXPECT_GE(c["min"].get<float>(), key_range(key)->min) << key;
      EXPECT_LE(c["max"].get<float>(), key_range(key)->max) << key;
      EXPECT_GE(c["value"].get<float>(), c["min"].get<float>()) << key;
      EXPECT_LE(c["value"].get<float>(), c["max"].get<float>()) << key;
    }
    return out;
  };
  const nlohmann::json& look = normalised.header["looks"][0];
  EXPECT_EQ(keys(look), (std::vector<std::string>{"alpha", "beta", "step", "scale"}));
  EXPECT_EQ(look["controls"][2]["acts"], "uniform");
  EXPECT_EQ(look["controls"][2]["uniform"], "u_image_step");
  EXPECT_EQ(look["controls"][2]["label"], "step (pixels)");
  EXPECT_EQ(look["controls"][3]["acts"], "grid");
  EXPECT_EQ(keys(by_dt.header["looks"][0]),
            (std::vector<std::string>{"alpha", "beta", "speed", "scale"}));
  EXPECT_EQ(by_dt.header["looks"][0]["controls"][2]["acts"], "dt");
  // Every key has a label; a unit where its name alone would not say it.
  for (const SceneKey& key : scene_keys()) EXPECT_FALSE(key.label.empty()) << key.name;
  EXPECT_EQ(key_label("scale"), "noise scale (pixels)");
  EXPECT_EQ(key_label("alpha"), "alpha");
}

TEST(WebPage, RefusesWhatIsTooBigAndNamesWithoutHtml) {
  const PreparedScene scene = torus_scene();
  if (!has_web_runtime()) GTEST_SKIP() << "built without the browser runtime";
  WebPageLimits few_triangles;
  few_triangles.triangles = 10;
  EXPECT_NE(what_throws([&] {
              (void)web_page(scene, nullptr, few_triangles);
            }).find("triangles, more than a page takes (10)"),
            std::string::npos);
  WebPageLimits few_vectors;
  few_vectors.vectors = 10;
  EXPECT_NE(what_throws([&] {
              (void)web_page(scene, nullptr, few_vectors);
            }).find("vectors, more than a page takes (10 vectors)"),
            std::string::npos);
  const std::filesystem::path png = std::filesystem::temp_directory_path() / "ibfvs-page.png";
  EXPECT_NE(what_throws([&] { (void)write_web_page(scene, png); }).find("must be named NAME.html"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(png));
}

}  // namespace
}  // namespace ibfvs
