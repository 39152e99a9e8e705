#pragma once
// A self-contained web page of a prepared scene (docs/web.md): one HTML file
// holding the scene (a JSON header and one base64 block of compact binary
// arrays), the GLSL ES 3.00 sources that the shader generator emits for its
// features, the uniforms the settings give (shaders::settings_uniforms), and
// the browser runtime (web/src/runtime.ts, bundled at build time). It opens
// from disk: no server, no network.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "ibfvs/core/scene/scene_prep.h"

namespace ibfvs {

/// Whether this build holds the browser runtime (it needs node and npm at
/// build time, and web/node_modules from scripts/install-deps.sh).
[[nodiscard]] bool has_web_runtime();

/// The most a page takes: beyond, the file passes 100 MB and a browser's
/// memory for one tab.
struct WebPageLimits {
  std::size_t triangles = 4'000'000;
  std::size_t vectors = 16'000'000;  ///< over all time steps (8 bytes each in the page)
};

/// Sizes of a written page, in bytes.
struct WebPageReport {
  std::size_t page = 0;     ///< the whole file
  std::size_t scene = 0;    ///< the binary arrays before base64
  std::size_t runtime = 0;  ///< the embedded script
  /// A surface that moves: the vertices that move at some step, the sets of
  /// their points and normals stored (a step like the one before it shares
  /// its set), and the bytes those take in the scene.
  std::size_t moving_vertices = 0, motion_sets = 0, motion = 0;
  /// Their screws from each step to the next (the motion between steps), in bytes.
  std::size_t screws = 0;
  /// Steps whose triangles are their own (a changing mesh): each a mesh of its own.
  std::size_t other_meshes = 0;
};

/// A page's scene without the page around it: what the notebook widget
/// (python/ibfvs/notebook.py) hands the runtime in place of the page's two
/// script elements.
struct WebPageParts {
  std::string header;               ///< the JSON header (page.schema.json)
  std::vector<std::uint8_t> block;  ///< the binary arrays
  std::string name;                 ///< the scene's name (its mesh file's stem)
};

/// The scene's parts, as web_page() puts them in the page (its header and
/// limits; `report` gets the scene's sizes).
[[nodiscard]] WebPageParts web_page_parts(const PreparedScene& scene,
                                          WebPageReport* report = nullptr,
                                          const WebPageLimits& limits = {});

/// The page's style sheet for its canvas, panel and message: the page's
/// and the notebook widget's.
[[nodiscard]] std::string_view web_page_style();

/// The notebook widget's ES module (web/src/widget.ts: anywidget's render
/// around the page's runtime), or null in a build without the runtime.
[[nodiscard]] const char* web_widget_module();

/// The page as text; an unsteady field's steps all go in (the page plays
/// them, with a time slider; points that move and steps with triangles of
/// their own too), and so do the styles that take the same data
/// (restyled: a style menu), a surface image, random-cell colours and the
/// lock. Throws InputError for what a page cannot hold (more than `limits`)
/// or when this build has no runtime.
[[nodiscard]] std::string web_page(const PreparedScene& scene, WebPageReport* report = nullptr,
                                   const WebPageLimits& limits = {});
/// Writes web_page() to `path` (which must end in .html). Throws InputError.
WebPageReport write_web_page(const PreparedScene& scene, const std::filesystem::path& path,
                             const WebPageLimits& limits = {});

}  // namespace ibfvs
