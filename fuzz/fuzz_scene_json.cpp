// The scene description (the JSON a .hscene holds) from its text.
#include <string_view>

#include "fuzz_target.h"
#include "scene/scene_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string error;
  bool notJson = false;
  hs::scene::sceneFromJsonText(std::string_view(reinterpret_cast<const char*>(data), size), error, notJson);
  return 0;
}
