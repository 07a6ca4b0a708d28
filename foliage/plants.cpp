// Procedural plants (plants.h). The tree follows Weber & Penn's model in a
// reduced form: per level a count of children, their down angle (from the
// parent's axis) and rotate angle (around it, ~140 degrees apart, the
// phyllotaxis that spreads them), a length ratio times a shape function of
// the child's position on its parent (conical for conifers, a flame for
// broadleaves), curvature per segment, and radius tapering along the stem.
#include "foliage/plants.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/gtc/quaternion.hpp>

namespace hs::foliage {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Rng {
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double unit() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
  double range(double a, double b) { return a + (b - a) * unit(); }
};

struct Builder {
  int lod = 0;  // detail: stems get half the segments and sides per level
  std::vector<glm::vec3> pos;
  std::vector<glm::vec2> uv;
  std::vector<uint32_t> bark, leaves;
  PlantStats stats;

  uint32_t vertex(const glm::dvec3& p, const glm::dvec2& t) {
    pos.emplace_back(p);
    uv.emplace_back(t);
    return uint32_t(pos.size() - 1);
  }
  // A tube through `pts` with radii `rad` (closed at the tip by a point).
  void tube(const std::vector<glm::dvec3>& pts, const std::vector<glm::dquat>& frames, const std::vector<double>& rad,
            int sides) {
    const uint32_t first = uint32_t(pos.size());
    double v = 0.0;
    for (size_t i = 0; i < pts.size(); ++i) {
      if (i > 0) v += glm::length(pts[i] - pts[i - 1]);
      for (int k = 0; k <= sides; ++k) {
        const double a = 2.0 * kPi * k / sides;
        const glm::dvec3 off = frames[i] * glm::dvec3(std::cos(a), std::sin(a), 0.0);
        vertex(pts[i] + off * rad[i], {double(k) / sides, v});
      }
    }
    const uint32_t ring = uint32_t(sides + 1);
    for (uint32_t i = 0; i + 1 < pts.size(); ++i)
      for (uint32_t k = 0; k < uint32_t(sides); ++k) {
        const uint32_t a = first + i * ring + k, b = a + 1, c = a + ring + 1, d = a + ring;
        bark.insert(bark.end(), {a, b, c, a, c, d});
      }
    ++stats.stems;
  }
  // A leaf card: a quad of side `size` hanging from `at`.
  void card(const glm::dvec3& at, const glm::dquat& q, double size) {
    const glm::dvec3 x = q * glm::dvec3(size * 0.5, 0, 0), y = q * glm::dvec3(0, size, 0);
    const uint32_t a = vertex(at - x, {0, 0}), b = vertex(at + x, {1, 0}), c = vertex(at + x + y, {1, 1}),
                   d = vertex(at - x + y, {0, 1});
    leaves.insert(leaves.end(), {a, b, c, a, c, d});
    ++stats.leaves;
  }
};

// Weber & Penn's shape ratios, r the position along the parent from its base (0) to tip (1).
double shapeRatio(PlantKind kind, double r) {
  switch (kind) {
    case PlantKind::Conifer: return 0.2 + 0.8 * (1.0 - r);                                   // conical
    case PlantKind::Shrub: return 0.2 + 0.8 * std::sin(kPi * 0.5 * (1.0 - r) + 0.3);           // hemispherical
    default: return r <= 0.7 ? 0.3 + 0.7 * (r / 0.7) * 0.6 + 0.3 * r : 0.2 + 0.8 * (1.0 - r) / 0.3;  // flame-like
  }
}

struct TreeShape {
  double baseSize, curve, taper, radiusRatio;
  double down[4], downVar[4], lengthRatio[4], childDensity[4];
  int segments[4];
};

TreeShape shapeOf(PlantKind kind) {
  if (kind == PlantKind::Conifer)
    return {0.12, 4.0, 0.95, 0.018, {0, 85, 40, 40}, {0, 15, 10, 10}, {1, 0.35, 0.3, 0.4}, {0, 1, 0.5, 0.3},
            {12, 5, 3, 2}};
  if (kind == PlantKind::Shrub)
    return {0.0, 25.0, 0.9, 0.03, {0, 20, 45, 45}, {0, 20, 15, 15}, {1, 0.5, 0.4, 0.4}, {0, 1, 0.6, 0.4},
            {6, 5, 3, 2}};
  return {0.35, 12.0, 0.9, 0.025, {0, 55, 45, 45}, {0, 15, 15, 15}, {1, 0.5, 0.45, 0.4}, {0, 1, 0.6, 0.4},
          {10, 6, 4, 3}};
}

void stem(Builder& b, Rng& rng, const PlantParams& p, const TreeShape& sh, int level, const glm::dvec3& start,
          const glm::dquat& dir, double length, double radius) {
  // The stem's bend is drawn once and spread over its segments, so the
  // random draws (and with them the whole plant) do not depend on the
  // resolution: a coarser level of detail is the same plant.
  const int segs = std::max(2, sh.segments[std::min(level, 3)] >> b.lod);
  std::vector<glm::dvec3> pts{start};
  std::vector<glm::dquat> frames{dir};
  std::vector<double> rad{radius};
  glm::dquat q = dir;
  const double curve = sh.curve * kPi / 180.0 * (level == 0 ? 0.3 : 1.0);
  const double bend = curve * 2.0 * (rng.unit() - 0.3);
  for (int i = 1; i <= segs; ++i) {
    q = q * glm::angleAxis(bend / segs, glm::dvec3(1, 0, 0));
    pts.push_back(pts.back() + q * glm::dvec3(0, 0, length / segs));
    frames.push_back(q);
    rad.push_back(std::max(radius * (1.0 - sh.taper * double(i) / segs), radius * 0.05));
  }
  // From the second level of detail on, the twigs (the last level, which
  // carries the leaves) are not drawn: too thin to see that far.
  if (!(b.lod >= 2 && level == p.levels && level > 0)) b.tube(pts, frames, rad, std::max(3, (p.sides >> std::min(level, 2)) >> b.lod));
  auto along = [&](double t, glm::dvec3& at, glm::dquat& f, double& r) {
    const double x = std::clamp(t, 0.0, 1.0) * segs;
    const int i = std::min(int(x), segs - 1);
    const double u = x - i;
    at = pts[size_t(i)] * (1.0 - u) + pts[size_t(i) + 1] * u;
    f = frames[size_t(i) + 1];
    r = rad[size_t(i)] * (1.0 - u) + rad[size_t(i) + 1] * u;
  };
  if (level < p.levels) {
    const int l = std::min(level + 1, 3);
    const double base = level == 0 ? sh.baseSize : 0.1;
    const int n = level == 0 ? p.branches : std::max(2, int(std::round(p.branches * sh.childDensity[l] * length / std::max(p.height, 1e-3) * 3.0)));
    double rot = rng.range(0.0, 2.0 * kPi);
    for (int k = 0; k < n; ++k) {
      const double t = base + (1.0 - base) * (double(k) + rng.unit()) / n;
      glm::dvec3 at;
      glm::dquat f;
      double r;
      along(t, at, f, r);
      rot += (140.0 + rng.range(-10.0, 10.0)) * kPi / 180.0;
      const double down = (sh.down[l] + rng.range(-sh.downVar[l], sh.downVar[l])) * kPi / 180.0;
      const glm::dquat child = f * glm::angleAxis(rot, glm::dvec3(0, 0, 1)) * glm::angleAxis(down, glm::dvec3(1, 0, 0));
      const double offset = (t - base) / std::max(1e-6, 1.0 - base);
      const double len = level == 0 ? length * sh.lengthRatio[l] * shapeRatio(p.kind, offset)
                                     : sh.lengthRatio[l] * (length - 0.6 * t * length);
      if (len < 0.02) continue;
      stem(b, rng, p, sh, l, at, child, len, std::max(r * 0.7 * std::pow(len / length, 0.8), 0.004));
    }
  }
  if (level == p.levels && level > 0) {
    for (int k = 0; k < p.leavesPerBranch; ++k) {
      glm::dvec3 at;
      glm::dquat f;
      double r;
      along(0.25 + 0.75 * (k + rng.unit()) / p.leavesPerBranch, at, f, r);
      const glm::dquat lq = f * glm::angleAxis(rng.range(0, 2 * kPi), glm::dvec3(0, 0, 1)) *
                            glm::angleAxis(rng.range(0.6, 1.3), glm::dvec3(1, 0, 0));
      b.card(at, lq, p.leafSize * rng.range(0.8, 1.2));
    }
  }
}

void grass(Builder& b, Rng& rng, const PlantParams& p) {
  for (int k = 0; k < p.branches; ++k) {
    const double yaw = rng.range(0, 2 * kPi), lean = rng.range(0.0, 0.6), len = p.height * rng.range(0.6, 1.0);
    const double w = std::max(0.004, p.leafSize * 0.05) * rng.range(0.7, 1.3);
    const glm::dvec3 base(rng.range(-0.08, 0.08) * p.height, rng.range(-0.08, 0.08) * p.height, 0.0);
    const glm::dvec3 out(std::cos(yaw), std::sin(yaw), 0.0), side(-std::sin(yaw), std::cos(yaw), 0.0);
    const int segs = 4;
    uint32_t prevL = 0, prevR = 0;
    for (int i = 0; i <= segs; ++i) {
      const double t = double(i) / segs, a = lean * t * 1.5;
      const glm::dvec3 c = base + out * (len * t * std::sin(a)) + glm::dvec3(0, 0, len * t * std::cos(a * 0.7));
      const double hw = w * (1.0 - t) + 1e-4;
      const uint32_t l = b.vertex(c - side * hw, {0.0, t}), r = b.vertex(c + side * hw, {1.0, t});
      if (i > 0) b.leaves.insert(b.leaves.end(), {prevL, prevR, r, prevL, r, l});
      prevL = l;
      prevR = r;
    }
    ++b.stats.leaves;
  }
}

void rock(Builder& b, Rng& rng, const PlantParams& p) {
  // Icosahedron, subdivided 3 times.
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<uint32_t> f = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6,
                             7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7,
                             9, 8, 1};
  for (glm::dvec3& x : v) x = glm::normalize(x);
  for (int level = 0; level < 3; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto m = [&](uint32_t a, uint32_t c) {
      const auto key = std::minmax(a, c);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[c]));
      return mid[key] = uint32_t(v.size() - 1);
    };
    std::vector<uint32_t> g;
    for (size_t i = 0; i < f.size(); i += 3) {
      const uint32_t a = f[i], bb = f[i + 1], c = f[i + 2], ab = m(a, bb), bc = m(bb, c), ca = m(c, a);
      g.insert(g.end(), {a, ab, ca, bb, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f = std::move(g);
  }
  struct Wave {
    glm::dvec3 d;
    double freq, amp, phase;
  };
  std::vector<Wave> waves;
  for (int k = 0; k < 10; ++k)
    waves.push_back({glm::normalize(glm::dvec3(rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)) + 1e-9),
                     rng.range(1.5, 6.0), rng.range(0.02, 0.09), rng.range(0, 2 * kPi)});
  const glm::dvec3 stretch(1.0, rng.range(0.75, 1.2), rng.range(0.55, 0.85));
  const double r = p.height * 0.5;
  const uint32_t first = uint32_t(b.pos.size());
  for (const glm::dvec3& x : v) {
    double s = 1.0;
    for (const Wave& w : waves) s += w.amp * std::cos(w.freq * glm::dot(x, w.d) + w.phase);
    glm::dvec3 q = x * s * stretch * r;
    q.z = std::max(q.z, -0.35 * r);  // a flat bottom to sit on
    b.vertex(q + glm::dvec3(0, 0, 0.25 * r), {0.5 + 0.5 * x.x, 0.5 + 0.5 * x.y});
  }
  for (uint32_t i : f) b.bark.push_back(first + i);
  ++b.stats.stems;
}

}  // namespace

const char* plantKindName(PlantKind k) {
  switch (k) {
    case PlantKind::Broadleaf: return "broadleaf";
    case PlantKind::Conifer: return "conifer";
    case PlantKind::Shrub: return "shrub";
    case PlantKind::Grass: return "grass";
    case PlantKind::Rock: return "rock";
  }
  return "broadleaf";
}

const std::vector<ParamDecl>& plantParamDecls() {
  static const std::vector<ParamDecl> decls = {
      {.key = "kind", .option = "kind", .label = "Kind", .type = ParamType::Choice, .defaultValue = "broadleaf",
       .choices = {"broadleaf", "conifer", "shrub", "grass", "rock"}, .help = "what to grow", .editor = true},
      {.key = "seed", .option = "seed", .label = "Seed", .min = 0, .max = 2147483647, .integer = true,
       .defaultValue = 1, .help = "the same seed grows the same plant", .valueName = "S", .editor = true},
      {.key = "height_m", .option = "height", .label = "Height", .unit = Unit::Metres, .min = 0.05, .max = 120.0,
       .defaultValue = 12.0, .help = "tree height, grass blade length, rock diameter", .valueName = "M",
       .editor = true, .decimals = 2},
      {.key = "levels", .option = "levels", .label = "Branch levels", .min = 0, .max = 3, .integer = true,
       .defaultValue = 2, .help = "levels of branches below the trunk", .valueName = "N", .editor = true},
      {.key = "branches", .option = "branches", .label = "Branches", .min = 1, .max = 400, .integer = true,
       .defaultValue = 24, .help = "first-level branches (shrub: stems; grass: blades)", .valueName = "N",
       .editor = true},
      {.key = "leaf_size_m", .option = "leaf-size", .label = "Leaf size", .unit = Unit::Metres, .min = 0.01,
       .max = 2.0, .defaultValue = 0.25, .help = "side of a leaf card", .valueName = "M", .editor = true},
      {.key = "leaves_per_branch", .option = "leaves", .label = "Leaves per branch", .min = 0, .max = 200,
       .integer = true, .defaultValue = 8, .help = "leaf cards on each last-level stem", .valueName = "N",
       .editor = true},
      {.key = "sides", .option = "sides", .label = "Stem sides", .min = 3, .max = 32, .integer = true,
       .defaultValue = 8, .help = "vertices around the trunk", .valueName = "N", .editor = true},
  };
  return decls;
}

PlantParams defaultPlant(PlantKind kind, uint64_t seed) {
  PlantParams p;
  p.kind = kind;
  p.seed = seed;
  switch (kind) {
    case PlantKind::Broadleaf: break;
    case PlantKind::Conifer:
      p.height = 18.0;
      p.branches = 60;
      p.leafSize = 0.18;
      p.leavesPerBranch = 10;
      break;
    case PlantKind::Shrub:
      p.height = 1.6;
      p.branches = 7;
      p.levels = 2;
      p.leafSize = 0.12;
      p.leavesPerBranch = 6;
      p.sides = 5;
      break;
    case PlantKind::Grass:
      p.height = 0.6;
      p.branches = 40;
      p.levels = 0;
      p.leafSize = 0.2;
      break;
    case PlantKind::Rock:
      p.height = 1.5;
      p.levels = 0;
      break;
  }
  return p;
}

namespace {

mesh::MeshData buildPlant(const PlantParams& in, int lod, PlantStats* stats, std::vector<std::string>* warnings) {
  std::vector<std::string> w;
  const auto& d = plantParamDecls();
  PlantParams p = in;
  const std::string ctx = std::string("plant (") + plantKindName(p.kind) + ")";
  p.height = clampParam(paramIn(d, "height_m"), p.height, w, ctx);
  p.levels = int(clampParam(paramIn(d, "levels"), p.levels, w, ctx));
  p.branches = int(clampParam(paramIn(d, "branches"), p.branches, w, ctx));
  p.leafSize = clampParam(paramIn(d, "leaf_size_m"), p.leafSize, w, ctx);
  p.leavesPerBranch = int(clampParam(paramIn(d, "leaves_per_branch"), p.leavesPerBranch, w, ctx));
  p.sides = int(clampParam(paramIn(d, "sides"), p.sides, w, ctx));
  if (warnings) warnings->insert(warnings->end(), w.begin(), w.end());

  Builder b;
  b.lod = lod;
  Rng rng{p.seed * 0x2545F4914F6CDD1Dull + uint64_t(p.kind)};
  switch (p.kind) {
    case PlantKind::Broadleaf:
    case PlantKind::Conifer: {
      const TreeShape sh = shapeOf(p.kind);
      stem(b, rng, p, sh, 0, glm::dvec3(0.0), glm::dquat(1, 0, 0, 0), p.height, p.height * sh.radiusRatio);
      break;
    }
    case PlantKind::Shrub: {
      const TreeShape sh = shapeOf(p.kind);
      PlantParams q = p;
      q.levels = std::max(1, p.levels);
      for (int k = 0; k < p.branches; ++k) {
        const glm::dquat dir = glm::angleAxis(rng.range(0, 2 * kPi), glm::dvec3(0, 0, 1)) *
                               glm::angleAxis(rng.range(0.1, 0.7), glm::dvec3(1, 0, 0));
        const glm::dvec3 at(rng.range(-0.1, 0.1) * p.height, rng.range(-0.1, 0.1) * p.height, 0.0);
        q.branches = std::max(3, p.branches);
        stem(b, rng, q, sh, 1, at, dir, p.height * rng.range(0.6, 1.0), p.height * 0.012);
      }
      break;
    }
    case PlantKind::Grass: grass(b, rng, p); break;
    case PlantKind::Rock: rock(b, rng, p); break;
  }

  mesh::MeshData m;
  m.positions = std::move(b.pos);
  m.uvs = std::move(b.uv);
  m.indices = b.bark;
  m.indices.insert(m.indices.end(), b.leaves.begin(), b.leaves.end());
  m.materials.push_back({p.kind == PlantKind::Rock ? "rock" : "bark",
                         p.kind == PlantKind::Rock ? glm::vec4(0.42f, 0.40f, 0.37f, 1.0f) : glm::vec4(0.30f, 0.22f, 0.15f, 1.0f),
                         -1});
  if (!b.bark.empty()) m.submeshes.push_back({0, uint32_t(b.bark.size()), 0});
  if (!b.leaves.empty()) {
    m.textures.push_back(leafTexture(p.kind));
    m.materials.push_back({p.kind == PlantKind::Grass ? "blades" : "leaves", glm::vec4(1.0f), 0});
    m.submeshes.push_back({uint32_t(b.bark.size()), uint32_t(b.leaves.size()), 1});
  }
  mesh::computeVertexNormals(m);
  b.stats.triangles = m.triangleCount();
  if (stats) *stats = b.stats;
  return m;
}

}  // namespace

mesh::MeshData generatePlant(const PlantParams& in, PlantStats* stats, std::vector<std::string>* warnings) {
  return buildPlant(in, 0, stats, warnings);
}

namespace {

// Appends the triangles `idx` of `from` (their vertices copied, moved by
// `place`) to `to` as indices into it.
template <class Place>
void appendTriangles(mesh::MeshData& to, const mesh::MeshData& from, const uint32_t* idx, size_t n, Place&& place,
                     std::vector<uint32_t>& out) {
  std::map<uint32_t, uint32_t> remap;
  for (size_t k = 0; k < n; ++k) {
    auto [it, fresh] = remap.try_emplace(idx[k], uint32_t(to.positions.size()));
    if (fresh) {
      to.positions.push_back(place(from.positions[idx[k]]));
      to.normals.push_back(from.normals[idx[k]]);
      to.uvs.push_back(from.uvs[idx[k]]);
    }
    out.push_back(it->second);
  }
}

}  // namespace

// Leaves are many small disconnected cards and stems many small open
// tubes, which the decimator cannot merge (it keeps their open borders:
// a broadleaf went from 14.1k to 11.3k triangles and stopped), so a
// plant's levels are made the way game engines thin trees: the stems
// generated again with half the segments and sides per level (the same
// plant: its random draws do not depend on the resolution), the leaves by
// keeping a seeded share of the cards
// (sqrt(ratio) per level: half of them for the default 0.25) grown by
// 1/sqrt(share) about their centres so the crown keeps its coverage
// (grass keeps a share of its blades, ungrown). Each level's error is
// measured against the full plant with meshproc's measureError.
mesh::LodChain generatePlantLods(const PlantParams& p, const mesh::LodOptions& options, PlantStats* stats) {
  mesh::MeshData full = generatePlant(p, stats);
  const mesh::Submesh* leafSm = nullptr;
  const mesh::Submesh* barkSm = nullptr;
  for (const mesh::Submesh& sm : full.submeshes) (sm.material == 1 ? leafSm : barkSm) = &sm;
  if (!leafSm) return mesh::buildLodChain(full, options);

  mesh::LodChain out;
  mesh::Lod base;
  base.mesh = full;
  base.triangles = full.triangleCount();
  out.levels.push_back(std::move(base));
  const size_t elem = p.kind == PlantKind::Grass ? 24 : 6;  // a blade's or a card's indices
  const size_t elements = leafSm->indexCount / elem;
  mesh::ErrorOptions eo;
  eo.samplesPerFace = 4.0;
  for (int level = 1; level <= options.levels; ++level) {
    const double share = std::pow(std::sqrt(std::clamp(options.ratio, 0.01, 1.0)), level);
    const double grow = p.kind == PlantKind::Grass ? 1.0 : 1.0 / std::sqrt(share);
    mesh::MeshData m;
    m.origin = full.origin;
    m.materials = full.materials;  // level 0 holds the texture (as buildLodChain's levels)
    std::vector<uint32_t> barkIdx, leafIdx;
    if (barkSm) {
      // The same plant with stems of fewer segments and sides.
      const mesh::MeshData b = buildPlant(p, level, nullptr, nullptr);
      for (const mesh::Submesh& sm : b.submeshes)
        if (sm.material == 0)
          appendTriangles(m, b, b.indices.data() + sm.firstIndex, sm.indexCount, [](const glm::vec3& v) { return v; },
                          barkIdx);
    }
    for (size_t e = 0; e < elements; ++e) {
      Rng pick{p.seed ^ (uint64_t(e) * 0x9E3779B97F4A7C15ull) ^ 0x1EAFull};
      if (pick.unit() >= share) continue;
      const uint32_t* idx = full.indices.data() + leafSm->firstIndex + e * elem;
      glm::vec3 centre(0.0f);
      for (size_t k = 0; k < elem; ++k) centre += full.positions[idx[k]];
      centre /= float(elem);
      appendTriangles(m, full, idx, elem, [&](const glm::vec3& v) { return centre + (v - centre) * float(grow); },
                      leafIdx);
    }
    m.indices = barkIdx;
    m.indices.insert(m.indices.end(), leafIdx.begin(), leafIdx.end());
    if (!barkIdx.empty()) m.submeshes.push_back({0, uint32_t(barkIdx.size()), 0});
    if (!leafIdx.empty()) m.submeshes.push_back({uint32_t(barkIdx.size()), uint32_t(leafIdx.size()), 1});
    const size_t tris = m.triangleCount();
    if (tris >= out.levels.back().triangles || tris < options.minTriangles) break;
    mesh::Lod lod;
    const mesh::ErrorReport e = mesh::measureError(full, m, eo);
    lod.triangles = tris;
    lod.hausdorff = std::max(e.hausdorff, out.levels.back().hausdorff);
    lod.hausdorffRel = e.bboxDiagonal > 0.0 ? lod.hausdorff / e.bboxDiagonal : 0.0;
    lod.meanError = e.mean;
    lod.samplesPerFace = e.samplesPerFace;
    lod.mesh = std::move(m);
    out.levels.push_back(std::move(lod));
  }
  return out;
}

mesh::Texture leafTexture(PlantKind kind, int size) {
  mesh::Texture t;
  t.name = std::string("*") + plantKindName(kind) + "_leaf";
  t.width = t.height = size;
  t.rgba.assign(size_t(size) * size_t(size) * 4, 0);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double u = (x + 0.5) / size * 2.0 - 1.0, v = (y + 0.5) / size;  // u across, v along
      bool inside;
      double shade = 1.0;
      if (kind == PlantKind::Grass) {
        inside = std::abs(u) <= 0.9 * (1.0 - v);  // a blade tapering to its tip
      } else if (kind == PlantKind::Conifer) {
        // Needles: thin lines fanning from the stem.
        const double a = std::atan2(u, v + 0.05), k = std::fmod(std::abs(a) * 9.0, 1.0);
        inside = v > 0.05 && std::hypot(u, v) < 0.95 && (k < 0.35);
      } else {
        const double half = 0.45 * std::sin(kPi * std::clamp(v, 0.0, 1.0));  // an ovate leaf
        inside = v > 0.02 && std::abs(u) <= half;
        if (std::abs(u) < 0.03) shade = 0.75;  // the midrib
      }
      uint8_t* px = &t.rgba[(size_t(y) * size_t(size) + size_t(x)) * 4];
      const double g = (0.55 + 0.25 * v) * shade;
      px[0] = uint8_t(60 * g);
      px[1] = uint8_t(150 * g);
      px[2] = uint8_t(50 * g);
      px[3] = inside ? 255 : 0;
    }
  return t;
}

}  // namespace hs::foliage
