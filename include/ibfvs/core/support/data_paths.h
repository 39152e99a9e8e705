#pragma once
// Where the fetched data (scripts/fetch_data.sh) lives.

#include <filesystem>
#include <optional>

namespace ibfvs {

/// The data folder: $IBFVS_DATA_DIR, else the source tree's data/, else ./data.
std::filesystem::path data_dir();

/// data_dir()/relative if that file exists.
std::optional<std::filesystem::path> find_data_file(const std::filesystem::path& relative);

}  // namespace ibfvs
