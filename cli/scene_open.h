#pragma once
// Every command opens its scene through here, so what the loader did besides
// reading (an interrupted save rolled back, out-of-range values clamped;
// scene/hscene_file.h LoadReport) reaches the user as warnings on stderr.
#include <optional>
#include <string>

#include "scene/scene_state.h"

namespace hs::cli {

std::optional<scene::SceneState> openScene(const std::string& path, std::string& error);

}  // namespace hs::cli
