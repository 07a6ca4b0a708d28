#pragma once
// The foliage tools as pure operations on a FoliageStore: each takes the
// store, the ground and its parameters, changes the store and returns the
// undo data of the cells it touched (FoliageUndo: swap() undoes, a second
// swap() redoes) with counts and messages. The editor's brushes, the CLI
// and scripts call these; the document wraps the undo data in its step.
//
// Placement (docs/foliage.md, "Placement"): Poisson-disk dart throwing,
// deterministic for a seed. Candidates come in strata that walk the ground
// (64 m terrain tiles of the region's bounds, then the mesh triangles
// under it), as many per stratum as its area asks, each from a
// counter-based hash of (seed, type, index, attempt). Each is evaluated
// (surface point, filters, rotation, scale, quantised position) in
// parallel; then, in candidate order, one thread accepts those at least
// the type's spacing (3D) from every instance of that type already there
// (earlier strokes included, from the store) or accepted before (and, in a
// competing scatter, the mean spacing from other types), through a grid of
// cells the size of the spacing. A candidate refused for spacing is thrown
// again near its first throw (up to kAttempts); one the filters refuse is
// not (the filters thin the density, they do not move it). Ids follow the
// acceptance order. The result depends on the seed only, never on the
// number of threads.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "foliage/store.h"
#include "foliage/surface.h"

namespace hs::foliage {

constexpr int kAttempts = 4;
// An operation throws at most this many candidates per type (a density of
// 100 per m^2 over 0.5 km^2, 50 per hectare over 10,000 km^2); more is
// capped with a message, never an allocation that fails. They are thrown
// in batches of kBatch (all attempts of a batch, then the next), so the
// working memory is bounded by the batch, not the total.
constexpr double kMaxCandidates = 5e7;
constexpr uint64_t kBatch = uint64_t(1) << 22;

struct OpStats {
  size_t candidates = 0;       // thrown (first attempts)
  size_t outside = 0;          // off the region, the terrain or over a hole
  size_t filtered = 0;         // refused by slope, altitude or layer filters
  size_t spacingRejected = 0;  // thrown kAttempts times, always too close
  size_t placed = 0, removed = 0, moved = 0, changed = 0;
  std::vector<std::string> messages;  // what was capped, refused or dropped, naming the type
};

struct EditResult {
  FoliageUndo undo;
  OpStats stats;
  bool cancelled = false;  // by its Progress: the store is as it was, nothing to undo
};

// Types by index; empty: every type (erase, select) or none (paint).
using TypeSet = std::vector<uint16_t>;

struct PaintParams {
  Region2 region;              // a dab: Region2::disc(centre, radius)
  TypeSet types;               // one type or a set
  double densityFactor = 1.0;  // times each type's density (0..10)
  uint64_t seed = 0;
  unsigned threads = 0;        // 0: all allowed
  // Reports per batch of candidates and may cancel (paint, fill and
  // scatter: a cancelled edit changes nothing).
  const Progress* progress = nullptr;
};

// Adds instances of each type in the region up to its density: what is
// already there counts (a second dab over the same spot adds little), and
// the spacing holds against every instance of that type.
EditResult paint(FoliageStore& store, const Ground& ground, const PaintParams& p);
// paint() over an area (a rectangle, a lasso polygon): the fill tool. A
// type with a paint-layer filter fills only that layer's region.
EditResult fill(FoliageStore& store, const Ground& ground, const Region2& area, const TypeSet& types,
                uint64_t seed, unsigned threads = 0, const Progress* progress = nullptr);
// Fills a paint-layer region: the terrain where `layer` (a material name)
// weighs at least `minWeight`, within `area` (default: the whole terrain).
// Terrain only; the types' own filters apply too.
EditResult fillLayer(FoliageStore& store, const Ground& ground, const std::string& layer, double minWeight,
                     const TypeSet& types, uint64_t seed, const std::optional<Region2>& area = std::nullopt,
                     unsigned threads = 0, const Progress* progress = nullptr);
// The rule-based scatter: each type over the whole ground (or `area`), by
// its own rules (density, spacing, slope, altitude, layer, surface). With
// `compete`, the types compete for room in the order given (the first, the
// trees, win): an instance keeps from those of every other type in the set
// the mean of the two types' spacings (their collision radii added).
EditResult scatter(FoliageStore& store, const Ground& ground, const TypeSet& types, uint64_t seed,
                   const std::optional<Region2>& area = std::nullopt, unsigned threads = 0, bool compete = false,
                   const Progress* progress = nullptr);

// Removes the instances (of `types`; empty: all) whose XY lies in the region.
EditResult erase(FoliageStore& store, const Region2& region, const TypeSet& types = {});

// A selection: instance ids with the cells that hold them, sorted.
struct Selection {
  std::vector<std::pair<CellKey, uint32_t>> items;
  size_t size() const { return items.size(); }
  bool empty() const { return items.empty(); }
  std::vector<uint32_t> ids() const;
};
// The instance nearest to `point` in 3D within `radius` (a click's pick).
Selection selectPoint(const FoliageStore& store, const glm::dvec3& point, double radius, const TypeSet& types = {});
// Every instance whose XY lies in the region (a brush or a lasso polygon).
Selection selectRegion(const FoliageStore& store, const Region2& region, const TypeSet& types = {});

// Moves the selection by `offset`; with `snap`, each moved instance is put
// back on the surface it stands on (the terrain under its new XY, or the
// nearest mesh point); one that finds no surface there is left unmoved and
// counted. Ids stay; `selection` is updated to the new cells.
EditResult moveSelection(FoliageStore& store, const Ground& ground, Selection& selection, const glm::dvec3& offset,
                         bool snap);
EditResult deleteSelection(FoliageStore& store, Selection& selection);
// Re-evaluates the selected instances with their type's current settings:
// rotation, scale and sink drawn again (from `seed` and each id), the
// surface under them sampled again, and those the filters now refuse removed.
// `progress` may cancel: then the store and the selection are as they were.
EditResult reapply(FoliageStore& store, const Ground& ground, Selection& selection, uint64_t seed,
                   const Progress* progress = nullptr);

// The instance a type places at surface point `sp` (exposed for tests):
// rotation from yaw, pitch and alignment, scale, sink; from (seed, key).
Instance makeInstance(const FoliageType& t, uint16_t type, const SurfacePoint& sp, uint64_t seed, uint64_t key);
// Do the type's filters keep this point? `layerWeight` is the terrain's
// weight of the type's layer there (ignored without a layer filter, and
// for mesh points; not checked when !checkLayer).
bool passesFilters(const FoliageType& t, const SurfacePoint& sp, double layerWeight, bool checkLayer = true);
bool passesLayer(const FoliageType& t, double layerWeight);

}  // namespace hs::foliage
