#include "ibfvs/options_markdown.h"

#include <string>

#include <CLI/CLI.hpp>

namespace ibfvs::app {
namespace {

// Table cells hold one line, and a bar would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out;
}

// The option as typed: its names, and a value's placeholder without the
// validator's range that --help appends (the meaning states it).
std::string usage(const CLI::Option& option) {
  if (option.get_positional()) return option.get_name(true, false) + " (first argument)";
  std::string out = option.get_name(false, true);
  // A flag's default value in braces (--no-x{false}) is CLI11's, not a name.
  for (std::size_t brace; (brace = out.find('{')) != std::string::npos;)
    out.erase(brace, out.find('}', brace) - brace + 1);
  for (std::size_t comma = out.find(','); comma != std::string::npos;
       comma = out.find(',', comma + 2))
    out.replace(comma, 1, ", ");
  if (option.get_type_size() != 0) {
    std::string type = option.get_type_name();
    type = type.substr(0, type.find_first_of(":("));
    if (!type.empty()) out += " " + type;
    if (option.get_expected_max() == CLI::detail::expected_max_vector_size) out += " ...";
  }
  return out;
}

}  // namespace

std::string options_markdown(const CLI::App& app) {
  std::string out;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    out += "### `ibfvs " + command->get_name() + "`\n\n" + command->get_description() + ".\n\n";
    out += "| option | default | meaning |\n|---|---|---|\n";
    for (const CLI::Option* option : command->get_options()) {
      // Hidden options (no group) and --help are not part of the table.
      if (option->get_group().empty() || option->get_name() == "--help") continue;
      const std::string value = option->get_default_str();
      out += "| `" + cell(usage(*option)) + "` | " +
             (value.empty() ? "" : "`" + cell(value) + "`") + " | " +
             cell(option->get_description()) + " |\n";
    }
    out += "\n";
  }
  return out;
}

}  // namespace ibfvs::app
