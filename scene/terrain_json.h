#pragma once
// Terrains in the scene description (the JSON part of a .hscene file and
// scene::canonicalJson): per terrain its id, name, grid (samples, spacing,
// size, double origin, CRS), materials, paint rules, and a summary of its
// tiles: which sparse tiles (holes, paint) exist and one content hash over
// every tile. The tiles themselves are blobs (terrain_file.h); the summary
// lets a load name a missing tile and lets tests compare documents by
// content without comparing hundreds of megabytes.
#include <string>

#include "core/json.h"
#include "scene/scene_state.h"

namespace hs::scene {

Json terrainsToJson(const SceneState& state);
// Adds the described terrains (the array at `path`, "terrains") to `state`
// with their grids made and every tile at its fill value (the file loader
// then decodes the blobs). False, with the first bad value's path in
// `reader`, when one is bad.
bool readTerrains(JsonReader& reader, const Json& json, const std::string& path, SceneState& state);

// Paint rules as the description writes them (also `terrain paint-rules
// --rules FILE`): objects with layer, enabled, use_altitude,
// altitude_min/max/blend, use_slope, slope_min/max/blend, strength.
Json paintRulesToJson(const std::vector<terrain::PaintRule>& rules);
// The array at `path` ("" for a rules file, "terrains[0].paint_rules" in a
// description) for a terrain of `layers` paint layers.
bool readPaintRules(JsonReader& reader, const Json& json, const std::string& path, int layers,
                    std::vector<terrain::PaintRule>& out);

// Tile presence as the description records it (a bit per tile, base64).
std::string tileBitmap(const std::vector<bool>& present);
std::vector<bool> tileBitmapFromText(const std::string& text, size_t tiles, bool& ok);

}  // namespace hs::scene
