// libFuzzer target: LAMMPS/LIGGGHTS dump parsing. Any input must give a frame or a
// ParseError, never a crash, a hang or a huge allocation.
#include "io/LammpsDump.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    for (const craterkit::DumpIndexEntry& e : craterkit::indexDump(text, "fuzz.dump"))
      craterkit::parseDumpSnapshot(text, e, "fuzz.dump");
  } catch (const craterkit::ParseError&) {
  }
  return 0;
}
