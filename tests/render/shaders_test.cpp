// The one shader generator emits the pass in both dialects: every source it
// makes, for single features, their combinations and every filter length
// (and the display pass where they have one), compiles as GLSL 4.50 core and
// as GLSL ES 3.00 (WebGL2) under glslang, the Khronos reference compiler. The 4.50 sources also run
// in every GL test.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "helpers.h"
#include "ibfvs/render/pass_settings.h"
#include "ibfvs/render/shaders.h"

namespace ibfvs {
namespace {

namespace fs = std::filesystem;
using shaders::Dialect;
using shaders::ShaderFeatures;

// Sources written to files whose extension names the stage, then compiled
// by glslang in one run: its log names each file that fails, and each file
// holds its features' key in its name.
class Sources {
 public:
  void add(const std::string& source, const std::string& what, const char* stage) {
    std::string name = what;  // appended, not concatenated: GCC 12's -Wrestrict misfires on that
    name += '-';
    name += std::to_string(files_.size());
    name += '.';
    name += stage;
    files_.push_back(dir_ / name);
    std::ofstream(files_.back()) << source;
  }
  std::size_t size() const { return files_.size(); }
  // The empty string when every file compiles, else the start of glslang's log.
  std::string errors() const {
    const fs::path log = dir_ / "glslang.log";
    std::string command = IBFVS_GLSLANG;
    for (const fs::path& f : files_) command += " '" + f.string() + "'";
    command += " > '" + log.string() + "' 2>&1";
    if (std::system(command.c_str()) == 0) return {};
    return test::read_file(log).substr(0, 4000);  // the first failures say enough
  }

 private:
  test::TempDir dir_;
  std::vector<fs::path> files_;
};

std::vector<ShaderFeatures> combinations() {
  std::vector<ShaderFeatures> out(1);  // nothing on
  bool ShaderFeatures::*flags[] = {
      &ShaderFeatures::object_noise, &ShaderFeatures::surface_image, &ShaderFeatures::color_scalar,
      &ShaderFeatures::beta_scalar,  &ShaderFeatures::image_step,    &ShaderFeatures::inject_add,
      &ShaderFeatures::mono_texture, &ShaderFeatures::cubic,         &ShaderFeatures::contrast,
      &ShaderFeatures::record_flow,  &ShaderFeatures::sharpen};
  ShaderFeatures all;
  for (auto flag : flags) {
    ShaderFeatures one;
    one.*flag = true;
    out.push_back(one);
    all.*flag = true;
  }
  for (int taps = 1; taps <= 16; ++taps) {
    ShaderFeatures f;  // the default look's kind: grey F_t, filtered, sharpened
    f.mono_texture = f.cubic = f.sharpen = f.contrast = f.image_step = true;
    f.filter_taps = taps;
    out.push_back(f);
    f.mono_texture = false;  // a colour F_t filtered
    out.push_back(f);
  }
  all.filter_taps = 16;
  out.push_back(all);
  all.mono_texture = false;
  out.push_back(all);
  return out;
}

TEST(Shaders, EverySourceCompilesAsGlsl450AndAsEs300) {
  for (Dialect dialect : {Dialect::Gl45, Dialect::Es300}) {
    const std::string what = dialect == Dialect::Es300 ? "es300" : "gl450";
    Sources sources;
    for (const ShaderFeatures& f : combinations()) {
      const std::string key = what + "-features" + std::to_string(f.key());
      sources.add(shaders::ibfvs_vertex_source(f, dialect), key, "vert");
      sources.add(shaders::ibfvs_fragment_source(f, dialect), key, "frag");
      if (shaders::tap_texture(f))  // the display pass that goes with it
        sources.add(shaders::display_fragment_source(f, dialect), key + "-display", "frag");
      if (shaders::deferred_pass(f)) {  // the two halves of the deferred pass
        sources.add(shaders::gbuffer_fragment_source(f, dialect), key + "-gbuffer", "frag");
        sources.add(shaders::resolve_fragment_source(f, dialect), key + "-resolve", "frag");
      }
    }
    sources.add(shaders::grid_vertex_source(dialect), what + "-grid", "vert");
    sources.add(shaders::display_vertex_source(dialect), what + "-display", "vert");
    sources.add(shaders::grid_fragment_source(dialect), what + "-grid", "frag");
    sources.add(shaders::stats_fragment_source(true, dialect), what + "-stats-grey", "frag");
    sources.add(shaders::stats_fragment_source(false, dialect), what + "-stats-colour", "frag");
    sources.add(shaders::overlay_vertex_source(dialect), what + "-overlay", "vert");
    sources.add(shaders::overlay_fragment_source(dialect), what + "-overlay", "frag");
    EXPECT_EQ(sources.errors(), "") << what;
    std::printf("glslang: %zu %s sources compiled\n", sources.size(), what.c_str());
  }
}

TEST(Shaders, TheDialectsDifferOnlyInTheirPrelude) {
  ShaderFeatures f;
  f.mono_texture = f.cubic = f.sharpen = f.contrast = f.color_scalar = true;
  f.filter_taps = 4;
  const std::string gl = shaders::ibfvs_fragment_source(f, Dialect::Gl45);
  const std::string es = shaders::ibfvs_fragment_source(f, Dialect::Es300);
  EXPECT_EQ(gl.rfind("#version 450 core\n", 0), 0u);
  EXPECT_EQ(es.rfind("#version 300 es\n", 0), 0u);
  // The same body after the dialect's own lines: from the first feature define on.
  const std::string marker = "#define IBFVS_COLOR_SCALAR";
  ASSERT_NE(gl.find(marker), std::string::npos);
  EXPECT_EQ(gl.substr(gl.find(marker)), es.substr(es.find(marker)));
}

}  // namespace
}  // namespace ibfvs
