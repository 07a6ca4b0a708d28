#pragma once
// The terrains part of `hybridscape-cli info`: size in metres, resolution,
// spacing, origin, height range, CRS, layers, holes, memory.
#include "core/json.h"

#include "scene/scene_state.h"

namespace hs::cli {

Json terrainInfoJson(const scene::SceneState& s);
void printTerrainInfo(const scene::SceneState& s);

}  // namespace hs::cli
