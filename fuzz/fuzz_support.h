#pragma once
// What every harness shares: the fuzzer's bytes as a file (the readers take
// paths, as the command line gives them), and the one way a reader may fail:
// an InputError whose message names the file. Anything else (another
// exception, a crash, a sanitizer report, a mesh that breaks its own
// invariants) aborts, and libFuzzer keeps the input.

#include <unistd.h>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs::fuzz {

[[noreturn]] inline void fail(const std::string& why) {
  std::fprintf(stderr, "ibfvs fuzz: %s\n", why.c_str());
  std::abort();
}

/// The readers' limits in a harness (support/isolation.h): their children
/// may allocate 2 GiB (half of IBFVS_MEMORY_LIMIT), below libFuzzer's malloc
/// limit (the 2.5 GiB RSS limit), whose report would otherwise come from the
/// child; and run 5 s, within libFuzzer's -timeout of 20 s, so that a reader
/// that never finishes is the error line it is for a user, not a timeout.
inline void limit_readers() {
  setenv("IBFVS_MEMORY_LIMIT", "4G", 0);
  setenv("IBFVS_READER_SECONDS", "5", 0);
}

/// This process's own folder (several fuzzers run side by side).
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "ibfvs-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) fail("cannot make a temporary folder");
    return std::filesystem::path(pattern);
  }();
  return dir;
}

/// Writes the bytes to `name` in the scratch folder and returns its path.
inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size,
                                         std::string_view name) {
  const std::filesystem::path path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) fail("cannot write " + path.string());
  return path;
}

/// Runs `read`; an InputError is the expected failure, and its message must
/// name `named` (the file, or the setting) so that the user knows what is wrong.
template <class Read>
void expect_clean_failure(std::string_view named, Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.find(one_line(std::string(named))) == std::string::npos)
      fail("the error does not name " + excerpt(named, 200) + ": " + excerpt(message, 400));
    if (message.find('\n') != std::string::npos && message.find('\n') + 1 != message.size())
      fail("the error is not one line: " + excerpt(message, 400));
  }
}

/// What a reader that returned must guarantee: every index in range, finite
/// positions, one normal (unit or zero) and one value of every array per vertex.
inline void check_mesh(const TriMesh& m) {
  const std::size_t n = m.positions.size();
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] >= n) fail("a triangle index is out of range");
  for (const glm::vec3& p : m.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail("a position is not finite");
  if (!m.normals.empty() && m.normals.size() != n) fail("normals and positions differ in count");
  if (!m.vectors.empty() && m.vectors.size() != n) fail("vectors and positions differ in count");
  for (const auto& [name, values] : m.scalars)
    if (values.size() != n) fail("scalar array " + name + " has the wrong length");
  for (const auto& [name, values] : m.vector_arrays)
    if (values.size() != n) fail("vector array " + name + " has the wrong length");
}

}  // namespace ibfvs::fuzz
