// libFuzzer target: gzip decompression of dumps (output capped at 1032x the input).
#include "io/FileBytes.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)craterkit::gunzip(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.gz");
  } catch (const craterkit::ParseError&) {
  }
  return 0;
}
