#include "scene/demo_terrain.h"

#include <algorithm>
#include <cmath>

#include "terrain/brush_dab.h"
#include "terrain/erosion_thermal.h"
#include "terrain/noise.h"
#include "terrain/paint_rules.h"
#include "terrain/terrain.h"

namespace hs::scene {
namespace {

constexpr int kSamples = 257;
constexpr double kSize = 320.0;                         // metres, first to last sample
const glm::dvec3 kOrigin(-160.0, -60.0, 0.0);           // south-west corner: the bunnies stand 60 m in

struct Pillar {
  double x, y;       // world metres
  double radius;     // of the top
  double height;     // metres above the floor
};

// Where the Meteora pillars stand: north of the clearing, seen by the demo's
// first camera as a rock wall in the distance and by the flight as it turns.
constexpr Pillar kPillars[] = {
    {-55.0, 95.0, 16.0, 48.0}, {-12.0, 140.0, 22.0, 72.0}, {38.0, 105.0, 13.0, 40.0},
    {85.0, 160.0, 20.0, 66.0}, {-100.0, 170.0, 18.0, 58.0}, {110.0, 70.0, 11.0, 30.0},
};

double smooth01(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

bool addDemoTerrain(SceneState& s, std::string& error) {
  terrain::HeightfieldDesc d;
  d.samplesX = d.samplesY = kSamples;
  d.sizeMetres = glm::dvec2(kSize);
  d.origin = kOrigin;
  auto made = terrain::Terrain::create(d);
  if (!made) {
    error = "demo terrain: " + made.error();
    return false;
  }
  terrain::Terrain tr = made.take();
  terrain::Heightfield& hf = tr.height;
  const double sp = hf.spacing().x;

  // Floor: gentle fractal hills rising away from the clearing; pillars with
  // wobbly outlines (noise on the radius) and terraced flanks (sandstone
  // bedding); the clearing exactly flat at 0 where the bunnies stand.
  terrain::FractalNoise hills;
  hills.seed = 7;
  hills.scale = 90.0;
  hills.octaves = 6;
  terrain::FractalNoise wobble;
  wobble.seed = 11;
  wobble.scale = 9.0;
  wobble.octaves = 3;
  terrain::TerraceOptions bedding;
  bedding.stepHeight = 6.5f;
  bedding.sharpness = 0.55f;
  std::vector<float> h(size_t(kSamples) * kSamples);
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i) {
      const double wx = kOrigin.x + i * sp, wy = kOrigin.y + j * sp;
      const double r0 = std::hypot(wx, wy);
      double z = 2.5 * (double(hills.at(i * sp, j * sp)) + 0.35) + 0.06 * std::max(0.0, wy - 20.0);
      for (const Pillar& p : kPillars) {
        const double dist = std::hypot(wx - p.x, wy - p.y);
        const double r = p.radius * (1.0 + 0.22 * double(wobble.at(wx * 0.7 + p.x, wy * 0.7)));
        // Near-vertical walls with a rounded shoulder, a talus skirt beyond.
        const double body = std::sqrt(smooth01(r * 1.18, r * 0.7, dist));
        const double skirt = 0.1 * smooth01(r * 2.0, r * 1.15, dist);
        z = std::max(z, z + p.height * (0.88 * body + skirt));
      }
      // Terraced only where the rock stands (the floor keeps its hills).
      if (z > 8.0) z = std::max(double(terrain::terraceHeight(float(z), bedding)), 8.0);
      z *= smooth01(16.0, 30.0, r0);  // the clearing: 0 inside 16 m, blending out by 30 m
      h[size_t(j) * kSamples + size_t(i)] = float(z);
    }
  hf.write(hf.bounds(), h);

  // Weathering: material above 38 degrees slides into scree aprons. The
  // clearing is masked out, so the bunnies keep flat ground.
  terrain::ErosionMask mask;
  mask.region = hf.bounds();
  mask.weights.resize(mask.region.samples());
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i)
      mask.weights[size_t(j) * kSamples + size_t(i)] =
          float(smooth01(30.0, 45.0, std::hypot(kOrigin.x + i * sp, kOrigin.y + j * sp)));
  terrain::ThermalParams thermal;
  thermal.talusDegrees = 42.0;
  thermal.iterations = 6;
  thermal.strength = 0.5f;
  terrain::erodeThermal(hf, thermal, mask);

  TerrainAsset t;
  t.id = s.maxTerrainId() + 1;
  t.name = "Valley Terrain";
  for (int l = 0; l < tr.paint.layerCount(); ++l) t.materials.push_back(tr.paint.material(l));
  // Darker, more natural albedos than the library's defaults (the demo is
  // lit by a strong sun), set as document values like a user would.
  const glm::vec3 albedo[] = {{0.20f, 0.15f, 0.10f}, {0.10f, 0.17f, 0.05f}, {0.36f, 0.27f, 0.19f},
                              {0.30f, 0.26f, 0.22f}, {0.30f, 0.29f, 0.27f}, {0.10f, 0.08f, 0.05f},
                              {0.25f, 0.24f, 0.21f}, {0.80f, 0.82f, 0.85f}};
  for (size_t l = 0; l < t.materials.size() && l < 8; ++l) t.materials[l].albedo = albedo[l];
  t.paintRules = defaultPaintRules(hf);
  const terrain::PaintRulesResult painted = terrain::applyPaintRules(tr, t.paintRules);
  if (!painted.ok()) {
    error = "demo terrain: " + painted.error;
    return false;
  }
  // Patches of bare soil and forest floor in the grass, so the ground near
  // the camera is not one flat colour.
  terrain::FractalNoise patches;
  patches.seed = 23;
  patches.scale = 14.0;
  patches.octaves = 4;
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i) {
      const float n = patches.at(i * sp, j * sp);
      if (n > 0.15f) tr.paint.blend(i, j, 0, std::min(0.8f, (n - 0.15f) * 2.5f));
      else if (n < -0.3f) tr.paint.blend(i, j, 5, std::min(0.7f, (-0.3f - n) * 2.5f));
    }
  t.data = std::make_shared<TerrainData>(std::move(tr));

  Entity e;
  e.id = s.maxEntityId() + 1;
  e.name = t.name;
  e.terrain = TerrainInstance{t.id, 1.0};
  s.roots.push_back(e.id);
  s.entities.emplace(e.id, std::move(e));
  s.terrains.emplace(t.id, std::move(t));
  return true;
}

}  // namespace hs::scene
