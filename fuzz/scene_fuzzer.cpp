// read_scene: a TOML scene file (toml++), every key through the scene's own
// setters, then the scene written back as TOML and read again, which must
// give the same text.

#include "fuzz_support.h"
#include "ibfvs/core/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ibfvs;
  const auto path = fuzz::write_input(data, size, "input.toml");
  fuzz::expect_clean_failure(path.string(), [&] {
    const Scene scene = read_scene(path);
    const std::string text = scene_toml(scene);
    const std::string bytes(text);
    const auto again = fuzz::write_input(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                         bytes.size(), "again.toml");
    Scene round;
    try {
      round = read_scene(again);
    } catch (const InputError& e) {
      fuzz::fail(std::string("scene_toml wrote a scene that does not read back: ") + e.what() +
                 "\n" + text);
    }
    if (scene_toml(round) != text) fuzz::fail("scene_toml does not round-trip:\n" + text);
  });
  return 0;
}
