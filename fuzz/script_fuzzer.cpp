// read_script: the viewer's scripts (`ibfvs view --script FILE`).

#include "fuzz_support.h"
#include "ibfvs/script_runner.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ibfvs;
  const auto path = fuzz::write_input(data, size, "input.script");
  fuzz::expect_clean_failure(path.string(), [&] {
    const auto actions = app::read_script(path);
    for (std::size_t i = 1; i < actions.size(); ++i)
      if (actions[i].frame < actions[i - 1].frame) fuzz::fail("frames decrease");
  });
  return 0;
}
