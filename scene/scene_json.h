#pragma once
// The scene description as JSON: the text part of a .hscene file, and the
// canonical form tests compare documents by. Bulk data (mesh arrays,
// textures) is not in it; assets carry their content hash instead.
#include <optional>
#include <string>

#include <QJsonObject>

#include "scene/scene_state.h"

namespace hs::scene {

// 2: terrains (description "terrains", tile blobs "terrain/<id>/..."). A
// version-1 reader would drop them silently, so it is told the file is newer.
// 3: mesh LODs (assets' "lods", blobs "mesh/<id>/lod<k>") and processing
// reports; a version-2 reader would drop the LODs on its next save.
constexpr int kSceneFormatVersion = 4;

QJsonObject sceneToJson(const SceneState& state);
// Canonical compact text of sceneToJson (stable key order and number format).
std::string canonicalJson(const SceneState& state);

// Reads a description. Assets come back without mesh data (the file loader
// fills it from blobs). On failure returns nullopt and sets `error`, naming
// the JSON path of the bad value ("entities[3].transform.scale").
std::optional<SceneState> sceneFromJson(const QJsonObject& json, std::string& error);

}  // namespace hs::scene
