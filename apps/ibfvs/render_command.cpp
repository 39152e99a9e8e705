#include "ibfvs/render_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>

#include <CLI/CLI.hpp>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/interrupt.h"
#include "ibfvs/page/web_page.h"
#include "ibfvs/progress.h"
#include "ibfvs/render/export.h"
#include "ibfvs/render/session.h"
#include "ibfvs/video/video_writer.h"

namespace ibfvs::app {
namespace fs = std::filesystem;

std::string flag_of(std::string_view key) {
  std::string flag = "--" + std::string(key);
  for (char& c : flag)
    if (c == '_') c = '-';
  return flag;
}

std::string error_line(const std::exception& error) {
  if (const auto* s = dynamic_cast<const SettingError*>(&error))
    return flag_of(s->key()) + ": " + s->problem();
  return error.what();
}

void add_scene_options(CLI::App& cmd, SceneOptions& o) {
  cmd.add_option("input", o.input,
                 "SCENE.toml (every key a setting; flags override it) or a mesh (as --mesh)");
  for (const SceneKey& key : scene_keys()) {
    const std::string flag = flag_of(key.name == "quiet" ? "quiet,-q"
                                     : key.name == "out" ? "out,-o"
                                                         : key.name);
    CLI::Option* option = nullptr;
    if (key.kind == KeyKind::Flag) {
      // A flag that is on by default is turned off by --no-NAME.
      const std::vector<std::string> shown = key.get(Scene{});
      const bool on = !shown.empty() && shown.front() == "true";
      option = on ? cmd.add_flag(flag + ",!" + flag_of("no_" + std::string(key.name)), key.help)
                  : cmd.add_flag(flag, key.help);
    } else {
      option = cmd.add_option(flag, key.help)->type_name("VALUE")->expected(1);
      option->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
      // The default, as the key prints it for a default scene.
      const std::vector<std::string> shown = key.get(Scene{});
      if (!shown.empty()) option->default_str(shown.front());
    }
    o.flags.emplace_back(&key, option);
  }
}

std::string scene_keys_table(bool markdown) {
  const auto type = [](KeyKind kind) -> const char* {
    switch (kind) {
      case KeyKind::String:
        return "string";
      case KeyKind::Integer:
        return "integer";
      case KeyKind::Number:
        return "number";
      case KeyKind::Flag:
        return "boolean";
      case KeyKind::Vector:
        return "array of numbers or string";
      case KeyKind::Size:
        return "[W, H] or \"WxH\"";
      case KeyKind::StringList:
        return "string or array of strings";
      case KeyKind::Elements:
        return "array of tables or strings";
      case KeyKind::Time:
        return "integer or string";
    }
    return "";
  };
  std::string out;
  if (markdown) out = "| key | type | flag | default | meaning |\n|---|---|---|---|---|\n";
  const Scene defaults;
  for (const SceneKey& key : scene_keys()) {
    const std::vector<std::string> shown = key.get(defaults);
    std::string value = shown.empty() ? "" : shown.front();
    std::string help = key.help;
    if (markdown) {
      // Table cells: escape the bars of alternatives.
      for (std::size_t p = help.find('|'); p != std::string::npos; p = help.find('|', p + 2))
        help.replace(p, 1, "\\|");
      out += "| `" + std::string(key.name) + "` | " + type(key.kind) + " | `" + flag_of(key.name) +
             "` | " + (value.empty() ? "" : "`" + value + "`") + " | " + help + " |\n";
    } else {
      out += std::string(key.name) + " (" + type(key.kind) + (value.empty() ? "" : ", " + value) +
             "): " + help + "\n";
    }
  }
  return out;
}

Scene scene_from_command_line(const SceneOptions& o) {
  std::vector<Setting> settings;
  if (!o.input.empty()) {
    if (is_scene_path(o.input))
      settings = read_scene_settings(o.input);
    else
      settings.push_back({"mesh", o.input, ""});
  }
  for (const auto& [key, option] : o.flags) {
    if (option->count() == 0) continue;
    if (key->kind == KeyKind::Flag) {
      settings.push_back({std::string(key->name), option->as<bool>() ? "true" : "false", ""});
      continue;
    }
    const std::vector<std::string> values = option->results();
    const bool repeatable = key->kind == KeyKind::StringList || key->kind == KeyKind::Elements;
    if (repeatable)
      for (const std::string& v : values) settings.push_back({std::string(key->name), v, ""});
    else if (!values.empty())
      settings.push_back({std::string(key->name), values.back(), ""});
  }
  Scene scene;
  apply_settings(scene, settings);
  return scene;
}

namespace {

// The default video name for a mesh: its file stem, or for a generated
// surface (landscape:3, globe, relief:...) its name with ':' and ',' made
// safe for file names and for ffmpeg (which reads "a:b" as a protocol).
std::string default_output_stem(const std::string& mesh) {
  std::string stem = fs::exists(mesh) ? fs::path(mesh).stem().string() : mesh;
  if (!fs::exists(mesh)) {
    const std::size_t slash = stem.find_last_of('/');
    if (stem.rfind("relief:", 0) == 0 && slash != std::string::npos)
      stem = "relief-" + stem.substr(slash + 1);
  }
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '-';
  return stem;
}

enum class OutputKind { Video, Png, PngSequence, Page };

bool is_page_path(const fs::path& out) {
  const std::string ext = lower_extension(out);
  return ext == ".html" || ext == ".htm";
}

OutputKind output_kind(const fs::path& out, const char* option) {
  if (is_video_path(out)) return OutputKind::Video;
  if (is_page_path(out)) return OutputKind::Page;
  if (lower_extension(out) != ".png")
    throw InputError(std::string(option) + ": unknown output type '" + out.string() +
                     "' (expected .mp4, .mkv, .webm, .mov, .avi, .gif, .png or .html)");
  return out.string().find('%') != std::string::npos ? OutputKind::PngSequence : OutputKind::Png;
}

std::string frame_path(const std::string& pattern, int frame) {
  // Only one integer conversion is allowed in the pattern (checked before rendering).
  std::vector<char> buf(pattern.size() + 32);
  std::snprintf(buf.data(), buf.size(), pattern.c_str(), frame);
  return buf.data();
}

void check_pattern(const std::string& pattern) {
  const std::size_t p = pattern.find('%');
  const std::size_t d = pattern.find_first_of("d", p);
  bool ok = p != std::string::npos && d != std::string::npos &&
            pattern.find('%', p + 1) == std::string::npos;
  for (std::size_t i = p + 1; ok && i < d; ++i)
    ok = std::isdigit(static_cast<unsigned char>(pattern[i]));
  if (!ok)
    throw InputError("--out: a frame pattern needs exactly one %d or %0Nd, got '" + pattern + "'");
}

// The files a scene reads: an output path must not be one of them.
std::vector<std::string> scene_inputs(const Scene& o, const std::string& scene_file) {
  std::vector<std::string> inputs{o.mesh, o.surface_image, scene_file};
  inputs.insert(inputs.end(), o.field_steps.begin(), o.field_steps.end());
  for (const std::optional<FieldSpec>& field : {o.field, o.default_field})
    if (field) inputs.push_back(field->path);
  return inputs;
}

void check_not_input(const fs::path& out, const std::vector<std::string>& inputs,
                     const char* option) {
  for (const std::string& input : inputs)
    if (!input.empty() && same_file(out, input))
      throw InputError(std::string(option) + ": " + out.string() +
                       " is an input of this render; writing it would destroy " + input);
}

}  // namespace

void ensure_parent(const fs::path& out, const char* option) {
  const fs::path parent = out.parent_path();
  std::error_code ec;
  if (fs::is_directory(out, ec))
    throw InputError(std::string(option) + ": " + out.string() + " is a folder");
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw InputError(std::string(option) + ": the folder '" + parent.string() + "' does not exist");
}

int run_render(const Scene& o, const std::string& scene_file) {
  // ---- output paths (checked before anything is loaded)
  const bool demo = o.mesh.empty();
  const fs::path out = !o.out.empty() ? fs::path(o.out)
                       : demo         ? fs::path("ibfvs-demo.mp4")
                                      : fs::path(default_output_stem(o.mesh) + ".mp4");
  const OutputKind kind = output_kind(out, "--out");
  if (kind == OutputKind::PngSequence) check_pattern(out.string());
  ensure_parent(out, "--out");
  const std::vector<std::string> inputs = scene_inputs(o, scene_file);
  if (kind != OutputKind::PngSequence) check_not_input(out, inputs, "--out");
  const bool export_page = !o.export_model.empty() && is_page_path(o.export_model);
  if (kind == OutputKind::Page || export_page) {
    if (!has_web_runtime())
      throw InputError(std::string(export_page ? "--export" : "--out") +
                       ": this ibfvs was built without the browser runtime for pages (it needs "
                       "npm and web/node_modules: scripts/install-deps.sh)");
  }
  if (!o.export_model.empty()) {
    if (!export_page) check_export_path(o.export_model, "--export");
    ensure_parent(o.export_model, "--export");
    check_not_input(o.export_model, inputs, "--export");
  }
  if (!o.texture_out.empty()) {
    if (output_kind(o.texture_out, "--texture-out") != OutputKind::Png)
      throw InputError("--texture-out: must be a .png file, got '" + o.texture_out + "'");
    ensure_parent(o.texture_out, "--texture-out");
    check_not_input(o.texture_out, inputs, "--texture-out");
  }

  PreparedScene prepared = prepare_scene(o);
  for (const std::string& w : prepared.warnings)
    std::fprintf(stderr, "ibfvs: warning: %s\n", w.c_str());
  struct {
    int width, height;
  } const size{prepared.width, prepared.height};
  const int frames = prepared.frames;
  const std::string mesh_name = prepared.mesh_name;
  const float dt = prepared.dt, max_px = prepared.max_px;
  const std::string field = field_text(prepared);  // prepared goes to the session

  // ---- a web page: the browser renders it; nothing to render here
  if (kind == OutputKind::Page) {
    const WebPageReport report = write_web_page(prepared, out);
    if (!o.quiet)
      std::printf(
          "ibfvs: wrote %s (%zu bytes: the scene %zu, the runtime %zu) from %s: %zu "
          "vertices, %zu triangles, field %s\n",
          out.c_str(), report.page, report.scene, report.runtime, mesh_name.c_str(),
          prepared.mesh->vertex_count(), prepared.mesh->triangle_count(), field.c_str());
    if (!o.quiet && report.other_meshes > 0)
      std::printf("ibfvs: %zu steps with triangles of their own, each a mesh in the page\n",
                  report.other_meshes);
    if (!o.quiet && report.moving_vertices > 0)
      std::printf(
          "ibfvs: the surface moves: %zu of its vertices, %zu sets of their points for "
          "%zu steps, %zu bytes; their screws between steps %zu bytes\n",
          report.moving_vertices, report.motion_sets, prepared.step_count, report.motion,
          report.screws);
    return 0;
  }

  // ---- render
  gl::HeadlessContext context;
  // Read through the session, never a renderer held across the frames (a
  // restart or a new size makes a new one).
  Session session(std::move(prepared));
  const std::shared_ptr<const TriMesh> mesh = session.scene().mesh;
  std::unique_ptr<VideoWriter> video;
  if (kind == OutputKind::Video)
    video = std::make_unique<VideoWriter>(out, size.width, size.height, o.fps);
  Progress progress(frames, !o.quiet);
  const auto start = std::chrono::steady_clock::now();
  const InterruptGuard interrupt;
  int done = 0;
  for (int k = 0; k < frames && !InterruptGuard::requested(); ++k, ++done) {
    session.advance();
    if (kind == OutputKind::Video) {
      ImageU8 frame = video->spare();
      session.read_output(frame);
      video->write(std::move(frame));
    }
    if (kind == OutputKind::PngSequence) {
      const std::string frame_file = frame_path(out.string(), k);
      check_not_input(frame_file, inputs, "--out");
      write_png(session.read_output(), frame_file);
    }
    progress.update(k + 1);
  }
  session.finish();
  context.throw_if_errors();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.finish();
  if (const int signal = InterruptGuard::requested()) {
    // Stopped: finish what can be whole; the last frame's outputs (a PNG,
    // --texture-out, --export) were never reached.
    std::string what;
    if (video) {
      video->close();
      what = "wrote " + out.string() + ", a shorter video of " + std::to_string(done) + " frames";
    } else if (kind == OutputKind::PngSequence) {
      what = "wrote its first " + std::to_string(done) + " frames";
    } else {
      what = out.string() + " was not written (it is the last frame)";
    }
    std::fprintf(stderr, "ibfvs: interrupted by %s after %d of %d frames: %s\n",
                 InterruptGuard::name(signal), done, frames, what.c_str());
    return 128 + signal;
  }
  if (kind == OutputKind::Png) write_png(session.read_output(), out);
  if (video) video->close();
  if (!o.texture_out.empty()) {
    write_png16(session.read_texture().select_channels(0, 3), o.texture_out);
  }
  if (export_page) {
    const WebPageReport report = write_web_page(session.scene(), o.export_model);
    if (!o.quiet)
      std::printf("ibfvs: exported %s (%zu bytes)\n", o.export_model.c_str(), report.page);
  } else if (!o.export_model.empty()) {
    // F_t as an 8-bit RGB image and each vertex's position in it (section 3.7).
    const ExportReport report = export_textured_model(session.renderer(), *mesh, o.export_model);
    if (report.outside > 0)
      std::fprintf(stderr,
                   "ibfvs: warning: %zu vertices lie outside the view that made the texture; "
                   "their texture coordinates are clamped to the image border\n",
                   report.outside);
    std::string written;
    for (std::size_t i = 0; i + 1 < report.files.size(); ++i)
      written += (i ? ", " : "") + report.files[i].string();
    if (!o.quiet)
      std::printf("ibfvs: exported %s and %s\n", written.c_str(), report.files.back().c_str());
  }

  if (!o.quiet) {
    std::printf(
        "ibfvs: wrote %s (%d frames, %dx%d) from %s: %zu vertices, %zu triangles, field %s, "
        "dt %.4g (%s %.2f px/frame), %.1f fps on %s\n",
        out.c_str(), frames, size.width, size.height, mesh_name.c_str(), mesh->vertex_count(),
        mesh->triangle_count(), field.c_str(), dt,
        o.image_normalize ? "image-normalised, every point" : "max", max_px, frames / seconds,
        context.renderer().c_str());
    if (!o.texture_out.empty())
      std::printf("ibfvs: wrote texture image %s\n", o.texture_out.c_str());
  }
  return 0;
}

}  // namespace ibfvs::app
