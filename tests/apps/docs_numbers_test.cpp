// The numbers and names the docs state, checked against what the program and
// the test suite give: a page's size from the command that writes it, the
// runs labelled `optimised`, the tests the docs name. A number here that no
// longer rounds to the program's fails, as an out-of-date option table does
// (readme_test.cpp).

#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "command_runner.h"
#include "helpers.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/names.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {
namespace {

namespace fs = std::filesystem;

std::string source_file(const std::string& path) {
  return test::read_file(fs::path(IBFVS_SOURCE_DIR) / path);
}

// Whether `bytes` in `unit` (1000 or 1e6) rounds to `stated` as written
// ("1.05", "7.4", "75"): within half its last digit.
bool rounds_to(double bytes, double unit, const std::string& stated) {
  const std::size_t dot = stated.find('.');
  const int digits = dot == std::string::npos ? 0 : static_cast<int>(stated.size() - dot - 1);
  return std::abs(bytes / unit - std::stod(stated)) <= 0.5 * std::pow(10.0, -digits) + 1e-9;
}

// "1.05 MB" or "75 KB" against a byte count.
void expect_size(double bytes, const std::string& cell, const std::string& what) {
  static const std::regex size(R"(\s*([0-9.]+) (MB|KB)\s*)");
  std::smatch m;
  ASSERT_TRUE(std::regex_match(cell, m, size)) << what << ": '" << cell << "' is not a size";
  const double unit = m[2] == "MB" ? 1e6 : 1e3;
  EXPECT_TRUE(rounds_to(bytes, unit, m[1].str()))
      << what << ": the docs say " << m[1] << " " << m[2] << ", the program wrote " << bytes
      << " bytes (" << bytes / unit << " " << m[2] << ")";
}

class StatedNumbers : public test::CommandTest {
 protected:
  // The page a command wrote: its bytes, its scene's and its runtime's, as
  // the render command prints them.
  struct PageSizes {
    double page = 0, scene = 0, runtime = 0;
  };
  PageSizes write_page(const std::string& args) {
    const test::Result r = run(args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
    static const std::regex wrote(R"(\((\d+) bytes: the scene (\d+), the runtime (\d+)\))");
    std::smatch m;
    PageSizes s;
    if (!std::regex_search(r.out, m, wrote)) {
      ADD_FAILURE() << args << ": no sizes in\n" << r.out;
      return s;
    }
    s.page = std::stod(m[1]);
    s.scene = std::stod(m[2]);
    s.runtime = std::stod(m[3]);
    return s;
  }
  bool with_data() {
    const fs::path data(IBFVS_TEST_DATA_DIR);
    if (!fs::exists(data / "meshes/cow.off") || !fs::exists(data / "earth/etopo20.cdf"))
      return false;
    fs::create_directory_symlink(data, dir_ / "data");
    fs::create_directory_symlink(IBFVS_SCENES_DIR, dir_ / "scenes");
    return true;
  }
};

// docs/web.md's table of page sizes: each row's command, run, writes a page
// whose sizes round to the row's; and the gallery's year of winds.
TEST_F(StatedNumbers, StatedPageSizesAreThePrograms) {
  if (!with_data()) GTEST_SKIP() << "fetched data missing (scripts/fetch_data.sh)";
  const std::string web = source_file("docs/web.md");
  const std::string begin =
      "<!-- page sizes: checked by StatedNumbers.StatedPageSizesAreThePrograms -->";
  const std::size_t a = web.find(begin), b = web.find("<!-- end of page sizes -->");
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  const std::string table = web.substr(a + begin.size(), b - a - begin.size());
  static const std::regex row(
      R"(\| ([^|]+) \| `ibfvs ([^`]+)` \|[^|]+\|([^|]+)\|([^|]+)\|([^|]+)\|)");
  int rows = 0;
  for (auto it = std::sregex_iterator(table.begin(), table.end(), row);
       it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1], args = (*it)[2];
    SCOPED_TRACE(name);
    if (const std::size_t at = args.find("data/cfd/"); at != std::string::npos) {
      const std::size_t end = args.find('/', at + 9);
      if (!fs::exists(fs::path(IBFVS_TEST_DATA_DIR) / args.substr(at + 5, end - at - 5)))
        continue;  // a case of scripts/cfd_*.sh, made where it runs (minutes: not in CI)
    }
    const PageSizes s = write_page(args);
    expect_size(s.page, (*it)[3], name + ": the page");
    expect_size(s.scene, (*it)[4], name + ": the scene's arrays");
    expect_size(s.runtime, (*it)[5], name + ": the runtime");
    ++rows;
  }
  EXPECT_GE(rows, 3) << "the table's rows were not found";

  // The gallery: `figure6-year.html` (N MB ...), from its own command.
  const std::string gallery = source_file("docs/gallery.md");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(gallery, m, std::regex(R"(`figure6-year\.html` \(([0-9.]+ MB))")));
  const std::string stated = m[1];
  ASSERT_TRUE(std::regex_search(
      gallery, m, std::regex(R"(ibfvs (render [^\n]*) --out docs/gallery/figure6-year\.html)")));
  expect_size(write_page(m[1].str() + " --out figure6-year.html").page, stated,
              "docs/gallery.md's figure6-year.html");
}

// The Navy winds' dates as the docs state them (docs/data.md, earth.md,
// design.md): the first and last month, how many, and which month a
// `--time K` shows, against the dates the command reads from the file's
// time axis.
TEST_F(StatedNumbers, TheEarthDatasDatesAreItsTimeAxis) {
  if (!with_data() || !fs::exists(dir_ / "data/earth/monthly_navy_winds.cdf"))
    GTEST_SKIP() << "fetched data missing (scripts/fetch_data.sh)";
  // A page's text with its line breaks as spaces.
  const auto flat = [](const char* page) {
    return std::regex_replace(source_file(page), std::regex(R"(\s+)"), " ");
  };
  const std::string winds =
      "render --mesh globe:1 --field wind:data/earth/monthly_navy_winds.cdf --frames 1 "
      "--size 16x16 --out winds.png --time ";
  // "at time index 0 to 131 (1982-01-16 20:00 to 1992-12-17 03:30)"
  test::Result r = run(winds + "0:131");
  ASSERT_EQ(r.status, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      r.out, m,
      std::regex(
          R"(at time index 0 to (\d+) \((\d{4}-\d\d-\d\d)[^)]* to (\d{4}-\d\d-\d\d)[^)]*\))")))
      << r.out;
  const int months = std::stoi(m[1]) + 1;
  const std::string first = m[2], last = m[3];
  static const std::regex range(R"((\d{4}-\d\d-\d\d) to (\d{4}-\d\d-\d\d))");
  int ranges = 0;
  for (const char* page : {"docs/data.md", "docs/earth.md", "docs/design.md"}) {
    const std::string text = flat(page);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), range);
         it != std::sregex_iterator(); ++it, ++ranges)
      EXPECT_EQ((*it)[1].str() + " to " + (*it)[2].str(), first + " to " + last)
          << page << " dates the winds otherwise than their time axis";
  }
  EXPECT_GE(ranges, 3);
  const std::string data = flat("docs/data.md");
  ASSERT_TRUE(std::regex_search(data, m, std::regex(R"((\d+) months, \d{4}-)")));
  EXPECT_EQ(std::stoi(m[1]), months) << "docs/data.md's count of months";

  // "months from January 1982", "`--time 6` is July 1982"
  static const char* const names[] = {"January",   "February", "March",    "April",
                                      "May",       "June",     "July",     "August",
                                      "September", "October",  "November", "December"};
  const auto month_of = [](const std::string& date) {
    return std::string(names[std::stoi(date.substr(5, 2)) - 1]) + " " + date.substr(0, 4);
  };
  const std::string earth = flat("docs/earth.md");
  ASSERT_TRUE(std::regex_search(earth, m, std::regex(R"(months from (\w+ \d{4}))")));
  EXPECT_EQ(m[1].str(), month_of(first)) << "docs/earth.md: the first month";
  int shown = 0;
  static const std::regex time_is(R"(`--time (\d+)` is (\w+ \d{4}))");
  for (auto it = std::sregex_iterator(earth.begin(), earth.end(), time_is);
       it != std::sregex_iterator(); ++it, ++shown) {
    r = run(winds + (*it)[1].str());
    ASSERT_EQ(r.status, 0) << r.err;
    std::smatch d;
    ASSERT_TRUE(std::regex_search(r.out, d, std::regex(R"(at time index \d+ \((\d{4}-\d\d-\d\d))")))
        << r.out;
    EXPECT_EQ((*it)[2].str(), month_of(d[1])) << "docs/earth.md: `--time " << (*it)[1] << "`";
  }
  EXPECT_GE(shown, 1);
}

// The runs labelled `optimised` (left out of the sanitized suite) are as
// many as README.md and docs/reliability.md say.
TEST(StatedCounts, OptimisedRunsAreAsManyAsTheDocsSay) {
  const std::string list = source_file("tests/optimised_only.cmake");
  const std::size_t a = list.find("set(ibfvs_optimised_only"), b = list.find(')', a);
  ASSERT_NE(a, std::string::npos);
  int listed = 0;
  const std::string body = list.substr(a, b - a);
  static const std::regex entry(R"(\n\s+[A-Za-z]+\.[A-Za-z]+ [a-z]+)");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), entry);
       it != std::sregex_iterator(); ++it)
    ++listed;
  const std::string cmake = source_file("tests/CMakeLists.txt");
  int labelled = 0;
  for (std::size_t at = cmake.find(";optimised\""); at != std::string::npos;
       at = cmake.find(";optimised\"", at + 1))
    ++labelled;
  const int all = listed + labelled;
  EXPECT_GE(listed, 5);
  const std::map<std::string, int> words{{"five", 5},    {"six", 6},     {"seven", 7},
                                         {"eight", 8},   {"nine", 9},    {"ten", 10},
                                         {"eleven", 11}, {"twelve", 12}, {"thirteen", 13}};
  const auto stated = [&](const std::string& page, const std::string& pattern) {
    std::smatch m;
    const std::string text = source_file(page);
    if (!std::regex_search(text, m, std::regex(pattern))) {
      ADD_FAILURE() << page << " no longer says /" << pattern << "/";
      return -1;
    }
    const auto w = words.find(m[1]);
    return w == words.end() ? -1 : w->second;
  };
  EXPECT_EQ(stated("README.md", R"(less ([a-z]+) long runs)"), all);
  EXPECT_EQ(stated("docs/reliability.md", R"(Release suite: ([a-z]+) long runs)"), all);
  EXPECT_EQ(stated("docs/reliability.md", R"(\(([a-z]+) in `tests/optimised_only\.cmake`)"),
            listed);
}

// Every test docs/reliability.md names (`Suite.Name`) is one the suite has,
// and so is every test another page names of a suite the suite has.
TEST(StatedCounts, TheTestsTheDocsNameExist) {
  std::set<std::string> tests, suites;
  static const std::regex gtest(R"(TEST(?:_F)?\((\w+), (\w+)\))");
  static const std::regex ctest(R"(add_test\(NAME ([A-Za-z]+\.[A-Za-z]+))");
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(IBFVS_SOURCE_DIR) / "tests")) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".txt") continue;
    const std::string text = test::read_file(entry.path());
    for (auto it = std::sregex_iterator(text.begin(), text.end(), gtest);
         it != std::sregex_iterator(); ++it) {
      tests.insert((*it)[1].str() + "." + (*it)[2].str());
      suites.insert((*it)[1]);
    }
    for (auto it = std::sregex_iterator(text.begin(), text.end(), ctest);
         it != std::sregex_iterator(); ++it)
      tests.insert((*it)[1]);
  }
  ASSERT_GT(tests.size(), 100u);
  static const std::regex named(R"(`([A-Z][A-Za-z0-9]*)\.([A-Za-z][A-Za-z0-9]*)`)");
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(IBFVS_SOURCE_DIR) / "docs")) {
    if (entry.path().extension() != ".md") continue;
    const bool reliability = entry.path().filename() == "reliability.md";
    const std::string text = test::read_file(entry.path());
    for (auto it = std::sregex_iterator(text.begin(), text.end(), named);
         it != std::sregex_iterator(); ++it) {
      const std::string suite = (*it)[1], name = suite + "." + (*it)[2].str();
      if (!reliability && !suites.contains(suite)) continue;
      EXPECT_TRUE(tests.contains(name))
          << entry.path().filename() << " names `" << name << "`, which is no test";
      ++checked;
    }
  }
  EXPECT_GE(checked, 5);
}

// docs/cli.md's table of styles: each style's row names every number key
// the style sets away from the defaults by its value ("display filter 24
// px": filter 24), so that a style's change shows there or fails here.
TEST(StatedCounts, EachStylesRowStatesTheNumbersItSets) {
  const std::string cli = source_file("docs/cli.md");
  const Scene plain;
  int rows = 0;
  for (const EnumName<Style>& style : enum_entries<Style>()) {
    const std::string start = "\n| `" + std::string(style.name) + "` |";
    const std::size_t at = cli.find(start);
    ASSERT_NE(at, std::string::npos) << style.name << " has no row in docs/cli.md";
    const std::string row = cli.substr(at, cli.find('\n', at + 1) - at);
    Scene styled;
    apply_style(styled, style.value);
    for (const std::string_view key : changed_keys(plain, styled)) {
      const SceneKey* k = find_scene_key(key);
      if (!k || k->kind != KeyKind::Number) continue;
      for (const std::string& value : k->get(styled)) {
        const std::regex number("(^|[^0-9.])" +
                                std::regex_replace(value, std::regex(R"(\.)"), R"(\.)") +
                                "([^0-9.]|$)");
        EXPECT_TRUE(std::regex_search(row, number))
            << "docs/cli.md's row of style " << style.name << " does not state " << key << " "
            << value << ":\n"
            << row;
      }
    }
    ++rows;
  }
  EXPECT_EQ(rows, 8);
}

}  // namespace
}  // namespace ibfvs
