// Writes the plugin's server-manager XML from its template at build time,
// filling in what the scene keys' table (scene_keys(), scene.h) says, so
// that the representation's properties cannot drift from the library:
//   @KEY.default@  the key's default as ParaView takes it (a number; an
//                  enumeration's number; 1 or 0 for a flag)
//   @KEY.range@    min="MIN" max="MAX" of a number key's span
//   @KEY.entries@  an enumeration key's <Entry value="N" text="Name"/> lines, by number
//   @KEY.label@    the key's label (SceneKey::label) in title case
//   @page.triangles@  the most triangles a web page takes (WebPageLimits)
// and repeats a block for each of several names, first:
//   <!-- @each NAME NAME ... --> BLOCK <!-- @end -->  BLOCK once for each
//                  NAME, with @name@ in it replaced by the name
// Usage: ibfvs_paraview_xml TEMPLATE OUT. A placeholder for a key that does
// not exist or has no such part fails the build, naming it.

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/text.h"
#include "ibfvs/page/web_page.h"

namespace {

using ibfvs::KeyKind;
using ibfvs::SceneKey;

std::string fill(const SceneKey& key, const std::string& part, const std::string& indent) {
  if (part == "range") {
    if (!key.range) throw std::runtime_error("has no range");
    return "min=\"" + ibfvs::format_number(key.range->min) + "\" max=\"" +
           ibfvs::format_number(key.range->max) + "\"";
  }
  if (part == "entries") {
    if (key.choices.empty()) throw std::runtime_error("is no enumeration");
    // By number, as ParaView lists them.
    std::vector<ibfvs::KeyChoice> choices = key.choices;
    std::sort(choices.begin(), choices.end(),
              [](const auto& a, const auto& b) { return a.value < b.value; });
    std::string out;
    for (const ibfvs::KeyChoice& c : choices) {
      std::string text(c.name);
      text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
      out += (out.empty() ? "" : "\n" + indent) + "<Entry value=\"" + std::to_string(c.value) +
             "\" text=\"" + text + "\"/>";
    }
    return out;
  }
  if (part == "label") {
    // Title case, as ParaView's labels are: each word's first letter but
    // the small words' and a unit's in brackets.
    std::string text(key.label), word;
    std::string out;
    std::istringstream words(text);
    for (bool first = true; words >> word; first = false) {
      const bool small = word == "in" || word == "of" || word == "and";
      if ((first || !small) && std::isalpha(static_cast<unsigned char>(word[0])))
        word[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(word[0])));
      out += (first ? "" : " ") + word;
    }
    return out;
  }
  if (part == "default") {
    const std::vector<std::string> shown = key.get(ibfvs::Scene{});
    if (shown.size() != 1) throw std::runtime_error("has no single default");
    if (key.kind == KeyKind::Flag) return shown.front() == "true" ? "1" : "0";
    for (const ibfvs::KeyChoice& c : key.choices)
      if (c.name == shown.front()) return std::to_string(c.value);
    return shown.front();
  }
  throw std::runtime_error("has no part '" + part + "'");
}

}  // namespace

// The template with its @each blocks written out.
std::string expand_each(const std::string& xml) {
  const std::regex block(R"(([ \t]*)<!-- @each ([A-Za-z ]+) -->\n([\s\S]*?)[ \t]*<!-- @end -->\n)");
  std::string out;
  std::size_t done = 0;
  for (std::sregex_iterator it(xml.begin(), xml.end(), block), end; it != end; ++it) {
    const std::smatch& m = *it;
    out += xml.substr(done, static_cast<std::size_t>(m.position(0)) - done);
    done = static_cast<std::size_t>(m.position(0) + m.length(0));
    std::istringstream names(m[2].str());
    for (std::string name; names >> name;)
      out += std::regex_replace(m[3].str(), std::regex("@name@"), name);
  }
  return out + xml.substr(done);
}

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: ibfvs_paraview_xml TEMPLATE OUT\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) {
    std::cerr << argv[1] << ": cannot read\n";
    return 1;
  }
  const std::string xml = expand_each(text.str());
  const std::regex placeholder(R"(@([a-z_]+)\.([a-z]+)@)");
  std::string out;
  std::size_t done = 0;
  for (std::sregex_iterator it(xml.begin(), xml.end(), placeholder), end; it != end; ++it) {
    const std::smatch& m = *it;
    const std::size_t at = static_cast<std::size_t>(m.position(0));
    out += xml.substr(done, at - done);
    done = at + static_cast<std::size_t>(m.length(0));
    const std::size_t line = xml.rfind('\n', at) + 1;
    const std::string indent = xml.substr(line, xml.find_first_not_of(' ', line) - line);
    if (m[0].str() == "@page.triangles@") {
      out += std::to_string(ibfvs::WebPageLimits{}.triangles);
      continue;
    }
    const SceneKey* key = ibfvs::find_scene_key(m[1].str());
    try {
      if (!key) throw std::runtime_error("is no scene key");
      out += fill(*key, m[2].str(), indent);
    } catch (const std::exception& e) {
      std::cerr << argv[1] << ": " << m[0].str() << ": '" << m[1].str() << "' " << e.what() << "\n";
      return 1;
    }
  }
  out += xml.substr(done);
  std::ofstream file(argv[2], std::ios::binary);
  file << out;
  if (!file) {
    std::cerr << argv[2] << ": cannot write\n";
    return 1;
  }
  return 0;
}
