// Scene files (TOML): reading one into settings by name, and writing a
// scene as one (only the keys that differ from the defaults).
#include <algorithm>
#include <sstream>

#include <toml++/toml.h>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/data_paths.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/limits.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {

namespace {

// A default Scene, for "is this value the default?".
const Scene& defaults() {
  static const Scene d;
  return d;
}

// ${data}: the fetched-data folder; ${scene}: the scene file's folder.
std::string expand(std::string s, const std::filesystem::path& scene) {
  const auto replace = [&s](const std::string& token, const std::string& by) {
    for (std::size_t p = s.find(token); p != std::string::npos; p = s.find(token, p + by.size()))
      s.replace(p, token.size(), by);
  };
  replace("${data}", data_dir().string());
  const std::filesystem::path folder = scene.parent_path();
  replace("${scene}", folder.empty() ? std::string(".") : folder.string());
  return s;
}

std::string number_text(const toml::node& n) {
  if (n.is_integer()) return std::to_string(*n.value<std::int64_t>());
  return format_number(*n.value<double>());
}

// Appends `value` to `list`, with `separator` between items.
void append(std::string& list, const char* separator, const std::string& value) {
  if (!list.empty()) list += separator;
  list += value;
}

// A flow element written as a table {a, b, rotational, radial, tangential, core}.
std::string element_text(const toml::table& t, const std::string& at) {
  std::string text;
  for (const char* end : {"a", "b"}) {
    const toml::array* p = t[end].as_array();
    if (!p || p->size() != 3) throw InputError(at + ": element '" + end + "' must be [x, y, z]");
    for (const toml::node& c : *p) {
      if (!c.is_number()) throw InputError(at + ": element '" + end + "' must be [x, y, z]");
      append(text, ",", number_text(c));
    }
  }
  for (const char* s : {"rotational", "radial", "tangential"}) {
    const auto v = t[s];
    if (v && !v.is_number())
      throw InputError(at + ": element '" + std::string(s) + "' must be a number");
    append(text, ",", v ? number_text(*v.node()) : std::string("0"));
  }
  if (const auto core = t["core"]) {
    if (!core.is_number()) throw InputError(at + ": element 'core' must be a number");
    append(text, ",", number_text(*core.node()));
  }
  for (const auto& [k, unused] : t) {
    const std::string name(k.str());
    if (name != "a" && name != "b" && name != "rotational" && name != "radial" &&
        name != "tangential" && name != "core")
      throw InputError(at + ": unknown element key '" + name + "'");
  }
  return text;
}

}  // namespace

bool is_scene_path(std::string_view path) {
  return path.size() > 5 && path.substr(path.size() - 5) == ".toml";
}

std::vector<Setting> read_scene_settings(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string() + ": no such scene file");
  toml::table table;
  try {
    table = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw InputError(path.string() + ":" + std::to_string(e.source().begin.line) + ": " +
                     one_line(std::string(e.description())));
  }
  std::vector<Setting> out;
  for (const auto& [key_node, value] : table) {
    const std::string key(key_node.str());
    const std::string where = path.string() + ":" + std::to_string(value.source().begin.line);
    const SceneKey* k = find_scene_key(key);
    if (!k) throw InputError(where + ": unknown key " + excerpt(key) + " (see docs/scenes.md)");
    const auto wrong = [&](const char* expected) {
      throw InputError(where + ": " + excerpt(key) + " must be " + expected);
    };
    const auto add = [&](const std::string& text) { out.push_back({key, text, where}); };
    switch (k->kind) {
      case KeyKind::String:
        if (!value.is_string()) wrong("a string");
        add(expand(*value.value<std::string>(), path));
        break;
      case KeyKind::Integer:
        if (!value.is_integer()) wrong("an integer");
        add(number_text(value));
        break;
      case KeyKind::Number:
        if (!value.is_number()) wrong("a number");
        add(number_text(value));
        break;
      case KeyKind::Time:
        if (value.is_integer())
          add(number_text(value));
        else if (value.is_string())
          add(*value.value<std::string>());
        else
          wrong("an integer or a string");
        break;
      case KeyKind::Flag:
        if (!value.is_boolean()) wrong("true or false");
        add(*value.value<bool>() ? "true" : "false");
        break;
      case KeyKind::Vector:
      case KeyKind::Size: {
        if (value.is_string()) {
          add(*value.value<std::string>());
          break;
        }
        const toml::array* a = value.as_array();
        if (!a || a->empty()) wrong("an array of numbers or a string");
        std::string joined;
        for (const toml::node& n : *a) {
          if (!n.is_number()) wrong("an array of numbers or a string");
          append(joined, k->kind == KeyKind::Size ? "x" : ",", number_text(n));
        }
        add(joined);
        break;
      }
      case KeyKind::StringList: {
        if (value.is_string()) {
          add(expand(*value.value<std::string>(), path));
          break;
        }
        const toml::array* a = value.as_array();
        if (!a) wrong("a string or an array of strings");
        for (const toml::node& n : *a) {
          if (!n.is_string()) wrong("a string or an array of strings");
          add(expand(*n.value<std::string>(), path));
        }
        break;
      }
      case KeyKind::Elements: {
        const toml::array* a = value.as_array();
        if (!a) wrong("an array of tables {a, b, rotational, radial, tangential, core}");
        for (const toml::node& n : *a) {
          if (n.is_string()) {
            add(*n.value<std::string>());
            continue;
          }
          const toml::table* t = n.as_table();
          if (!t) wrong("an array of tables {a, b, rotational, radial, tangential, core}");
          add(element_text(*t, path.string() + ":" + std::to_string(n.source().begin.line)));
        }
        break;
      }
    }
  }
  return out;
}

Scene read_scene(const std::filesystem::path& path) {
  Scene scene;
  apply_settings(scene, read_scene_settings(path));
  return scene;
}

std::string scene_toml(const Scene& scene) {
  toml::table table;
  for (const SceneKey& k : scene_keys()) {
    const std::vector<std::string> texts = k.get(scene);
    if (texts.empty() || texts == k.get(defaults())) continue;
    const std::string key(k.name);
    const std::string& text = texts.front();
    switch (k.kind) {
      case KeyKind::Integer:
        table.insert_or_assign(
            key, static_cast<std::int64_t>(parse_integer(text, INT64_MIN + 1, INT64_MAX)));
        break;
      case KeyKind::Number:
        table.insert_or_assign(key, parse_number(text));
        break;
      case KeyKind::Flag:
        table.insert_or_assign(key, text == "true");
        break;
      case KeyKind::Size:
      case KeyKind::Vector: {
        // Numbers as a TOML array; other forms (auto, percentiles) as text.
        toml::array a;
        try {
          for (float v : parse_numbers(text)) a.push_back(static_cast<double>(v));
        } catch (const InputError&) {
          a.clear();
        }
        if (k.kind == KeyKind::Size) {
          const std::size_t x = text.find('x');
          a.clear();
          a.push_back(
              static_cast<std::int64_t>(parse_integer(text.substr(0, x), 1, kMaxImageSide)));
          a.push_back(
              static_cast<std::int64_t>(parse_integer(text.substr(x + 1), 1, kMaxImageSide)));
        }
        if (a.empty())
          table.insert_or_assign(key, text);
        else
          table.insert_or_assign(key, std::move(a));
        break;
      }
      case KeyKind::StringList:
      case KeyKind::Elements: {
        toml::array a;
        for (const std::string& t : texts) a.push_back(t);
        table.insert_or_assign(key, std::move(a));
        break;
      }
      case KeyKind::Time:
        if (text.find_first_not_of("0123456789-") == std::string::npos)
          table.insert_or_assign(key,
                                 static_cast<std::int64_t>(parse_integer(text, -1, INT64_MAX)));
        else
          table.insert_or_assign(key, text);
        break;
      case KeyKind::String:
        table.insert_or_assign(key, text);
        break;
    }
  }
  std::ostringstream out;
  out << "# an ibfvs scene (docs/scenes.md); render it with: ibfvs render THIS.toml\n"
      << table << "\n";
  return out.str();
}

}  // namespace ibfvs
