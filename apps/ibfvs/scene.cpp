#include "ibfvs/scene.h"

#include <cstdint>
#include <map>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "ibfvs/core/error.h"
#include "ibfvs/data_paths.h"

namespace ibfvs::app {
namespace {

// What a key's value may be.
enum class Kind {
  String,      // a string
  Integer,     // an integer
  Number,      // an integer or a float
  Flag,        // a boolean: true adds the flag
  Vector,      // an array of numbers (joined with commas) or a string
  Size,        // [W, H] or "WxH"
  StringList,  // a string or an array of strings: the option repeated
  Elements,    // an array of tables {a, b, rotational, radial, tangential, core}, or strings
  Time,        // an integer or a string "A:B"
};

const std::map<std::string, Kind>& keys() {
  static const std::map<std::string, Kind> k = {
      {"mesh", Kind::String},
      {"field", Kind::String},
      {"element", Kind::Elements},
      {"tangent", Kind::String},
      {"size", Kind::Size},
      {"frames", Kind::Integer},
      {"out", Kind::String},
      {"texture_out", Kind::String},
      {"alpha", Kind::Number},
      {"beta", Kind::Number},
      {"scale", Kind::Number},
      {"profile", Kind::String},
      {"vg", Kind::Number},
      {"spike_width", Kind::Number},
      {"seed", Kind::Integer},
      {"step", Kind::Number},
      {"dt", Kind::Number},
      {"image_normalize", Kind::Flag},
      {"inject", Kind::String},
      {"background", Kind::Vector},
      {"surface_color", Kind::Vector},
      {"color_by", Kind::String},
      {"color_map", Kind::String},
      {"color_range", Kind::Vector},
      {"beta_by", Kind::String},
      {"beta_range", Kind::Vector},
      {"scalar", Kind::StringList},
      {"time", Kind::Time},
      {"field_step", Kind::StringList},
      {"frames_per_step", Kind::Integer},
      {"camera", Kind::Vector},
      {"look_at", Kind::Vector},
      {"ortho", Kind::Flag},
      {"fov", Kind::Number},
      {"orbit", Kind::Number},
      {"advect_view", Kind::String},
      {"subdivide", Kind::Integer},
      {"fps", Kind::Number},
      {"displace", Kind::String},
      {"surface_image", Kind::String},
      {"style", Kind::String},
      {"init", Kind::String},
      {"lock_at", Kind::Integer},
      {"lock_camera", Kind::Vector},
      {"default_field", Kind::String},
      {"export", Kind::String},
      {"noise_space", Kind::String},
      {"quiet", Kind::Flag},
  };
  return k;
}

// ${data}: the fetched-data folder; ${scene}: the scene file's folder.
std::string expand(std::string s, const std::filesystem::path& scene) {
  const auto replace = [&s](const std::string& token, const std::string& by) {
    for (std::size_t p = s.find(token); p != std::string::npos; p = s.find(token, p + by.size()))
      s.replace(p, token.size(), by);
  };
  replace("${data}", data_dir().string());
  std::filesystem::path folder = scene.parent_path();
  replace("${scene}", folder.empty() ? std::string(".") : folder.string());
  return s;
}

// Appends `value` to `list`, with `separator` between items. (Written out
// because GCC 12 warns falsely, -Wrestrict, on "x" + std::string here.)
void append(std::string& list, const char* separator, const std::string& value) {
  if (!list.empty()) list += separator;
  list += value;
}

std::string number_text(const toml::node& n) {
  std::ostringstream out;
  if (const auto i = n.value<std::int64_t>(); i && n.is_integer())
    out << *i;
  else
    out << *n.value<double>();
  return out.str();
}

}  // namespace

bool is_scene_path(const std::string& arg) {
  return arg.size() > 5 && arg.compare(arg.size() - 5, 5, ".toml") == 0;
}

std::vector<std::string> scene_arguments(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string() + ": no such scene file");
  toml::table table;
  try {
    table = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw InputError(path.string() + ":" + std::to_string(e.source().begin.line) + ": " +
                     std::string(e.description()));
  }
  std::vector<std::string> args;
  for (const auto& [key_node, value] : table) {
    const std::string key(key_node.str());
    const std::string where = path.string() + ":" + std::to_string(value.source().begin.line);
    const auto it = keys().find(key);
    if (it == keys().end())
      throw InputError(where + ": unknown key '" + key + "' (see docs/scenes.md)");
    std::string option = "--" + key;
    for (char& c : option)
      if (c == '_') c = '-';
    const auto wrong = [&](const char* expected) {
      throw InputError(where + ": '" + key + "' must be " + expected);
    };
    const auto add = [&](const std::string& v) {
      args.push_back(option);
      args.push_back(v);
    };
    switch (it->second) {
      case Kind::String:
        if (!value.is_string()) wrong("a string");
        add(expand(*value.value<std::string>(), path));
        break;
      case Kind::Integer:
        if (!value.is_integer()) wrong("an integer");
        add(number_text(value));
        break;
      case Kind::Number:
        if (!value.is_number()) wrong("a number");
        add(number_text(value));
        break;
      case Kind::Time:
        if (value.is_integer())
          add(number_text(value));
        else if (value.is_string())
          add(*value.value<std::string>());
        else
          wrong("an integer or a string \"A:B\"");
        break;
      case Kind::Flag:
        if (!value.is_boolean()) wrong("true or false");
        if (*value.value<bool>()) args.push_back(option);
        break;
      case Kind::Vector:
      case Kind::Size: {
        if (value.is_string()) {
          add(*value.value<std::string>());
          break;
        }
        const toml::array* a = value.as_array();
        if (!a || a->empty()) wrong("an array of numbers or a string");
        std::string joined;
        for (const toml::node& n : *a) {
          if (!n.is_number()) wrong("an array of numbers or a string");
          append(joined, it->second == Kind::Size ? "x" : ",", number_text(n));
        }
        add(joined);
        break;
      }
      case Kind::StringList: {
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
      case Kind::Elements: {
        const toml::array* a = value.as_array();
        if (!a) wrong("an array of tables {a, b, rotational, radial, tangential, core}");
        for (const toml::node& n : *a) {
          if (n.is_string()) {
            add(*n.value<std::string>());
            continue;
          }
          const toml::table* t = n.as_table();
          if (!t) wrong("an array of tables {a, b, rotational, radial, tangential, core}");
          const std::string at = path.string() + ":" + std::to_string(n.source().begin.line);
          std::string text;
          for (const char* end : {"a", "b"}) {
            const toml::array* p = (*t)[end].as_array();
            if (!p || p->size() != 3)
              throw InputError(at + ": element '" + end + "' must be [x, y, z]");
            for (const toml::node& c : *p) {
              if (!c.is_number())
                throw InputError(at + ": element '" + end + "' must be [x, y, z]");
              append(text, ",", number_text(c));
            }
          }
          for (const char* s : {"rotational", "radial", "tangential"}) {
            const toml::node_view<const toml::node> v = (*t)[s];
            if (v && !v.is_number())
              throw InputError(at + ": element '" + std::string(s) + "' must be a number");
            append(text, ",", v ? number_text(*v.node()) : std::string("0"));
          }
          if (const auto core = (*t)["core"]) {
            if (!core.is_number()) throw InputError(at + ": element 'core' must be a number");
            append(text, ",", number_text(*core.node()));
          }
          for (const auto& [k, _] : *t) {
            const std::string name(k.str());
            if (name != "a" && name != "b" && name != "rotational" && name != "radial" &&
                name != "tangential" && name != "core")
              throw InputError(at + ": unknown element key '" + name + "'");
          }
          add(text);
        }
        break;
      }
    }
  }
  return args;
}

// Adds one option's value to a scene table, typed as the key table says.
static void add_value(toml::table& table, const std::string& key, Kind kind,
                      const std::string& value) {
  switch (kind) {
    case Kind::Integer:
      table.insert_or_assign(key, static_cast<std::int64_t>(std::stoll(value)));
      break;
    case Kind::Number:
      table.insert_or_assign(key, std::stod(value));
      break;
    case Kind::Vector:
    case Kind::Size: {
      toml::array a;
      const char separator = kind == Kind::Size ? 'x' : ',';
      std::stringstream parts(value);
      for (std::string part; std::getline(parts, part, separator);) a.push_back(std::stod(part));
      table.insert_or_assign(key, std::move(a));
      break;
    }
    case Kind::StringList:
    case Kind::Elements: {
      if (!table.contains(key)) table.insert(key, toml::array{});
      table[key].as_array()->push_back(value);
      break;
    }
    default:  // String, Time
      table.insert_or_assign(key, value);
      break;
  }
}

std::string scene_toml(const std::vector<std::string>& arguments) {
  toml::table table;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    std::string option = arguments[i], value;
    if (option == "-q") option = "--quiet";
    if (option.rfind("--", 0) != 0) throw InputError("scene: '" + option + "' is not an option");
    bool has_value = false;
    if (const std::size_t eq = option.find('='); eq != std::string::npos) {
      value = option.substr(eq + 1);
      option.resize(eq);
      has_value = true;
    }
    std::string key = option.substr(2);
    for (char& c : key)
      if (c == '-') c = '_';
    const auto it = keys().find(key);
    if (it == keys().end()) throw InputError("scene: scenes have no key for " + option);
    if (it->second == Kind::Flag) {
      table.insert_or_assign(key, has_value ? value != "false" : true);
      continue;
    }
    if (!has_value) {
      if (i + 1 >= arguments.size()) throw InputError("scene: " + option + " needs a value");
      value = arguments[++i];
    }
    try {
      add_value(table, key, it->second, value);
    } catch (const std::logic_error&) {  // stoll/stod: not a number
      throw InputError("scene: " + option + " '" + value + "' is not a valid value");
    }
  }
  std::ostringstream out;
  out << "# written by ibfvs view; render it with: ibfvs render THIS.toml\n" << table << "\n";
  return out.str();
}

}  // namespace ibfvs::app
