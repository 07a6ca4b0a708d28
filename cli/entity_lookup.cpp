#include "cli/entity_lookup.h"

#include <charconv>

namespace hs::cli {

scene::EntityId findEntity(const scene::SceneState& scene, const std::string& who) {
  scene::EntityId id = scene.findByName(who);
  if (id == scene::kNoEntity) {
    // A number names an entity by id (from_chars: no exception on overflow).
    scene::EntityId n = 0;
    const auto r = std::from_chars(who.data(), who.data() + who.size(), n);
    if (r.ec == std::errc() && r.ptr == who.data() + who.size()) id = n;
  }
  return scene.find(id) ? id : scene::kNoEntity;
}

}  // namespace hs::cli
