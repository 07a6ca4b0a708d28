#include "foliage/tools.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "core/params.h"
#include "core/parallel.h"

namespace hs::foliage {

namespace {

constexpr double kPi = 3.14159265358979323846;

uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
uint64_t key4(uint64_t a, uint64_t b, uint64_t c, uint64_t d) { return mix(a ^ mix(b ^ mix(c ^ mix(d)))); }
double unit(uint64_t h) { return double(h >> 11) * (1.0 / 9007199254740992.0); }
double unitOf(uint64_t key, uint64_t j) { return unit(mix(key ^ mix(j + 0x51ED27ull))); }

bool inSet(const TypeSet& set, uint16_t t) { return set.empty() || std::find(set.begin(), set.end(), t) != set.end(); }

std::string typeContext(const FoliageType& t) { return "foliage type \"" + t.name + "\""; }

// Points near a stroke, each with the distance it keeps (the type's own
// spacing; between competing types the mean of their spacings), in cells
// as large as the largest distance: the Poisson test's neighbour search.
// Dense (an array of at most 2^24 cell heads, cells up to 4x the distance
// wide); past that (a region spanning a terrain and a distant scan) sparse,
// a hash map of the cells that hold points, so memory and time follow the
// points, not the region.
class PoissonGrid {
 public:
  PoissonGrid(const glm::dvec2& lo, const glm::dvec2& hi, double maxRadius) : lo_(lo) {
    if (!(maxRadius > 0.0)) return;  // no spacing: never asked
    const glm::dvec2 ext = glm::max(hi - lo, glm::dvec2(1e-9));
    // Dense cells may grow up to 4x the distance to stay within 2^24.
    cell_ = std::max(maxRadius, std::sqrt(ext.x * ext.y / double(1 << 24)));
    sparse_ = cell_ > 4.0 * maxRadius;
    if (sparse_) cell_ = maxRadius;
    const double nx = std::floor(ext.x / cell_) + 1.0, ny = std::floor(ext.y / cell_) + 1.0;
    nx_ = int(std::min(nx, 2e9));
    ny_ = int(std::min(ny, 2e9));
    if (!sparse_) head_.assign(size_t(nx_) * size_t(ny_), -1);
  }
  void insert(const glm::dvec3& p, double radius) {
    if (!(radius > 0.0) || !(cell_ > 0.0)) return;
    int32_t& h = headAt(cx(p.x), cy(p.y));
    pts_.push_back({p, radius * radius});
    next_.push_back(h);
    h = int32_t(pts_.size() - 1);
  }
  // Is p closer (3D) to any point than that point's distance?
  bool conflicts(const glm::dvec3& p) const {
    if (pts_.empty()) return false;
    const int x = cx(p.x), y = cy(p.y);
    for (int yy = std::max(0, y - 1); yy <= std::min(ny_ - 1, y + 1); ++yy)
      for (int xx = std::max(0, x - 1); xx <= std::min(nx_ - 1, x + 1); ++xx)
        for (int32_t i = headOf(xx, yy); i >= 0; i = next_[size_t(i)]) {
          const glm::dvec3 d = pts_[size_t(i)].p - p;
          if (glm::dot(d, d) < pts_[size_t(i)].r2) return true;
        }
    return false;
  }

 private:
  struct Point {
    glm::dvec3 p;
    double r2;
  };
  int cx(double x) const { return int(std::clamp(std::floor((x - lo_.x) / cell_), 0.0, double(nx_ - 1))); }
  int cy(double y) const { return int(std::clamp(std::floor((y - lo_.y) / cell_), 0.0, double(ny_ - 1))); }
  static uint64_t key(int x, int y) { return (uint64_t(uint32_t(x)) << 32) | uint32_t(y); }
  int32_t& headAt(int x, int y) {
    if (!sparse_) return head_[size_t(y) * size_t(nx_) + size_t(x)];
    return sparseHead_.try_emplace(key(x, y), -1).first->second;
  }
  int32_t headOf(int x, int y) const {
    if (!sparse_) return head_[size_t(y) * size_t(nx_) + size_t(x)];
    auto it = sparseHead_.find(key(x, y));
    return it == sparseHead_.end() ? -1 : it->second;
  }
  glm::dvec2 lo_;
  double cell_ = 0.0;
  int nx_ = 1, ny_ = 1;
  bool sparse_ = false;
  std::vector<int32_t> head_, next_;
  std::unordered_map<uint64_t, int32_t> sparseHead_;
  std::vector<Point> pts_;
};

// Every instance of `type` whose XY lies in [lo, hi].
template <class Fn>
void forEachOfType(const FoliageStore& store, uint16_t type, const glm::dvec2& lo, const glm::dvec2& hi, Fn&& fn) {
  store.forEachCellIn(lo, hi, [&](const CellKey& k, const Cell& c) {
    for (const Run& r : c.runs)
      if (r.type == type)
        for (const PackedInstance& p : r.items) {
          const glm::dvec3 pos = unpackPosition(p, k);
          if (pos.x >= lo.x && pos.x <= hi.x && pos.y >= lo.y && pos.y <= hi.y) fn(pos, p, r.surface);
        }
  });
}

// A candidate that passed the filters: where and how it would stand.
struct Evaluated {
  uint32_t slot;      // index into the attempt's pending list
  uint32_t rot;       // packed rotation
  uint16_t scale;     // packed scale
  Surface surface;
  glm::dvec3 position;  // quantised
};

// A paint-layer region: the terrain where `layer` weighs at least `min`.
struct LayerMask {
  int layer = -1;
  double min = 0.5;
};

// The area of the mask within the region: the terrain cells whose centre
// is in both.
double maskedArea(const terrain::Terrain& tr, const Region2& region, const LayerMask& mask) {
  glm::dvec2 lo, hi;
  region.bounds(lo, hi);
  const terrain::Heightfield& hf = tr.height;
  const glm::dvec2 o(hf.origin()), sp = hf.spacing();
  const int x0 = std::max(0, int(std::floor((lo.x - o.x) / sp.x))), y0 = std::max(0, int(std::floor((lo.y - o.y) / sp.y)));
  const int x1 = std::min(hf.samplesX() - 2, int(std::ceil((hi.x - o.x) / sp.x)));
  const int y1 = std::min(hf.samplesY() - 2, int(std::ceil((hi.y - o.y) / sp.y)));
  size_t cells = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const glm::dvec2 c = o + (glm::dvec2(x, y) + 0.5) * sp;
      cells += region.contains(c) && terrainLayerWeight(tr, mask.layer, c) >= mask.min;
    }
  return double(cells) * sp.x * sp.y;
}

void placeType(FoliageStore& store, const Ground& ground, uint16_t type, const Region2& region, double factor,
               uint64_t seed, unsigned threads, EditResult& res, const LayerMask* mask,
               const TypeSet& competitors = {}, const Progress* progress = nullptr) {
  const FoliageType& t = store.type(type);
  OpStats& st = res.stats;
  const std::string ctx = typeContext(t);
  const double perM2 = t.densityPerHa * std::clamp(factor, 0.0, 10.0) / 1e4;
  if (!(perM2 > 0.0)) {
    st.messages.push_back(ctx + ": density 0: nothing placed");
    return;
  }
  glm::dvec2 lo, hi;
  region.bounds(lo, hi);
  const double regionArea = mask ? maskedArea(*ground.terrain, region, *mask) : region.area();
  if (!(regionArea > 0.0)) {
    st.messages.push_back(ctx + (mask ? ": the paint layer covers none of the region: nothing placed"
                                      : ": the region is empty (radius or area 0): nothing placed"));
    return;
  }
  auto inMask = [&](const glm::dvec2& xy) {
    return !mask || terrainLayerWeight(*ground.terrain, mask->layer, xy) >= mask->min;
  };
  const double r = t.spacing;
  double maxR = r;
  for (uint16_t c : competitors)
    if (c != type && c < store.types().size()) maxR = std::max(maxR, 0.5 * (store.type(c).spacing + r));
  const double margin = maxR + std::abs(t.sinkDepth) + 1.0;
  // What is there already: the Poisson grid (this type's instances, and
  // those of competing types at the mean of the two spacings), and the
  // share of the density still missing in the region.
  PoissonGrid grid(lo - margin, hi + margin, maxR);
  size_t existing = 0;
  forEachOfType(store, type, lo - margin, hi + margin, [&](const glm::dvec3& pos, const PackedInstance&, Surface) {
    grid.insert(pos, r);
    if (region.contains(glm::dvec2(pos)) && inMask(glm::dvec2(pos))) ++existing;
  });
  for (uint16_t c : competitors)
    if (c != type && c < store.types().size()) {
      const double rc = 0.5 * (store.type(c).spacing + r);
      forEachOfType(store, c, lo - margin, hi + margin,
                    [&](const glm::dvec3& pos, const PackedInstance&, Surface) { grid.insert(pos, rc); });
    }
  const bool useGrid = maxR > 0.0;
  const double target = perM2 * regionArea;
  const double share = std::max(0.0, 1.0 - double(existing) / target);
  if (share <= 0.0) return;

  int layer = -1;
  if (!t.layer.empty() && ground.terrain && t.surface != SurfaceFilter::Meshes) {
    layer = terrainLayerIndex(*ground.terrain, t.layer);
    if (layer < 0) {
      st.messages.push_back(ctx + ": layer: the terrain has no paint layer \"" + t.layer +
                            "\"; nothing placed on the terrain");
    }
  }
  const bool onTerrain = ground.terrain && t.surface != SurfaceFilter::Meshes && (t.layer.empty() || layer >= 0);
  const bool onMeshes = t.surface != SurfaceFilter::Terrain && !mask;

  // Candidates by strata, in an order that walks the ground (so the
  // surface reads and the Poisson grid stay in cache): the terrain part of
  // the region's bounds in 64 m tiles, row by row, then each mesh's
  // triangles under the region in index order. A stratum gets candidates
  // in proportion to its area (tile area; triangle area), by cumulative
  // rounding from a seeded offset, so the total is the expected count.
  const uint64_t typeKey = key4(seed, type, 0x7E11ull, 0);
  struct Stratum {
    const MeshGround* mesh;  // null: a terrain tile
    uint32_t face;
    glm::dvec2 lo, hi;       // a terrain tile's rectangle
  };
  std::vector<Stratum> strata;
  std::vector<double> weights;  // areas
  if (onTerrain) {
    // Over the part of the region's bounds the terrain covers (a region
    // reaching far off the terrain, such as the bounds of a terrain and a
    // distant scan, costs nothing there), in at most 2^20 tiles.
    const glm::dvec2 to(ground.terrain->height.origin());
    const glm::dvec2 tlo = glm::max(lo, to), thi = glm::min(hi, to + ground.terrain->height.sizeMetres());
    const glm::dvec2 ext = glm::max(thi - tlo, glm::dvec2(0.0));
    const double tile = std::max({64.0, 2.0 * r, std::sqrt(ext.x * ext.y / double(1 << 20))});
    const int tx = thi.x > tlo.x ? std::max(1, int(std::ceil(ext.x / tile))) : 0;
    const int ty = thi.y > tlo.y ? std::max(1, int(std::ceil(ext.y / tile))) : 0;
    for (int y = 0; y < ty; ++y)
      for (int x = 0; x < tx; ++x) {
        const glm::dvec2 a = tlo + glm::dvec2(x, y) * tile, b = glm::min(a + tile, thi);
        if (b.x > a.x && b.y > a.y) {
          strata.push_back({nullptr, 0, a, b});
          weights.push_back((b.x - a.x) * (b.y - a.y));
        }
      }
  }
  if (onMeshes) {
    std::vector<uint32_t> faces;
    for (const MeshGround* m : ground.meshes) {
      m->trianglesIn(lo, hi, faces);
      for (uint32_t f : faces) {
        strata.push_back({m, f, {}, {}});
        weights.push_back(m->area(f));
      }
    }
  }
  double lambdaTotal = 0.0;
  for (double w : weights) lambdaTotal += w;
  lambdaTotal *= perM2 * share;
  double scaleBy = perM2 * share;
  if (lambdaTotal > kMaxCandidates) {
    scaleBy *= kMaxCandidates / lambdaTotal;
    st.messages.push_back(ctx + ": " + formatNumber(std::round(lambdaTotal)) + " candidates asked for; capped at " +
                          formatNumber(kMaxCandidates) + " (lower the density or the area)");
  }
  std::vector<uint64_t> firstOf(strata.size() + 1, 0);
  {
    double cum = unitOf(typeKey, 1);
    for (size_t i = 0; i < strata.size(); ++i) {
      cum += weights[i] * scaleBy;
      firstOf[i + 1] = std::max(firstOf[i], uint64_t(std::floor(cum)));
    }
  }
  const uint64_t total = firstOf.back();
  st.candidates += total;
  if (total == 0) return;

  // Attempt 0 throws uniformly in its stratum; a candidate refused for
  // spacing is thrown again near where it first fell (within twice the
  // spacing on the terrain, on the same triangle on a mesh), so retries
  // keep the density local and mostly stay where the filters said yes.
  auto stratumOf = [&](uint64_t i) {
    return size_t(std::upper_bound(firstOf.begin(), firstOf.end(), i) - firstOf.begin()) - 1;
  };
  // 0: passed (out filled), 1: outside, 2: filtered.
  auto evaluate = [&](uint64_t i, size_t si, int attempt, Evaluated& out) -> int {
    const uint64_t key = key4(typeKey, i, uint64_t(attempt), 0xCA4Dull);
    const Stratum& sr = strata[si];
    std::optional<SurfacePoint> sp;
    if (!sr.mesh) {
      const uint64_t k0 = attempt == 0 ? key : key4(typeKey, i, 0, 0xCA4Dull);
      glm::dvec2 xy(sr.lo.x + (sr.hi.x - sr.lo.x) * unitOf(k0, 0), sr.lo.y + (sr.hi.y - sr.lo.y) * unitOf(k0, 1));
      if (attempt > 0) {
        const double rr = 2.0 * r * std::sqrt(unitOf(key, 0)), a = 2.0 * kPi * unitOf(key, 1);
        xy += glm::dvec2(rr * std::cos(a), rr * std::sin(a));
      }
      if (!region.contains(xy) || !inMask(xy)) return 1;
      sp = terrainSurface(ground.terrain->height, xy);
      if (!sp) return 1;
      if (!passesFilters(t, *sp, 0.0, false)) return 2;
      if (ground.coverHeight > 0.0)
        for (const MeshGround* m : ground.meshes)
          if (m->covers(sp->position, ground.coverHeight)) return 1;
      if (layer >= 0 && !passesLayer(t, terrainLayerWeight(*ground.terrain, layer, xy))) return 2;
    } else {
      const double u = std::sqrt(unitOf(key, 1)), v = unitOf(key, 2);
      sp = sr.mesh->pointOn(sr.face, glm::dvec3(1.0 - u, u * (1.0 - v), u * v));
      if (!region.contains(glm::dvec2(sp->position))) return 1;
      // Under the terrain (the buried foot of a scan): no foliage.
      if (ground.terrain)
        if (auto ts = terrainSurface(ground.terrain->height, glm::dvec2(sp->position));
            ts && ts->position.z > sp->position.z + 0.01)
          return 1;
      if (!passesFilters(t, *sp, 0.0)) return 2;
    }
    const Instance in = makeInstance(t, type, *sp, seed, key);
    out.position = quantized(in.position);
    out.rot = packRotation(in.rotation);
    out.scale = packScale(t.scaleMode, in.scale);
    out.surface = sp->surface;
    return 0;
  };

  // In batches of candidates (all attempts of one batch, then the next),
  // so the working memory stays bounded however many are thrown.
  std::vector<Evaluated> accepted;
  const unsigned ranges = resolveThreads(threads) * 8;
  std::vector<std::vector<Evaluated>> passed(ranges);
  std::vector<size_t> outside(ranges), filtered(ranges);
  std::vector<uint64_t> pending;
  for (uint64_t b0 = 0; b0 < total; b0 += kBatch) {
    // Before the store is touched: a cancel here leaves this type's cells as they were.
    if (progress && progress->cancelled()) {
      res.cancelled = true;
      return;
    }
    reportProgress(progress, double(b0) / double(total), t.name);
    pending.resize(size_t(std::min(total, b0 + kBatch) - b0));
    for (size_t i = 0; i < pending.size(); ++i) pending[i] = b0 + i;
    for (int attempt = 0; attempt < kAttempts && !pending.empty(); ++attempt) {
      // Evaluate in parallel, each range into its own list, in order.
      const size_t n = pending.size();
      const size_t used = std::max<size_t>(1, std::min<size_t>(ranges, n / 1024));
      parallelFor(int64_t(used), int(threads), 1, [&](int64_t b, int64_t e) {
        for (int64_t rg = b; rg < e; ++rg) {
          auto& out = passed[size_t(rg)];
          out.clear();
          outside[size_t(rg)] = filtered[size_t(rg)] = 0;
          if (progress && progress->cancelled()) continue;  // a Cancel waits for a range at most
          const size_t from = n * size_t(rg) / used, to = n * size_t(rg + 1) / used;
          Evaluated ev;
          size_t si = from < to ? stratumOf(pending[from]) : 0;
          for (size_t k = from; k < to; ++k) {
            while (pending[k] >= firstOf[si + 1]) ++si;  // pending is sorted
            const int verdict = evaluate(pending[k], si, attempt, ev);
            if (verdict == 0) {
              ev.slot = uint32_t(k);
              out.push_back(ev);
            } else {
              (verdict == 1 ? outside : filtered)[size_t(rg)]++;
            }
          }
        }
      });
      if (progress && progress->cancelled()) {
        res.cancelled = true;
        return;
      }
      const double batch = double(std::min(total, b0 + kBatch) - b0);
      reportProgress(progress, (double(b0) + batch * double(attempt + 1) / kAttempts) / double(total), t.name);
      // Accept in candidate order, on this thread.
      std::vector<uint64_t> again;
      for (size_t rg = 0; rg < used; ++rg) {
        st.outside += outside[rg];
        st.filtered += filtered[rg];
        for (const Evaluated& ev : passed[rg]) {
          if (useGrid && grid.conflicts(ev.position)) {
            if (attempt + 1 == kAttempts)
              ++st.spacingRejected;
            else
              again.push_back(pending[ev.slot]);
            continue;
          }
          grid.insert(ev.position, r);
          accepted.push_back(ev);
        }
      }
      pending = std::move(again);
    }
  }
  if (progress && progress->cancelled()) {
    res.cancelled = true;
    return;
  }
  // Ids in acceptance order; then into the cells, one cell at a time.
  const uint32_t firstId = store.takeIds(uint32_t(accepted.size()), &res.undo);
  std::vector<std::pair<CellKey, uint32_t>> order(accepted.size());
  for (size_t i = 0; i < accepted.size(); ++i) order[i] = {cellOf(accepted[i].position), uint32_t(i)};
  std::sort(order.begin(), order.end());
  for (size_t i = 0; i < order.size();) {
    const CellKey k = order[i].first;
    Cell& cell = store.edit(k, &res.undo);
    // Reservations: exact for a scatter into empty cells (16 bytes per
    // record, not a doubling vector's up to 32), by half again when a dab
    // adds a few to a full cell.
    size_t adds[2] = {0, 0};
    for (size_t j = i; j < order.size() && order[j].first == k; ++j) ++adds[int(accepted[order[j].second].surface)];
    for (int sf = 0; sf < 2; ++sf)
      if (adds[sf]) {
        auto& items = cell.run(type, Surface(sf)).items;
        if (items.capacity() < items.size() + adds[sf])
          items.reserve(std::max(items.size() + adds[sf], items.size() * 3 / 2));
      }
    for (; i < order.size() && order[i].first == k; ++i) {
      const Evaluated& ev = accepted[order[i].second];
      Instance in;
      in.position = ev.position;
      PackedInstance p = pack(in, t.scaleMode, k);
      p.rot = ev.rot;
      p.scale = ev.scale;
      p.id = firstId + order[i].second;
      cell.run(type, ev.surface).items.push_back(p);
    }
  }
  st.placed += accepted.size();
}

// A cancelled edit gives back what its earlier types placed: the store as
// it was, nothing to undo.
EditResult undoIfCancelled(FoliageStore& store, EditResult res) {
  if (!res.cancelled) return res;
  res.undo.swap(store);
  EditResult out;
  out.cancelled = true;
  out.stats.messages.push_back("cancelled: nothing changed");
  return out;
}

glm::dquat alignTo(const glm::dvec3& n, double maxDeg) {
  const glm::dvec3 z(0, 0, 1);
  const glm::dvec3 axis = glm::cross(z, n);
  const double s = glm::length(axis);
  if (s < 1e-12) return glm::dquat(1, 0, 0, 0);  // along +Z (or -Z: no single tilt; keep upright)
  double angle = std::atan2(s, n.z);
  angle = std::min(angle, maxDeg * kPi / 180.0);
  return glm::angleAxis(angle, axis / s);
}

}  // namespace

bool passesLayer(const FoliageType& t, double layerWeight) {
  return layerWeight >= t.layerWeight.x && layerWeight <= t.layerWeight.y;
}

bool passesFilters(const FoliageType& t, const SurfacePoint& sp, double layerWeight, bool checkLayer) {
  if (t.surface == SurfaceFilter::Terrain && sp.surface != Surface::Terrain) return false;
  if (t.surface == SurfaceFilter::Meshes && sp.surface != Surface::Mesh) return false;
  if (!(sp.slopeDeg >= t.slopeDeg.x && sp.slopeDeg <= t.slopeDeg.y)) return false;
  const double z = sp.position.z;
  if (!(z >= t.altitude.x && z <= t.altitude.y)) return false;
  if (checkLayer && !t.layer.empty() && sp.surface == Surface::Terrain && !passesLayer(t, layerWeight)) return false;
  return true;
}

Instance makeInstance(const FoliageType& t, uint16_t type, const SurfacePoint& sp, uint64_t seed, uint64_t key) {
  const uint64_t k = key4(seed, key, 0x1257ull, 0);
  Instance in;
  in.type = type;
  in.surface = sp.surface;
  const double yaw = t.randomYaw ? unitOf(k, 10) * 2.0 * kPi : 0.0;
  const double pitch = t.randomPitchDeg * kPi / 180.0 * unitOf(k, 11);
  const double dir = unitOf(k, 12) * 2.0 * kPi;
  glm::dquat q = glm::angleAxis(yaw, glm::dvec3(0, 0, 1));
  if (pitch > 0.0) q = glm::angleAxis(pitch, glm::dvec3(std::cos(dir), std::sin(dir), 0.0)) * q;
  if (t.alignToNormal) q = alignTo(sp.normal, t.alignMaxDeg) * q;
  in.rotation = glm::normalize(q);
  const double s = t.scale.x + (t.scale.y - t.scale.x) * unitOf(k, 13);
  if (t.scaleMode == ScaleMode::Uniform)
    in.scale = glm::dvec3(s);
  else
    in.scale = glm::dvec3(s, s, t.scaleZ.x + (t.scaleZ.y - t.scaleZ.x) * unitOf(k, 14));
  const glm::dvec3 up = in.rotation * glm::dvec3(0, 0, 1);
  in.position = sp.position - up * t.sinkDepth;
  return in;
}

// --- painting -------------------------------------------------------------------------

EditResult paint(FoliageStore& store, const Ground& ground, const PaintParams& p) {
  EditResult res;
  if (p.types.empty()) res.stats.messages.push_back("paint: no foliage type chosen: nothing placed");
  if (!(p.densityFactor >= 0.0 && p.densityFactor <= 10.0))
    res.stats.messages.push_back("paint: density factor " + formatNumber(p.densityFactor) +
                                 " is out of range (0 to 10); using " +
                                 formatNumber(std::clamp(std::isnan(p.densityFactor) ? 1.0 : p.densityFactor, 0.0, 10.0)));
  const double factor = std::isnan(p.densityFactor) ? 1.0 : std::clamp(p.densityFactor, 0.0, 10.0);
  for (size_t i = 0; i < p.types.size() && !res.cancelled; ++i) {
    const uint16_t type = p.types[i];
    if (type >= store.types().size()) {
      res.stats.messages.push_back("paint: no foliage type " + std::to_string(type));
      continue;
    }
    const Progress part(p.progress, double(i) / double(p.types.size()), double(i + 1) / double(p.types.size()));
    placeType(store, ground, type, p.region, factor, key4(p.seed, type, 0xFA1Full, 0), p.threads, res, nullptr, {},
              p.progress ? &part : nullptr);
  }
  return undoIfCancelled(store, std::move(res));
}

EditResult fillLayer(FoliageStore& store, const Ground& ground, const std::string& layer, double minWeight,
                     const TypeSet& types, uint64_t seed, const std::optional<Region2>& area, unsigned threads,
                     const Progress* progress) {
  EditResult res;
  if (!ground.terrain) {
    res.stats.messages.push_back("fill: paint layer \"" + layer + "\": there is no terrain");
    return res;
  }
  LayerMask mask;
  mask.layer = terrainLayerIndex(*ground.terrain, layer);
  mask.min = std::clamp(std::isnan(minWeight) ? 0.5 : minWeight, 0.0, 1.0);
  if (mask.layer < 0) {
    res.stats.messages.push_back("fill: the terrain has no paint layer \"" + layer + "\": nothing placed");
    return res;
  }
  Region2 region;
  if (area) {
    region = *area;
  } else {
    const glm::dvec2 o(ground.terrain->height.origin());
    region = Region2::rect(o, o + ground.terrain->height.sizeMetres());
  }
  for (size_t i = 0; i < types.size() && !res.cancelled; ++i) {
    const uint16_t type = types[i];
    if (type >= store.types().size()) {
      res.stats.messages.push_back("fill: no foliage type " + std::to_string(type));
      continue;
    }
    const Progress part(progress, double(i) / double(types.size()), double(i + 1) / double(types.size()));
    placeType(store, ground, type, region, 1.0, key4(seed, type, 0xF111ull, 0), threads, res, &mask, {},
              progress ? &part : nullptr);
  }
  return undoIfCancelled(store, std::move(res));
}

EditResult fill(FoliageStore& store, const Ground& ground, const Region2& area, const TypeSet& types, uint64_t seed,
                unsigned threads, const Progress* progress) {
  PaintParams p;
  p.region = area;
  p.types = types;
  p.seed = seed;
  p.threads = threads;
  p.progress = progress;
  return paint(store, ground, p);
}

EditResult scatter(FoliageStore& store, const Ground& ground, const TypeSet& types, uint64_t seed,
                   const std::optional<Region2>& area, unsigned threads, bool compete, const Progress* progress) {
  Region2 region;
  if (area) {
    region = *area;
  } else {
    glm::dvec2 lo, hi;
    ground.bounds(lo, hi);
    region = Region2::rect(lo, hi);
  }
  if (!compete) return fill(store, ground, region, types, seed, threads, progress);
  EditResult res;
  for (size_t i = 0; i < types.size() && !res.cancelled; ++i) {
    const uint16_t type = types[i];
    if (type >= store.types().size()) {
      res.stats.messages.push_back("scatter: no foliage type " + std::to_string(type));
      continue;
    }
    const Progress part(progress, double(i) / double(types.size()), double(i + 1) / double(types.size()));
    placeType(store, ground, type, region, 1.0, key4(seed, type, 0xFA1Full, 0), threads, res, nullptr, types,
              progress ? &part : nullptr);
  }
  return undoIfCancelled(store, std::move(res));
}

// --- erasing and selections --------------------------------------------------------------

EditResult erase(FoliageStore& store, const Region2& region, const TypeSet& types) {
  EditResult res;
  glm::dvec2 lo, hi;
  region.bounds(lo, hi);
  const std::vector<CellKey> keys = store.cellsIn(lo, hi);
  for (const CellKey& k : keys) {
    // Look before editing, so cells with nothing to erase stay out of the undo.
    const Cell* c = store.cell(k);
    bool any = false;
    for (const Run& r : c->runs)
      if (inSet(types, r.type))
        for (const PackedInstance& p : r.items) any = any || region.contains(glm::dvec2(unpackPosition(p, k)));
    if (!any) continue;
    for (Run& r : store.edit(k, &res.undo).runs) {
      if (!inSet(types, r.type)) continue;
      const size_t before = r.items.size();
      r.items.erase(std::remove_if(r.items.begin(), r.items.end(),
                                   [&](const PackedInstance& p) { return region.contains(glm::dvec2(unpackPosition(p, k))); }),
                    r.items.end());
      res.stats.removed += before - r.items.size();
    }
  }
  store.prune(res.undo.keys());
  return res;
}

std::vector<uint32_t> Selection::ids() const {
  std::vector<uint32_t> v;
  for (const auto& [k, id] : items) v.push_back(id);
  std::sort(v.begin(), v.end());
  return v;
}

Selection selectPoint(const FoliageStore& store, const glm::dvec3& point, double radius, const TypeSet& types) {
  Selection s;
  double best = radius * radius;
  bool found = false;
  std::pair<CellKey, uint32_t> hit;
  store.forEachCellIn(glm::dvec2(point) - radius, glm::dvec2(point) + radius, [&](const CellKey& k, const Cell& c) {
    for (const Run& r : c.runs)
      if (inSet(types, r.type))
        for (const PackedInstance& p : r.items) {
          const glm::dvec3 d = unpackPosition(p, k) - point;
          const double d2 = glm::dot(d, d);
          if (d2 <= best && (!found || d2 < best || p.id < hit.second)) {
            best = d2;
            hit = {k, p.id};
            found = true;
          }
        }
  });
  if (found) s.items.push_back(hit);
  return s;
}

Selection selectRegion(const FoliageStore& store, const Region2& region, const TypeSet& types) {
  Selection s;
  glm::dvec2 lo, hi;
  region.bounds(lo, hi);
  store.forEachCellIn(lo, hi, [&](const CellKey& k, const Cell& c) {
    for (const Run& r : c.runs)
      if (inSet(types, r.type))
        for (const PackedInstance& p : r.items)
          if (region.contains(glm::dvec2(unpackPosition(p, k)))) s.items.push_back({k, p.id});
  });
  std::sort(s.items.begin(), s.items.end());
  return s;
}

namespace {

// Takes the selected instances out of their cells (decoded), recording undo.
std::vector<Instance> takeSelected(FoliageStore& store, const Selection& sel, FoliageUndo& undo) {
  // Each id where it is now: in the cell the selection names, or, for one
  // an undo or redo moved since it was selected, in the cell that holds it
  // now (one pass over the store, only when some are elsewhere).
  std::map<CellKey, std::vector<uint32_t>> listed, byCell;
  for (const auto& [k, id] : sel.items) listed[k].push_back(id);
  std::vector<uint32_t> elsewhere;
  for (const auto& [k, ids] : listed) {
    std::vector<uint32_t> have;
    if (const Cell* c = store.cell(k))
      for (const Run& r : c->runs)
        for (const PackedInstance& p : r.items) have.push_back(p.id);
    std::sort(have.begin(), have.end());
    for (uint32_t id : ids) (std::binary_search(have.begin(), have.end(), id) ? byCell[k] : elsewhere).push_back(id);
  }
  if (!elsewhere.empty()) {
    std::sort(elsewhere.begin(), elsewhere.end());
    for (const auto& [k, c] : store.cells())
      for (const Run& r : c.runs)
        for (const PackedInstance& p : r.items)
          if (std::binary_search(elsewhere.begin(), elsewhere.end(), p.id)) byCell[k].push_back(p.id);
  }
  std::vector<Instance> out;
  for (auto& [k, ids] : byCell) {
    if (!store.cell(k)) continue;
    std::sort(ids.begin(), ids.end());
    for (Run& r : store.edit(k, &undo).runs) {
      auto keep = std::stable_partition(r.items.begin(), r.items.end(), [&](const PackedInstance& p) {
        return !std::binary_search(ids.begin(), ids.end(), p.id);
      });
      for (auto it = keep; it != r.items.end(); ++it) {
        Instance in = unpack(*it, store.type(r.type).scaleMode, k);
        in.type = r.type;
        in.surface = r.surface;
        out.push_back(in);
      }
      r.items.erase(keep, r.items.end());
    }
  }
  return out;
}

// The surface an instance stands on near `pos` (its own kind first).
std::optional<SurfacePoint> surfaceNear(const Ground& ground, const glm::dvec3& pos, Surface kind) {
  if (kind == Surface::Terrain && ground.terrain) return terrainSurface(ground.terrain->height, glm::dvec2(pos));
  std::optional<SurfacePoint> best;
  double bestD = std::numeric_limits<double>::infinity();
  for (const MeshGround* m : ground.meshes)
    if (auto sp = m->closest(pos, 1e4)) {
      const double d = glm::length(sp->position - pos);
      if (d < bestD) {
        bestD = d;
        best = sp;
      }
    }
  return best;
}

}  // namespace

EditResult moveSelection(FoliageStore& store, const Ground& ground, Selection& sel, const glm::dvec3& offset,
                         bool snap) {
  EditResult res;
  std::vector<Instance> taken = takeSelected(store, sel, res.undo);
  sel.items.clear();
  for (Instance in : taken) {
    const Instance old = in;
    in.position += offset;
    if (snap) {
      const FoliageType& t = store.type(in.type);
      const glm::dvec3 up = in.rotation * glm::dvec3(0, 0, 1);
      const glm::dvec3 anchor = in.position + up * t.sinkDepth;
      if (auto sp = surfaceNear(ground, anchor, in.surface)) {
        in.position = sp->position - up * t.sinkDepth;
      } else {
        in = old;
        res.stats.messages.push_back("move: instance " + std::to_string(in.id) +
                                     " has no surface under its new place; left where it was");
      }
    }
    in.position = quantized(in.position);
    if (in.position != old.position) ++res.stats.moved;
    store.add(in, &res.undo, true);
    sel.items.push_back({cellOf(in.position), in.id});
  }
  std::sort(sel.items.begin(), sel.items.end());
  store.prune(res.undo.keys());
  return res;
}

EditResult deleteSelection(FoliageStore& store, Selection& sel) {
  EditResult res;
  res.stats.removed = takeSelected(store, sel, res.undo).size();
  sel.items.clear();
  store.prune(res.undo.keys());
  return res;
}

EditResult reapply(FoliageStore& store, const Ground& ground, Selection& sel, uint64_t seed,
                   const Progress* progress) {
  EditResult res;
  const Selection before = sel;
  std::vector<Instance> taken = takeSelected(store, sel, res.undo);
  sel.items.clear();
  for (size_t i = 0; i < taken.size(); ++i) {
    // A surface query per instance: a large selection takes seconds.
    if (progress && i % 4096 == 0) {
      progress->report(double(i) / double(taken.size()), "reapply");
      if (progress->cancelled()) {
        res.cancelled = true;
        sel = before;
        return undoIfCancelled(store, std::move(res));
      }
    }
    const Instance& old = taken[i];
    const FoliageType& t = store.type(old.type);
    const glm::dvec3 up = old.rotation * glm::dvec3(0, 0, 1);
    // The surface point it was placed at: its anchor, before the sink.
    const glm::dvec3 anchor = old.position + up * t.sinkDepth;
    std::optional<SurfacePoint> sp = surfaceNear(ground, anchor, old.surface);
    double weight = 0.0;
    if (sp && sp->surface == Surface::Terrain && !t.layer.empty() && ground.terrain)
      weight = terrainLayerWeight(*ground.terrain, terrainLayerIndex(*ground.terrain, t.layer), glm::dvec2(anchor));
    if (!sp || !passesFilters(t, *sp, weight)) {
      ++res.stats.removed;
      continue;
    }
    Instance in = makeInstance(t, old.type, *sp, seed, old.id);
    in.id = old.id;
    in.position = quantized(in.position);
    store.add(in, &res.undo, true);
    sel.items.push_back({cellOf(in.position), in.id});
    ++res.stats.changed;
  }
  if (res.stats.removed)
    res.stats.messages.push_back("reapply: " + std::to_string(res.stats.removed) +
                                 " instances no longer pass their type's filters; removed");
  std::sort(sel.items.begin(), sel.items.end());
  store.prune(res.undo.keys());
  return res;
}

}  // namespace hs::foliage
