#include "app/foliage_ground_cache.h"

#include "app/busy_cursor.h"

namespace hs::app {

FoliageGroundCache::FoliageGroundCache(scene::Document& doc, QObject* parent) : QObject(parent), doc_(doc) {
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    // Anything that may move, add or remove a surface: entities (a
    // transform, visibility, a mesh component), assets, terrain tiles (the
    // ground holds a copy-on-write clone of the heights as they were).
    // Foliage edits alone leave the ground as it is.
    if (c.reset || c.hierarchy || c.assets || !c.entities.empty() || !c.terrains.empty()) ground_.reset();
  });
}

FoliageGroundCache::~FoliageGroundCache() = default;

const scene::FoliageGround& FoliageGroundCache::ground() {
  if (!ground_) {
    const BusyCursor busy;
    ground_ = std::make_shared<const scene::FoliageGround>(doc_.state());
    ++builds_;
  }
  return *ground_;
}

std::shared_ptr<const scene::FoliageGround> FoliageGroundCache::shared() {
  ground();
  return ground_;
}

}  // namespace hs::app
