#include "foliage/ground_follow.h"

#include <algorithm>
#include <cmath>

#include "foliage/surface.h"

namespace hs::foliage {

FoliageUndo followGround(FoliageStore& store, const terrain::Heightfield& before, const terrain::Heightfield& after,
                         const terrain::Region& changed, FollowStats* stats) {
  FoliageUndo undo;
  FollowStats st;
  if (changed.empty()) return undo;
  // The world rectangle of the cells around the changed samples (a
  // changed sample moves the triangles of the cells that share it), grown
  // by the largest sink so anchors inside it are found.
  double maxSink = 0.0;
  for (const FoliageType& t : store.types()) maxSink = std::max(maxSink, std::abs(t.sinkDepth));
  const glm::dvec2 o(after.origin()), s = after.spacing();
  const glm::dvec2 lo = o + glm::dvec2(changed.x0 - 1, changed.y0 - 1) * s - maxSink;
  const glm::dvec2 hi = o + glm::dvec2(changed.x1, changed.y1) * s + maxSink;
  const glm::dvec2 alo = o + glm::dvec2(changed.x0 - 1, changed.y0 - 1) * s;
  const glm::dvec2 ahi = o + glm::dvec2(changed.x1, changed.y1) * s;

  std::vector<Instance> moved;  // taken out of their cells, to add back
  for (const CellKey& k : store.cellsIn(lo, hi)) {
    const Cell* c = store.cell(k);
    // Decide per record first; edit the cell only when something changes.
    struct Change {
      size_t run, index;
      bool remove;
      Instance inst;
    };
    std::vector<Change> changes;
    for (size_t ri = 0; ri < c->runs.size(); ++ri) {
      const Run& r = c->runs[ri];
      if (r.surface != Surface::Terrain) continue;
      const FoliageType& t = store.type(r.type);
      for (size_t i = 0; i < r.items.size(); ++i) {
        Instance in = unpack(r.items[i], t.scaleMode, k);
        const glm::dvec3 up = in.rotation * glm::dvec3(0, 0, 1);
        const glm::dvec2 anchor = glm::dvec2(in.position + up * t.sinkDepth);
        if (anchor.x < alo.x || anchor.y < alo.y || anchor.x > ahi.x || anchor.y > ahi.y) continue;
        ++st.checked;
        const std::optional<SurfacePoint> now = terrainSurface(after, anchor);
        if (!now) {
          changes.push_back({ri, i, true, in});
          continue;
        }
        const std::optional<SurfacePoint> was = terrainSurface(before, anchor);
        if (was && was->position.z == now->position.z) continue;
        double offset = was ? in.position.z - was->position.z : -t.sinkDepth * up.z;
        if (std::abs(offset + t.sinkDepth * up.z) < 0.002) offset = -t.sinkDepth * up.z;
        in.type = r.type;
        in.surface = r.surface;
        in.position.z = now->position.z + offset;
        if (quantized(in.position) == unpackPosition(r.items[i], k)) continue;
        changes.push_back({ri, i, false, in});
      }
    }
    if (changes.empty()) continue;
    Cell& cell = store.edit(k, &undo);
    // Remove back to front per run, so indices stay valid.
    std::sort(changes.begin(), changes.end(),
              [](const Change& a, const Change& b) { return a.run != b.run ? a.run < b.run : a.index > b.index; });
    for (const Change& ch : changes) {
      auto& items = cell.runs[ch.run].items;
      items.erase(items.begin() + ptrdiff_t(ch.index));
      if (ch.remove)
        ++st.removed;
      else
        moved.push_back(ch.inst);
    }
  }
  // Back in, keeping ids (a record whose height left its cell moves cell).
  std::sort(moved.begin(), moved.end(), [](const Instance& a, const Instance& b) { return a.id < b.id; });
  for (const Instance& in : moved) store.add(in, &undo, true);
  st.moved = moved.size();
  store.prune(undo.keys());
  if (stats) *stats = st;
  return undo;
}

}  // namespace hs::foliage
