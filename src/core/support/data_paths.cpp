#include "ibfvs/core/support/data_paths.h"

#include <cstdlib>

namespace ibfvs {

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("IBFVS_DATA_DIR"); env && *env) return env;
  std::error_code ec;
  const std::filesystem::path source(IBFVS_SOURCE_DATA_DIR);
  if (std::filesystem::is_directory(source, ec)) return source;
  return "data";
}

std::optional<std::filesystem::path> find_data_file(const std::filesystem::path& relative) {
  std::error_code ec;
  const std::filesystem::path p = data_dir() / relative;
  if (std::filesystem::is_regular_file(p, ec)) return p;
  return std::nullopt;
}

}  // namespace ibfvs
