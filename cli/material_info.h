#pragma once
// Materials as `hybridscape-cli material list` and `info` show them: by
// name, with the asset they came with and every field of
// scene::materialFields() under the key `material set` takes.
#include "core/json.h"
#include "scene/scene_state.h"

namespace hs::cli {

// {"name": ..., "asset": <asset name or null>, "id": ..., <field key>: <value>, ...}
Json materialInfoJson(const scene::SceneState& s, const scene::Material& m);
// {"materials": [...]} in id order.
Json materialsInfoJson(const scene::SceneState& s);
// One block per material: its name, asset, then "  key: value" per field.
void printMaterials(const scene::SceneState& s);

}  // namespace hs::cli
