#include "ibfvs/core/support/file_names.h"

#include <algorithm>
#include <cctype>
#include <system_error>

#include <unistd.h>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

PendingFile::PendingFile(std::filesystem::path path) : path_(std::move(path)) {
  const std::string ext = path_.extension().string();
  std::string name = ".";
  name += path_.filename().string();
  name += ".partial-";
  name += std::to_string(getpid());
  name += ext;
  temporary_ = path_.parent_path() / name;
}

PendingFile::~PendingFile() {
  if (committed_) return;
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
}

void PendingFile::commit() {
  std::error_code ec;
  std::filesystem::rename(temporary_, path_, ec);
  if (ec) {
    std::filesystem::remove(temporary_, ec);
    throw InputError(path_.string() + ": cannot write the file (" + ec.message() + ")");
  }
  committed_ = true;
}

bool same_file(const std::filesystem::path& output, const std::filesystem::path& input) {
  std::error_code ec;
  if (std::filesystem::equivalent(output, input, ec) && !ec) return true;
  const auto a = std::filesystem::weakly_canonical(output, ec);
  if (ec) return false;
  const auto b = std::filesystem::weakly_canonical(input, ec);
  return !ec && a == b;
}

}  // namespace ibfvs
