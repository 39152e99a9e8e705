// Writes the plugin's server-manager XML from its template at build time,
// filling in what the scene keys' table (scene_keys(), scene.h) says, so
// that the representation's properties cannot drift from the library:
//   @KEY.default@  the key's default as ParaView takes it (a number; an
//                  enumeration's number; 1 or 0 for a flag)
//   @KEY.range@    min="MIN" max="MAX" of a number key's span
//   @KEY.entries@  an enumeration key's <Entry value="N" text="Name"/> lines, by number
//   @KEY.label@    the key's label (SceneKey::label) in title case
//   @KEY.host@     the key's host name (SceneKey::host), the property's name
//   @KEY.property@ a property's name, label, command and default:
//                  name="HOST" label="LABEL" command="SetHOST"
//                  number_of_elements="1" default_values="DEFAULT", HOST the
//                  key's host name (SceneKey::host), in a DoubleVectorProperty
//                  for a number key, else an IntVectorProperty
//   @page.triangles@  the most triangles a web page takes (WebPageLimits)
//   @topology.scale@, @topology.strength@, @topology.length@  the defaults
//                  of the topology's options (TopologyOptions), for
//                  Skin-Friction Topology
// and repeats a block for each of several names, first:
//   <!-- @each NAME NAME ... --> BLOCK <!-- @end -->  BLOCK once for each
//                  NAME, with @name@ in it replaced by the name
// Usage: ibfvs_paraview_xml TEMPLATE OUT [HEADER]. A placeholder for a key
// that does not exist or has no such part fails the build, naming it; so
// does a key with a host name but no @KEY.property@ in the template, and,
// given the representation's HEADER, a key whose Set<HOST>(double or int)
// it does not declare (ParaView's wrapping reads the setters from there).

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "ibfvs/core/fields/topology.h"
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
  if (part == "host") {
    if (key.host.empty()) throw std::runtime_error("has no host name");
    return std::string(key.host);
  }
  if (part == "property") {
    if (key.host.empty()) throw std::runtime_error("has no host name");
    const std::string host(key.host);
    return "name=\"" + host + "\" label=\"" + fill(key, "label", indent) + "\" command=\"Set" +
           host + "\"\n" + indent + "  number_of_elements=\"1\" default_values=\"" +
           fill(key, "default", indent) + "\"";
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

namespace {

// What text `path` holds ("" with `ok` false where it cannot be read).
std::string read_text(const char* path, bool& ok) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  ok = static_cast<bool>(in);
  return text.str();
}

// The element a placeholder at `at` stands in: the tag it opens.
std::string element_at(const std::string& xml, std::size_t at) {
  const std::size_t open = xml.rfind('<', at);
  if (open == std::string::npos) return {};
  const std::size_t end = xml.find_first_of(" \n", open);
  return xml.substr(open + 1, end - open - 1);
}

std::string property_element(const SceneKey& key) {
  return key.kind == KeyKind::Number ? "DoubleVectorProperty" : "IntVectorProperty";
}

// Every key with a host name has its property in the template and, given
// the representation's header, its Set<HOST> there with the property's
// type. One line on stderr for the first that does not, and false.
bool check_hosts(const char* template_path, const std::set<std::string_view>& properties,
                 const char* header_path) {
  std::map<std::string, std::string> setters;  // HOST -> its argument's type
  if (header_path) {
    bool ok = false;
    const std::string header = read_text(header_path, ok);
    if (!ok) {
      std::cerr << header_path << ": cannot read\n";
      return false;
    }
    const std::regex setter(R"(void\s+Set(\w+)\s*\(\s*(double|int)\b)");
    for (std::sregex_iterator it(header.begin(), header.end(), setter), end; it != end; ++it)
      setters[(*it)[1].str()] = (*it)[2].str();
  }
  for (const SceneKey& key : ibfvs::scene_keys()) {
    if (key.host.empty()) continue;
    if (!properties.contains(key.name)) {
      std::cerr << template_path << ": key '" << key.name << "' (" << key.host
                << ") has a host name but no @" << key.name << ".property@\n";
      return false;
    }
    const std::string type = key.kind == KeyKind::Number ? "double" : "int";
    const auto it = setters.find(std::string(key.host));
    if (header_path && (it == setters.end() || it->second != type)) {
      std::cerr << header_path << ": key '" << key.name << "' needs 'void Set" << key.host << "("
                << type << ")' here (ParaView's wrapping reads its setters from this header)\n";
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::cerr << "usage: ibfvs_paraview_xml TEMPLATE OUT [HEADER]\n";
    return 2;
  }
  bool read = false;
  const std::string text = read_text(argv[1], read);
  if (!read) {
    std::cerr << argv[1] << ": cannot read\n";
    return 1;
  }
  const std::string xml = expand_each(text);
  std::set<std::string_view> properties;  // the keys whose @KEY.property@ it holds
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
    if (m[1].str() == "topology") {
      const ibfvs::TopologyOptions options;
      const std::string part = m[2].str();
      if (part != "scale" && part != "strength" && part != "length")
        throw std::runtime_error(m[0].str() + ": no such option of the topology");
      out += ibfvs::format_number(static_cast<float>(part == "scale"      ? options.scale
                                                     : part == "strength" ? options.min_strength
                                                                          : options.min_length));
      continue;
    }
    const SceneKey* key = ibfvs::find_scene_key(m[1].str());
    try {
      if (!key) throw std::runtime_error("is no scene key");
      if (m[2].str() == "property") {
        if (element_at(xml, at) != property_element(*key))
          throw std::runtime_error("needs a " + property_element(*key) + ", not a " +
                                   element_at(xml, at));
        properties.insert(key->name);
      }
      out += fill(*key, m[2].str(), indent);
    } catch (const std::exception& e) {
      std::cerr << argv[1] << ": " << m[0].str() << ": '" << m[1].str() << "' " << e.what() << "\n";
      return 1;
    }
  }
  out += xml.substr(done);
  if (!check_hosts(argv[1], properties, argc == 4 ? argv[3] : nullptr)) return 1;
  std::ofstream file(argv[2], std::ios::binary);
  file << out;
  if (!file) {
    std::cerr << argv[2] << ": cannot write\n";
    return 1;
  }
  return 0;
}
