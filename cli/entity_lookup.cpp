#include "cli/entity_lookup.h"

#include "core/params.h"

namespace hs::cli {

scene::EntityId findEntity(const scene::SceneState& scene, const std::string& who) {
  scene::EntityId id = scene.findByName(who);
  if (id == scene::kNoEntity) {
    // A whole number names an entity by id. Ids count up from 1, far below
    // 2^53, where a double (how numbers are read) stops being exact.
    static const ParamDecl kId{.key = "id", .label = "entity id", .min = 1, .max = 9007199254740992.0,
                               .integer = true};
    std::string unused;
    if (const std::optional<Json> n = parseParam(kId, who, unused)) id = n->get<scene::EntityId>();
  }
  return scene.find(id) ? id : scene::kNoEntity;
}

}  // namespace hs::cli
