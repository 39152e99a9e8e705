#pragma once
// Internal to the core: the structure of OFF, OBJ and PLY files checked
// before OpenMesh reads them. Fuzzing found OpenMesh 9's readers looping
// forever (an OFF face of no vertices, a PLY header with a broken property
// line) and reading out of bounds (an OBJ face naming a normal not yet
// given); these checks walk the whole file once, as the format defines it,
// and throw InputError naming the file, the line and the problem, so that
// OpenMesh only ever sees well-formed input.

#include <cstdint>
#include <filesystem>
#include <string>

namespace ibfvs::detail {

/// An ASCII OFF file without comments (`text`), its counts in the header:
/// every vertex line has 3 or more numbers, every face line a vertex count of
/// 3 or more, that many indices below the vertex count, and numbers after.
void precheck_off(const std::filesystem::path& path, const std::string& text);

/// An OBJ file: v/vt/vn lines hold numbers, every index of a face (1-based,
/// or negative: counted back from the last given) names an element given
/// before it, in the forms i, i/t, i//n and i/t/n.
void precheck_obj(const std::filesystem::path& path);

/// A PLY file: a header of known keywords and types, then every element's
/// data, ASCII or binary (either byte order), walked to its end: list
/// lengths within the file, face indices below the vertex count.
void precheck_ply(const std::filesystem::path& path);

}  // namespace ibfvs::detail
