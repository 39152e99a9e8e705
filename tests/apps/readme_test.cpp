// Every command line README.md and the docs show runs: the examples in their
// code blocks and the commands quoted in their text, with small sizes and
// frame counts, so that the docs cannot drift from the program again.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "command_runner.h"
#include "helpers.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/render/session.h"

namespace ibfvs {
namespace {

namespace fs = std::filesystem;

// The `ibfvs ...` command lines of a Markdown text: lines of fenced code
// blocks (continuations joined, comments dropped; "./build/ibfvs" counts) and
// inline code spans that start with "ibfvs COMMAND -" or name a scene file.
// Spans with placeholders (SCENE.toml, [options], FILE) are descriptions, not
// examples, and are left out.
std::vector<std::string> readme_commands(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream lines(text);
  bool in_code = false;
  std::string prose, pending;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("```", 0) == 0) {
      in_code = !in_code;
      continue;
    }
    if (!in_code) {
      prose += line + " ";
      continue;
    }
    if (!pending.empty() || line.find("ibfvs ") != std::string::npos) {
      const bool continues = !line.empty() && line.back() == '\\';
      pending += continues ? line.substr(0, line.size() - 1) : line;
      if (continues) continue;
      std::string command = pending;
      pending.clear();
      if (const std::size_t hash = command.find(" #"); hash != std::string::npos)
        command.resize(hash);
      const std::size_t at = command.find("ibfvs ");
      if (command.find("./build/ibfvs") == std::string::npos && at != 0) continue;
      out.push_back(command.substr(at));
    }
  }
  const std::regex span("`(ibfvs (render|view|geometry|bench|keys|quality)[^`]*)`");
  for (auto it = std::sregex_iterator(prose.begin(), prose.end(), span);
       it != std::sregex_iterator(); ++it) {
    std::string command = std::regex_replace((*it)[1].str(), std::regex(" +"), " ");
    const bool example =
        command.find(" -") != std::string::npos || command.find(".toml") != std::string::npos;
    const bool placeholder =
        command.find('[') != std::string::npos || command.find("SCENE") != std::string::npos ||
        command.find("SAVED") != std::string::npos || command.find("FILE") != std::string::npos ||
        command.find("--help") != std::string::npos;
    if (example && !placeholder) out.push_back(command);
  }
  return out;
}

class Readme : public test::CommandTest {};

// README.md and every page of docs/ but three: docs/performance.md's and
// docs/reliability.md's commands are whole benchmark runs, scale tests and
// fuzzing campaigns, and docs/data.md's name the user's own files (its
// formats are the VTK tests' and the corpus's). Commands on an OpenFOAM case
// run where scripts/cfd_motorbike.sh or cfd_case.sh has made it (minutes:
// not in CI).
TEST_F(Readme, EveryCommandLineItShowsRuns) {
  const fs::path data(IBFVS_TEST_DATA_DIR);
  if (!fs::exists(data / "meshes/cow.off") || !fs::exists(data / "earth/etopo20.cdf"))
    GTEST_SKIP() << "fetched data missing (scripts/fetch_data.sh)";
  const bool xvfb = std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
  // The folders the README's paths are relative to, and the user's own
  // files its examples name (a PLY with vx vy vz).
  fs::create_directory_symlink(data, dir_ / "data");
  fs::create_directory_symlink(IBFVS_SCENES_DIR, dir_ / "scenes");
  TriMesh wing = make_torus(1.0f, 0.3f, 48, 16);
  wing.vectors.assign(wing.vertex_count(), glm::vec3(1.0f, 0.2f, 0.0f));
  write_ply(wing, dir_ / "wing.ply", true);
  file("quit.txt", "3 quit\n");
  fs::create_directories(dir_ / "docs/gallery");  // the gallery's outputs

  std::vector<fs::path> pages{fs::path(IBFVS_SOURCE_DIR) / "README.md"};
  for (const auto& entry : fs::directory_iterator(fs::path(IBFVS_SOURCE_DIR) / "docs")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".md" && name != "performance.md" && name != "reliability.md" &&
        name != "data.md")
      pages.push_back(entry.path());
  }
  std::sort(pages.begin(), pages.end());
  std::vector<std::string> commands;
  int pages_with_commands = 0;
  for (const fs::path& page : pages) {
    const std::vector<std::string> found = readme_commands(test::read_file(page));
    pages_with_commands += found.empty() ? 0 : 1;
    commands.insert(commands.end(), found.begin(), found.end());
  }
  EXPECT_GE(pages_with_commands, 9);
  int ran = 0, views = 0;
  int skipped = 0;
  for (const std::string& command : commands) {
    SCOPED_TRACE(command);
    // A case of scripts/cfd_*.sh: data/cfd/CASE/, run where it has been made.
    if (const std::size_t at = command.find("data/cfd/"); at != std::string::npos) {
      const std::size_t end = command.find('/', at + 9);
      if (!fs::exists(data / command.substr(at + 5, end - at - 5))) {
        ++skipped;
        continue;
      }
    }
    // Small and short: later flags override the README's own.
    std::string args = command.substr(command.find("ibfvs ") + 6);
    const std::string verb = args.substr(0, args.find(' '));
    std::string env = "IBFVS_DATA_DIR='" + data.string() + "'";
    if (verb == "render") {
      args += " --size 48x48 --frames 3 -q";
    } else if (verb == "view") {
      if (!xvfb) continue;
      args += " --size 64x64 --script quit.txt -q";
      env += " xvfb-run -a -s '-screen 0 640x480x24'";
      ++views;
    } else if (verb == "quality") {
      if (args.find("--png") != std::string::npos) {
        // The picture another tool made (ParaView's, in docs/quality.md): one of ours.
        const std::string png = args.substr(args.find("--png") + 6);
        ASSERT_EQ(run("render --size 48x48 --frames 3 -q --out " + png, env).status, 0);
      } else {
        args += " --size 64x64 --warmup 5";
      }
    } else if (verb == "bench") {
      args += " --subdivide 0 --sizes 32x32 --seconds 0.02 --repeats 1 --warmup 1 -q";
    }
    std::printf("README: ibfvs %s\n", args.c_str());
    const test::Result r = run(args, env);
    EXPECT_EQ(r.status, 0) << r.err;
    ++ran;
  }
  // The README and docs hold over fifty, the viewer's four included (the
  // README's and docs/viewer.md's first take the mesh as an argument).
  EXPECT_GE(ran + skipped, 50);
  if (xvfb) {
    EXPECT_EQ(views, 4);
  }
  std::printf("README: %d command lines ran, %d need an OpenFOAM case\n", ran, skipped);
}

// The docs come from the key and name tables: docs/scenes.md holds exactly
// `ibfvs keys --markdown`, docs/cli.md exactly `ibfvs options`, and its
// rows of the enum options list every name of their table.
TEST_F(Readme, DocsListEveryKeyAndEveryName) {
  const auto generated = [&](const char* page, const std::string& command, const std::string& begin,
                             const std::string& end) {
    const test::Result r = run(command);
    EXPECT_EQ(r.status, 0) << r.err;
    const std::string text = test::read_file(fs::path(IBFVS_SOURCE_DIR) / page);
    const std::size_t a = text.find(begin), b = text.find(end);
    EXPECT_NE(a, std::string::npos) << page;
    EXPECT_NE(b, std::string::npos) << page;
    if (a == std::string::npos || b == std::string::npos) return std::string();
    EXPECT_EQ(text.substr(a + begin.size(), b - a - begin.size()), r.out)
        << page << " is out of date: paste `ibfvs " << command << "` between its markers";
    return text.substr(a, b - a);
  };
  generated("docs/scenes.md", "keys --markdown",
            "<!-- keys: generated by `ibfvs keys --markdown` -->\n", "<!-- end of keys -->");
  const std::string options =
      generated("docs/cli.md", "options", "<!-- options: generated by `ibfvs options` -->\n",
                "<!-- end of options -->");
  // The render command's table: its first row of each option.
  const std::string render = options.substr(0, options.find("### `ibfvs view`"));
  ASSERT_NE(render.find("### `ibfvs render`"), std::string::npos);
  const auto row = [&](const std::string& flag) {
    const std::size_t at = render.find("\n| `" + flag);
    return at == std::string::npos ? std::string()
                                   : render.substr(at, render.find('\n', at + 1) - at);
  };
  const auto check = [&](const std::string& flag, const std::string& names) {
    const std::string r = row(flag);
    ASSERT_FALSE(r.empty()) << flag << " has no row in docs/cli.md's render table";
    for (std::size_t start = 0; start < names.size();) {
      std::size_t end = names.find_first_of(", ", start);
      if (end == std::string::npos) end = names.size();
      const std::string name = names.substr(start, end - start);
      if (!name.empty() && name != "or") {
        EXPECT_NE(r.find(name), std::string::npos) << flag << " row lacks " << name << ":\n" << r;
      }
      start = end + 1;
    }
  };
  check("--color-map", enum_name_list<ColorMap>());
  check("--profile", enum_name_list<NoiseProfile>());
  check("--tangent", enum_name_list<TangentMode>());
  check("--inject", enum_name_list<InjectMode>());
  check("--noise-space", enum_name_list<NoiseSpace>());
  check("--advect-view", enum_name_list<AdvectView>());
  check("--resample", enum_name_list<Resample>());
}

// `ibfvs options` takes no argument: anything else is one error line.
TEST_F(Readme, OptionsCommandRefusesArgumentsInOneLine) {
  for (const char* args : {"options --markdown", "options cow.off"}) {
    const test::Result r = run(args);
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_TRUE(r.out.empty()) << args;
    EXPECT_EQ(r.err.rfind("ibfvs: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("ibfvs options --help"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  }
}

// The ParaView representation starts from the same look as the command line:
// each property's default_values in the plugin's XML equals the Scene's.
TEST(ParaViewDefaults, EqualTheScenesDefaults) {
  const std::string xml = test::read_file(IBFVS_PARAVIEW_XML);
  const auto value = [&](const std::string& property) {
    const std::regex re("name=\"" + property + "\"[^>]*default_values=\"([^\"]*)\"");
    std::smatch m;
    EXPECT_TRUE(std::regex_search(xml, m, re)) << property << " has no default in the XML";
    return m.empty() ? std::nan("") : std::stod(m[1].str());
  };
  const Scene s;
  EXPECT_FLOAT_EQ(value("Alpha"), s.alpha);
  EXPECT_FLOAT_EQ(value("Beta"), s.beta);
  EXPECT_FLOAT_EQ(value("NoiseScale"), s.scale);
  EXPECT_FLOAT_EQ(value("StepPixels"), s.step);
  EXPECT_FLOAT_EQ(value("NoiseRate"), s.vg);
  EXPECT_EQ(value("TimeProfile"), static_cast<double>(s.profile));
  EXPECT_EQ(value("ImageNormalize"), s.image_normalize ? 1.0 : 0.0);
  EXPECT_FLOAT_EQ(value("FilterLength"), s.filter);
  EXPECT_FLOAT_EQ(value("Contrast"), s.contrast);
  EXPECT_FLOAT_EQ(value("Sharpen"), s.sharpen);
  EXPECT_EQ(value("Resample"), static_cast<double>(s.resample));  // the enum's numbers
  EXPECT_EQ(value("Seed"), static_cast<double>(s.seed));
  EXPECT_EQ(value("FramesPerStep"), static_cast<double>(kDefaultFramesPerStep));
}

// Every representation that offers IBFVS (ParaView's Surface representation
// for polygonal data, unstructured grids, structured grids, image data) shows
// the same IBFVS group: every property of the IBFVS representation that a
// panel shows, none missing (Frames Per Step and Restart Texture once were,
// on all but polygonal data).
TEST(ParaViewDefaults, EveryRepresentationExposesEveryPanelProperty) {
  const std::string xml = test::read_file(IBFVS_PARAVIEW_XML);
  const std::size_t begin = xml.find("<IBFVSRepresentationProxy");
  const std::size_t end = xml.find("</IBFVSRepresentationProxy>");
  ASSERT_NE(end, std::string::npos);
  const std::string proxy = xml.substr(begin, end - begin);
  std::set<std::string> shown;
  const std::regex property(R"re(<(\w*Property) name="(\w+)"([^>]*)>)re");
  for (std::sregex_iterator it(proxy.begin(), proxy.end(), property), stop; it != stop; ++it)
    if ((*it)[3].str().find("panel_visibility=\"never\"") == std::string::npos &&
        (*it)[3].str().find("function=") == std::string::npos)  // not a domain's input
      shown.insert((*it)[2].str());
  EXPECT_TRUE(shown.count("FramesPerStep") && shown.count("RestartTexture"));
  EXPECT_FALSE(shown.count("GatherForPage"));
  const std::regex extension(R"re(<Extension name="(\w+)">([\s\S]*?)</Extension>)re");
  std::set<std::string> representations;
  for (std::sregex_iterator it(xml.begin(), xml.end(), extension), stop; it != stop; ++it) {
    const std::string body = (*it)[2].str();
    std::set<std::string> exposed;
    const std::regex name(R"re(<Property name="(\w+)")re");
    for (std::sregex_iterator p(body.begin(), body.end(), name); p != stop; ++p)
      exposed.insert((*p)[1].str());
    EXPECT_EQ(exposed, shown) << (*it)[1].str();
    representations.insert((*it)[1].str());
  }
  EXPECT_EQ(representations,
            (std::set<std::string>{"GeometryRepresentation", "StructuredGridRepresentation",
                                   "UniformGridRepresentation", "UnstructuredGridRepresentation"}));
}

// Its enumerations are the library's name tables (EnumNames): every value,
// by its integer, with the name capitalised; none more.
template <class E>
void expect_xml_enumeration(const std::string& xml, const std::string& property) {
  const std::size_t at = xml.find("name=\"" + property + "\"");
  ASSERT_NE(at, std::string::npos) << property;
  const std::size_t begin = xml.find("<EnumerationDomain", at);
  const std::size_t end = xml.find("</EnumerationDomain>", begin);
  ASSERT_NE(end, std::string::npos) << property;
  const std::string domain = xml.substr(begin, end - begin);
  std::map<int, std::string> entries;
  const std::regex entry(
      R"re(<Entry (?:text="([^"]*)" value="(\d+)"|value="(\d+)" text="([^"]*)")/>)re");
  for (std::sregex_iterator it(domain.begin(), domain.end(), entry), stop; it != stop; ++it) {
    const std::smatch& m = *it;
    const bool text_first = m[1].matched;
    entries[std::stoi(text_first ? m[2].str() : m[3].str())] = text_first ? m[1].str() : m[4].str();
  }
  std::map<int, std::string> expected;
  for (const auto& e : EnumNames<E>::table) {
    std::string name(e.name);
    name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
    expected.emplace(static_cast<int>(e.value), name);
  }
  EXPECT_EQ(entries, expected) << property;
}

TEST(ParaViewDefaults, EnumerationsAreTheNameTables) {
  const std::string xml = test::read_file(IBFVS_PARAVIEW_XML);
  expect_xml_enumeration<NoiseProfile>(xml, "TimeProfile");
  expect_xml_enumeration<Resample>(xml, "Resample");
  expect_xml_enumeration<FieldFrame>(xml, "FieldFrame");
}

// Its number properties span their scene keys' ranges (key_range: the one
// table the command line, the viewer's sliders and the mapper's clamps use),
// and every ranged key has its property; the styles stay inside them.
TEST(ParaViewDefaults, RangesAreTheKeysRanges) {
  const std::string xml = test::read_file(IBFVS_PARAVIEW_XML);
  for (const SceneKey& k : scene_keys()) {
    if (!key_range(k.name)) continue;
    ASSERT_FALSE(k.host.empty()) << k.name << " has a range but no ParaView property";
    const std::string property(k.host);
    const std::regex re("name=\"" + property + "\"[^>]*command=\"Set" + property +
                        "\"[\\s\\S]*?<DoubleRangeDomain name=\"range\" min=\"([^\"]*)\" "
                        "max=\"([^\"]*)\"");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(xml, m, re)) << property << " has no range in the XML";
    EXPECT_FLOAT_EQ(std::stof(m[1].str()), k.range->min) << property;
    EXPECT_FLOAT_EQ(std::stof(m[2].str()), k.range->max) << property;
  }
  for (const auto& style : EnumNames<Style>::table) {
    Scene s;
    apply_style(s, style.value);
    for (const auto& [key, value] : {std::pair{"alpha", s.alpha},
                                     {"beta", s.beta},
                                     {"filter", s.filter},
                                     {"contrast", s.contrast},
                                     {"sharpen", s.sharpen}})
      EXPECT_EQ(clamp_to_key_range(key, value), value) << style.name << " " << key;
  }
}

}  // namespace
}  // namespace ibfvs
