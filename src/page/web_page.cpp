// The page writer (docs/web.md): the header as JSON in the shape of
// web/schema/page.schema.json (nlohmann-json), the binary block in base64
// (libb64), and the bundled runtime, in one HTML file.

#include "ibfvs/page/web_page.h"

#include <algorithm>
#include <fstream>

extern "C" {
#include <b64/cencode.h>
}

#include "ibfvs/core/fields/topology_morph.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/texture/display.h"
#include "ibfvs/core/texture/noise.h"
#include "ibfvs/render/frame_plan.h"
#include "ibfvs/render/overlay_geometry.h"
#include "ibfvs/render/pass_settings.h"
#include "ibfvs/render/shaders.h"
#include "page_json.h"

namespace ibfvs {

// The bundled runtime and the notebook widget's module, generated at build
// time (web_runtime.cpp, web_widget.cpp), or null.
extern const char* const kWebRuntime;
extern const char* const kWebWidget;

namespace {

using page::Json;

// The block in base64, in lines (the runtime drops the white space).
std::string base64(const std::vector<std::uint8_t>& bytes) {
  constexpr std::size_t kChunk = std::size_t{1} << 20;  // libb64 counts in int
  std::string out((bytes.size() + 2) / 3 * 4 * 74 / 72 + 8, '\0');
  base64_encodestate state;
  base64_init_encodestate(&state);
  std::size_t at = 0;
  for (std::size_t i = 0; i < bytes.size(); i += kChunk)
    at += static_cast<std::size_t>(base64_encode_block(
        reinterpret_cast<const char*>(bytes.data() + i),
        static_cast<int>(std::min(kChunk, bytes.size() - i)), out.data() + at, &state));
  at += static_cast<std::size_t>(base64_encode_blockend(out.data() + at, &state));
  out.resize(at);
  return out;
}

// JSON text for the page's script element: no "</script>" inside it ('<'
// appears only within strings, where \u003c reads back as '<'), and a file
// name that is not UTF-8 with its odd bytes replaced.
std::string script_json(const Json& j) {
  const std::string text = j.dump(-1, ' ', false, Json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size() + text.size() / 64);
  for (const char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

// The frame's plan (render/frame_plan.h) as far as the page runs it: not
// the deferred pass's halves (the page runs the pass in one piece) nor the
// host's.
Json plan() {
  Json out = Json::array();
  for (const PlannedPass& pass : frame_plan()) {
    if (pass.when == "deferred" || pass.when == "host") continue;
    Json reads = Json::array();
    for (const PlannedRead& r : pass.reads)
      reads.push_back({{"sampler", r.sampler}, {"image", r.image}});
    out.push_back({{"name", pass.name}, {"when", pass.when}, {"reads", std::move(reads)}});
  }
  return out;
}

// The number keys' spans, from the keys' table: the page's sliders span them.
Json ranges() {
  Json out = Json::object();
  for (const SceneKey& key : scene_keys())
    if (key.range)
      out[std::string(key.name)] = {
          {"min", key.range->min}, {"max", key.range->max}, {"enforced", key.range->enforced}};
  return out;
}

// The scene's overlay (render/topology_overlay.h): each step's quads, found
// on that step's surface and field as the Session finds them, moving into
// the next step's (the page loops: the last into the first) where the two
// steps share their points (topology_morph.h), ids carried from step to step.
Json overlay(const PreparedScene& p, const page::SceneSteps& d, page::Block& block) {
  if (p.scene.overlay != Overlay::Topology) return nullptr;
  const std::size_t n = d.data.size();
  std::vector<FlowTopology> found;
  int next_id = 0;
  for (std::size_t k = 0; k < n; ++k) {
    found.push_back(find_topology(step_surface(p, d.data[k]), d.data[k].field, p.scene.topology));
    if (k == 0)
      next_id = static_cast<int>(found[0].critical.points.size() + found[0].lines.lines.size());
    else
      carry_ids(found[k - 1], found[k], next_id, 2.0 * found[k - 1].lines.scale);
  }
  Json steps = Json::array();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t after = (k + 1) % n;
    const bool pair = after != k && !d.data[k].mesh && !d.data[after].mesh;
    TopologyMorph morph;
    if (!pair) {
      morph = hold(found[k]);
    } else if (after > k) {
      morph = morph_steps(found[k], found[after]);
    } else {  // the last into the first: the first's ids carried from the last
      FlowTopology first = found[after];
      int wrap_id = next_id;
      carry_ids(found[k], first, wrap_id, 2.0 * found[k].lines.scale);
      morph = morph_steps(found[k], first);
    }
    const OverlayGeometry g = build_overlay(morph, {p.width, p.height});
    std::vector<float> corners;
    corners.reserve(g.vertices.size() * kOverlayFloats);
    for (const OverlayVertex& v : g.vertices)
      corners.insert(
          corners.end(),
          {v.point.x,       v.point.y,       v.point.z,       v.other.x,       v.other.y,
           v.other.z,       v.corner.x,      v.corner.y,      v.colour.x,      v.colour.y,
           v.colour.z,      v.shape,         v.point_to.x,    v.point_to.y,    v.point_to.z,
           v.other_to.x,    v.other_to.y,    v.other_to.z,    v.point_bulge.x, v.point_bulge.y,
           v.point_bulge.z, v.other_bulge.x, v.other_bulge.y, v.other_bulge.z, v.span});
    // Through meshoptimizer's codecs: a quad's corners share most of their values.
    steps.push_back({{"vertices", block.add_vertices(corners, kOverlayFloats)},
                     {"indices", block.add_indices(g.indices, g.vertices.size())}});
  }
  const OverlaySizes sizes = overlay_sizes(p.height);
  return {{"vertex", shaders::overlay_vertex_source(shaders::Dialect::Es300)},
          {"fragment", shaders::overlay_fragment_source(shaders::Dialect::Es300)},
          {"line_width", sizes.line_width},
          {"glyph", sizes.glyph},
          {"lift", kOverlayLift},
          {"steps", std::move(steps)}};
}

}  // namespace

bool has_web_runtime() {
  return kWebRuntime != nullptr;
}

WebPageParts web_page_parts(const PreparedScene& p, WebPageReport* report,
                            const WebPageLimits& limits) {
  const std::string what = "page of " + p.mesh_name;
  if (!has_web_runtime())
    throw InputError(what +
                     ": this ibfvs was built without the browser runtime (it needs node "
                     "and npm at build time, and web/node_modules from "
                     "scripts/install-deps.sh)");
  const TriMesh& mesh = *p.mesh;
  if (mesh.triangle_count() > limits.triangles)
    throw InputError(what + ": " + std::to_string(mesh.triangle_count()) +
                     " triangles, more than a page takes (" + std::to_string(limits.triangles) +
                     "); subdivide less or decimate the mesh");
  const std::size_t steps = std::max<std::size_t>(p.step_count, 1);
  // Every step's data: a surface that moves (its points at each step) or
  // changes (a step with triangles of its own is a mesh of its own in the
  // page: step_mesh, 1.. for meshes[0..]; 0 for the first step's).
  page::SceneSteps d;
  d.data.resize(steps);
  d.step_mesh.assign(steps, 0);
  std::size_t other_meshes = 0, vectors_in_all = 0, triangles_in_all = mesh.triangle_count();
  for (std::size_t k = 0; k < steps; ++k) {
    if (p.step_data) d.data[k] = p.step_data(k);
    d.moving = d.moving || !d.data[k].positions.empty() || d.data[k].mesh;
    if (d.data[k].mesh) {
      d.step_mesh[k] = static_cast<int>(++other_meshes);
      vectors_in_all += d.data[k].mesh->vertex_count();
      triangles_in_all += d.data[k].mesh->triangle_count();
    }
  }
  vectors_in_all += steps * mesh.vertex_count();
  if (triangles_in_all > limits.triangles)
    throw InputError(what + ": " + std::to_string(triangles_in_all) +
                     " triangles over its steps' meshes, more than a page takes (" +
                     std::to_string(limits.triangles) + "); export fewer steps");
  if (vectors_in_all > limits.vectors)
    throw InputError(what + ": " + std::to_string(steps) + " time steps of " +
                     std::to_string(mesh.vertex_count()) + " vectors, more than a page takes (" +
                     std::to_string(limits.vectors) + " vectors); export fewer steps");
  // The first step's own data where it is not a series' (a steady scene).
  if (!p.step_data) d.data[0].field = p.field;

  // The noise phases of the finest look (the default's 1-pixel cells; a
  // coarser grid takes the first of them).
  const std::vector<page::Restyle> styles = page::restyles(p);
  NoiseParams finest_noise = p.settings.noise;
  for (const page::Restyle& r : styles)
    finest_noise.scale = std::min(finest_noise.scale, r.scene.settings.noise.scale);
  const NoiseGrid grid(p.width, p.height, finest_noise);
  const Bounds bounds = mesh_bounds(mesh);
  const float aspect = static_cast<float>(p.width) / static_cast<float>(p.height);
  const Camera camera(bounds, p.camera, aspect);
  // The box the positions are stored in: every step's points.
  d.lo = bounds.min;
  d.hi = bounds.max;
  for (const StepData& step : d.data)
    for (const glm::vec3& r : step.mesh ? step.mesh->positions : step.positions) {
      d.lo = glm::min(d.lo, r);
      d.hi = glm::max(d.hi, r);
    }
  page::Block block;
  Json arrays = page::arrays(p, d, grid.phases(), block, report);

  const glm::vec3 centre = bounds.centre();
  const std::string name = std::filesystem::path(p.mesh_name).stem().string();
  // The lock (Session::advance): at that frame F_t stops and the camera
  // moves to the lock view.
  Json lock = nullptr;
  if (p.lock_at >= 0) {
    const CameraParams& at = p.lock_camera.value_or(p.camera);
    const Camera lock_camera(bounds, at, aspect);
    lock = {{"frame", p.lock_at},
            {"view", page::matrix(lock_camera.view())},
            {"projection", page::matrix(lock_camera.projection())},
            {"target", page::vec3(centre + at.target)}};
  }
  // The orbit (Camera::orbit): degrees a frame about the vertical through
  // the look-at point.
  Json orbit = nullptr;
  if (p.scene.orbit != 0.0f) orbit = {{"degrees", p.scene.orbit}, {"up", page::vec3(p.camera.up)}};
  using shaders::Dialect;
  const Json header = {
      {"format", "ibfvs-page"},
      {"version", 2},
      {"name", name.empty() ? "ibfvs" : name},
      {"width", p.width},
      {"height", p.height},
      {"no_depth", frame::kNoDepth},
      {"any_depth", frame::kAnyDepth},
      {"lock", std::move(lock)},
      {"orbit", std::move(orbit)},
      {"target", page::vec3(centre + p.camera.target)},
      {"probe", shaders::probe_length(bounds.diagonal())},
      {"cull", closed_orientation(mesh)},
      {"stats",
       {{"size", display_stats_size(p.width, p.height)},
        {"every", frame::kStatsEvery},
        {"weight", frame::kStatsWeight}}},
      {"view", page::matrix(camera.view())},
      {"projection", page::matrix(camera.projection())},
      {"centre", page::vec3(centre)},
      {"shaders",
       {{"grid_vertex", shaders::grid_vertex_source(Dialect::Es300)},
        {"grid_fragment", shaders::grid_fragment_source(Dialect::Es300)},
        {"display_vertex", shaders::display_vertex_source(Dialect::Es300)}}},
      {"looks", page::looks(p, styles, glm::ivec2(grid.columns(), grid.rows()), centre, d.moving)},
      {"vertex_count", mesh.vertex_count()},
      {"steps", steps},
      {"step_labels", p.step_labels.size() == steps ? p.step_labels : std::vector<std::string>{}},
      {"step_mesh", d.step_mesh},
      {"frames_per_step", p.scene.frames_per_step},
      {"loop", p.scene.loop},
      {"index_count", 3 * mesh.triangle_count()},
      {"phase_size", {grid.columns(), grid.rows()}},
      {"arrays", std::move(arrays)},
      {"plan", plan()},
      {"overlay", overlay(p, d, block)},
      {"ranges", ranges()}};

  if (report) report->scene = block.bytes().size();
  return {script_json(header), block.bytes(), name.empty() ? "ibfvs" : name};
}

std::string_view web_page_style() {
  return ".ibfvs-canvas{display:block;touch-action:none;cursor:grab;max-width:100%}"
         ".ibfvs-panel{margin:.5em 0;display:flex;gap:1em;flex-wrap:wrap;align-items:center}"
         ".ibfvs-message{padding:1em;border:1px solid #c33;background:#fee;max-width:40em}";
}

const char* web_widget_module() {
  return kWebWidget;
}

std::string web_page(const PreparedScene& p, WebPageReport* report, const WebPageLimits& limits) {
  const WebPageParts parts = web_page_parts(p, report, limits);
  const std::string runtime = kWebRuntime;
  std::string page =
      "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>" +
      html_escape(parts.name) +
      " - ibfvs</title>\n"
      "<style>body{font:14px system-ui,sans-serif;margin:1em;background:#fafafa;color:#222}" +
      std::string(web_page_style()) +
      "</style>\n"
      "</head>\n<body>\n<div id=\"ibfvs\"><p class=\"ibfvs-message\">This page shows an animated "
      "flow texture with WebGL2 and JavaScript; it needs both switched on.</p></div>\n"
      "<p>" +
      html_escape(parts.name) +
      ": drag to turn, shift-drag to move, wheel to zoom, space to "
      "pause. Made by ibfvs.</p>\n"
      "<script type=\"application/json\" id=\"ibfvs-scene\">" +
      parts.header +
      "</script>\n"
      "<script type=\"application/octet-stream\" id=\"ibfvs-data\">\n" +
      base64(parts.block) + "\n</script>\n<script>\n" + runtime + "\n</script>\n</body>\n</html>\n";
  if (report) {
    report->page = page.size();
    report->runtime = runtime.size();
  }
  return page;
}

WebPageReport write_web_page(const PreparedScene& scene, const std::filesystem::path& path,
                             const WebPageLimits& limits) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".html" && ext != ".htm")
    throw InputError(path.string() + ": a page must be named NAME.html");
  WebPageReport report;
  const std::string page = web_page(scene, &report, limits);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path.string() + ": cannot write");
  out.write(page.data(), static_cast<std::streamsize>(page.size()));
  if (!out) throw InputError(path.string() + ": cannot write (disk full?)");
  return report;
}

}  // namespace ibfvs
