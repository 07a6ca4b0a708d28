#pragma once
// Every command opens its scene through here, so what the loader did besides
// reading (an interrupted save rolled back, out-of-range values clamped;
// scene/hscene_file.h LoadReport) reaches the user as warnings on stderr.
#include <functional>
#include <optional>
#include <string>

#include "scene/scene_state.h"

namespace hs::scene {
class Document;
}

namespace hs::cli {

std::optional<scene::SceneState> openScene(const std::string& path, std::string& error);

// Opens `path` as a document, runs `edit` on it (the editor's undoable
// operation; it says whether it changed anything) and saves the scene when
// it did. False with `error` when the scene cannot be opened or saved.
bool editSceneFile(const std::string& path, const std::function<bool(scene::Document&)>& edit, bool& changed,
                   std::string& error);

}  // namespace hs::cli
