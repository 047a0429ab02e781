// libFuzzer target for the scene reader (campaigns/scene.h): the input bytes are the text of a
// scene file. Bad input must end in a fibrenet::InputError; any other exception, a crash or
// undefined behaviour is a finding. scripts/fuzz.sh builds and runs it (docs/reliability.md).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>

#include "campaigns/scene.h"
#include "engine/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    fibrenet::campaigns::ParseScene(text, "fuzz.toml");
  } catch (const fibrenet::InputError&) {
    // Bad input refused with a message: the expected outcome.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scene_fuzz: bad input escaped as a non-InputError exception: %s\n",
                 e.what());
    std::abort();
  }
  return 0;
}
