#pragma once
// Small helpers on file names shared by the readers, writers and commands.

#include <filesystem>
#include <string>

namespace ibfvs {

/// The extension with its dot, in lower case: "Cow.OFF" -> ".off", "x" -> "".
std::string lower_extension(const std::filesystem::path& path);

/// An output written whole or not at all: under a temporary name beside the
/// requested one (same folder, same extension, so that writers that go by
/// the extension still do), renamed to it by commit(). Destroyed without
/// commit() (an error, an exception, an interruption), the temporary is
/// removed and the requested path is untouched.
class PendingFile {
 public:
  explicit PendingFile(std::filesystem::path path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;
  /// Where to write: ".NAME.partial-PID.EXT" beside the requested path.
  [[nodiscard]] const std::filesystem::path& temporary() const { return temporary_; }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// Renames the temporary to the requested path. Throws InputError naming
  /// the path when that fails (the temporary is then removed).
  void commit();

 private:
  std::filesystem::path path_, temporary_;
  bool committed_ = false;
};

/// True when `output` names the same file as `input` (the same path, or an
/// existing file reached another way: a link, "./", "../").
bool same_file(const std::filesystem::path& output, const std::filesystem::path& input);

}  // namespace ibfvs
