// The settings' parsers, as the command line and scene files reach them:
// lines `key=value` through apply_setting (every key's own parser: --field
// specs, flow elements, sizes, colours, cameras, ...), the field spec
// through FieldSpec::parse and back through its text form, and the mesh
// key's generated surfaces (globe, torus, cylinder, landscape, relief)
// through load_mesh. Paths are kept out (no '/'): the fuzzer must not read
// the machine's files.

#include <string>

#include "fuzz_support.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/scene/mesh_source.h"
#include "ibfvs/core/scene/scene.h"

namespace {

bool is_generator(const std::string& spec) {
  for (const char* prefix : {"globe", "torus", "cylinder", "landscape", "relief:"})
    if (spec.rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ibfvs;
  const std::string input(reinterpret_cast<const char*>(data), size);
  Scene scene;
  std::size_t start = 0;
  while (start < input.size()) {
    std::size_t end = input.find('\n', start);
    if (end == std::string::npos) end = input.size();
    const std::string line = input.substr(start, end - start);
    start = end + 1;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    // A NUL cannot reach a setting from a command line or a scene file.
    if (line.find('\0') != std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    fuzz::expect_clean_failure(key, [&] { apply_setting(scene, key, value); });
    if (key == "field") {
      // Spec errors name the part that is wrong; the caller adds the key.
      fuzz::expect_clean_failure("", [&] {
        const FieldSpec spec = FieldSpec::parse(value);
        const FieldSpec again = FieldSpec::parse(spec.text());
        if (again.text() != spec.text()) fuzz::fail("FieldSpec text does not round-trip: " + value);
      });
    }
    if (key == "mesh" && is_generator(value) && value.find('/') == std::string::npos &&
        value.find('*') == std::string::npos) {
      fuzz::expect_clean_failure("", [&] {
        const LoadedMesh loaded = load_mesh(value, 0, false);
        fuzz::check_mesh(loaded.mesh);
      });
    }
  }
  return 0;
}
