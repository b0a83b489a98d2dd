// libFuzzer target of the scene parser: any text is either a Scene or a SceneError. Each scene it
// makes also goes through the memory estimate (regions built and sampled, run/memory_estimate.hpp),
// which `rift check` and `rift run` do before anything else. Any other exception, a crash, a hang or
// a sanitizer report is a bug: `tests/fuzz/run` keeps its input in tests/fuzz/regressions/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "rift/core/error.hpp"
#include "rift/run/memory_estimate.hpp"
#include "rift/scene/parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto scene = rift::scene::parse_string(text, "fuzz.toml");
    (void)rift::run::estimate_memory(scene);
  } catch (const rift::SceneError&) {
  }
  return 0;
}
