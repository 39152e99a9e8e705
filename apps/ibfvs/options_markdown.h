#pragma once
// docs/cli.md's tables: every command's options, generated from the command
// line itself (names, defaults, help texts; enum options list their names
// from the one name table per enum), so the docs cannot drift from it.

#include <string>

namespace CLI {
class App;
}

namespace ibfvs::app {

/// One Markdown section per subcommand of `app`: its description, then a
/// table of its options (name and value, default, meaning), in the order
/// `--help` lists them.
std::string options_markdown(const CLI::App& app);

}  // namespace ibfvs::app
