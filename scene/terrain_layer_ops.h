#pragma once
// Adding and removing a terrain's paint layers, each one undo step.
//
// The number of layers is part of the tiles (one weight grid per layer), so
// neither edit can be a plain value patch of TerrainAsset, and removing a
// layer rewrites the weights of every layer where it had weight. Both work
// on a copy-on-write clone of the terrain (terrain::Terrain::clone: O(tiles)
// pointer copies) in a new TerrainData, with its own tile hash cache (hashes
// are cached per layer index, which these edits shift), change the clone,
// and swap the asset's tiles pointer to it in one ScenePatch together with
// the materials and rules.
// Undo puts the old pointer back: the terrain exactly as it was, tile for
// tile, without hand-written inverse logic; tile commands (strokes) recorded
// before and after keep working on the object they were recorded on, since
// the undo stack reaches each in the state it was made in.
//
// Costs, why they are acceptable for a rare edit: the undo step keeps the
// old tiles alive (shared with the new ones until either side writes them,
// so it costs only what is painted or sculpted afterwards, at most one copy
// of the terrain); renderers see a new terrain object and upload it once.
#include <string>
#include <vector>

#include "scene/document.h"
#include "terrain/paint_rules.h"

namespace hs::scene::ops {

// Appends a layer with `material` and weight 0 everywhere. Returns its index,
// or -1 with `error` (16 layers already, unknown terrain, a job running).
int addTerrainLayer(Document& doc, TerrainId id, const terrain::Material& material, std::string& error);

// Removes `layer`: its weight goes to the other layers in proportion (to the
// base layer where it was alone), so weights still sum to exactly 1; its
// rules go, and rules of later layers follow them down one index. Refuses
// to remove the last layer.
bool removeTerrainLayer(Document& doc, TerrainId id, int layer, std::string& error);

// `rules` as they read after `layer` is removed (pure; the CLI and tests use it).
std::vector<terrain::PaintRule> rulesWithoutLayer(const std::vector<terrain::PaintRule>& rules, int layer);

}  // namespace hs::scene::ops
