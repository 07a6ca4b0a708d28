// A sequence (keys, tracks, camera paths) from its JSON text.
#include <string_view>

#include "fuzz_target.h"
#include "sequencer/sequence_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string error;
  hs::sequencer::sequenceFromJsonText(std::string_view(reinterpret_cast<const char*>(data), size), error);
  return 0;
}
