// libFuzzer target: pkdgrav .ss parsing (and writing back what was read).
#include "io/PkdgravSs.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const craterkit::ParticleFrame f = craterkit::parseSs(bytes, "fuzz.ss", true);
    (void)craterkit::writeSs(f, true);
  } catch (const craterkit::InputError&) {
  }
  return 0;
}
