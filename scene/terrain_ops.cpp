#include "scene/terrain_ops.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "scene/edit.h"
#include "terrain/noise.h"
#include "terrain/terrain.h"

namespace hs::scene::ops {
namespace {

EntityId addTerrainAsset(Document& doc, terrain::Terrain tr, const std::string& name, const glm::dvec3& at,
                         double lodErrorPixels, const QString& text, EntityId showOn = kNoEntity) {
  TerrainAsset t;
  t.name = name;
  t.materials.reserve(size_t(tr.paint.layerCount()));
  for (int l = 0; l < tr.paint.layerCount(); ++l) t.materials.push_back(tr.paint.material(l));
  t.paintRules = defaultPaintRules(tr.height);
  t.data = std::make_shared<TerrainData>(std::move(tr));
  Edit e(doc, text);
  const TerrainId id = e.addTerrain(std::move(t));
  if (showOn != kNoEntity) {
    auto& shown = e.entity(showOn).terrain;
    const TerrainId before = shown ? shown->terrain : kNoTerrain;
    shown = TerrainInstance{id, shown ? shown->lodErrorPixels : std::clamp(lodErrorPixels, 0.1, 64.0)};
    e.removeTerrainIfUnused(before);
    e.commit();
    return showOn;
  }
  Entity ent;
  ent.name = name;
  ent.transform.translation = at;
  ent.terrain = TerrainInstance{id, std::clamp(lodErrorPixels, 0.1, 64.0)};
  const EntityId eid = e.addEntity(std::move(ent));
  e.commit();
  return eid;
}

std::string fileSafe(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s.empty() ? std::string("terrain") : s;
}

}  // namespace

EntityId addTerrain(Document& doc, const NewTerrain& spec, std::string& error) {
  if (spec.showOn != kNoEntity && !doc.state().find(spec.showOn)) {
    error = "no entity " + std::to_string(spec.showOn) + " to show the terrain on";
    return kNoEntity;
  }
  if (!(spec.heightRange.max >= spec.heightRange.min) || !std::isfinite(spec.heightRange.min) ||
      !std::isfinite(spec.heightRange.max)) {
    error = "the height range must be two finite heights, the first not above the second";
    return kNoEntity;
  }
  terrain::HeightfieldDesc d;
  d.samplesX = spec.samplesX;
  d.samplesY = spec.samplesY;
  d.sizeMetres = spec.sizeMetres;
  // Centred on the entity: the gizmo and "Frame Selected" sit in its middle.
  d.origin = glm::dvec3(-spec.sizeMetres * 0.5, 0.0);
  d.initialHeight = spec.heightRange.min;
  auto made = terrain::Terrain::create(d, spec.materials);
  if (!made) {
    error = made.error();
    return kNoEntity;
  }
  terrain::Terrain tr = made.take();
  if (spec.start == NewTerrain::Start::Hills && spec.heightRange.max > spec.heightRange.min) {
    terrain::FractalNoise n;
    n.seed = spec.seed;
    n.scale = std::max(spec.sizeMetres.x, spec.sizeMetres.y) / 4.0;
    n.octaves = 7;
    terrain::Heightfield& hf = tr.height;
    const glm::dvec2 sp = hf.spacing();
    const float lo = spec.heightRange.min, span = spec.heightRange.max - spec.heightRange.min;
    std::vector<float> row(size_t(hf.samplesX()));
    std::vector<float> all(size_t(hf.samplesX()) * size_t(hf.samplesY()));
    for (int y = 0; y < hf.samplesY(); ++y) {
      n.row(0.0, sp.x, y * sp.y, hf.samplesX(), row.data());
      for (int x = 0; x < hf.samplesX(); ++x)
        all[size_t(y) * size_t(hf.samplesX()) + size_t(x)] = lo + span * std::clamp(0.5f + 0.6f * row[size_t(x)], 0.0f, 1.0f);
    }
    hf.write(hf.bounds(), all);
  }
  return addTerrainAsset(doc, std::move(tr), spec.name, spec.centre, spec.lodErrorPixels,
                         QString("New terrain %1").arg(QString::fromStdString(spec.name)), spec.showOn);
}

EntityId addTerrainFromHeightfield(Document& doc, terrain::Heightfield hf, const std::string& name,
                                   std::string& error, double lodErrorPixels) {
  auto made = terrain::Terrain::fromHeightfield(std::move(hf));
  if (!made) {
    error = made.error();
    return kNoEntity;
  }
  return addTerrainAsset(doc, made.take(), name, glm::dvec3(0.0), lodErrorPixels,
                         QString("Import terrain %1").arg(QString::fromStdString(name)));
}

EntityId addTerrainFromDem(Document& doc, terrain::Heightfield hf, const std::string& file, const std::string& name,
                           std::string& error, std::string* usedName) {
  std::string chosen = name;
  if (!name.empty()) {
    if (doc.state().findByName(name) != kNoEntity) {
      error = "the scene already has an entity named '" + name + "' (choose another name)";
      return kNoEntity;
    }
  } else {
    const std::string base = std::filesystem::path(file).stem().string();
    chosen = base.empty() ? std::string("Terrain") : base;
    for (int i = 2; doc.state().findByName(chosen) != kNoEntity; ++i)
      chosen = (base.empty() ? std::string("Terrain") : base) + " " + std::to_string(i);
  }
  const EntityId id = addTerrainFromHeightfield(doc, std::move(hf), chosen, error);
  if (id != kNoEntity && usedName) *usedName = chosen;
  return id;
}

bool setTerrainMaterial(Document& doc, TerrainId id, int layer, const terrain::Material& m, const QString& mergeKey) {
  const TerrainAsset* t = doc.state().findTerrain(id);
  if (!t || layer < 0 || layer >= int(t->materials.size())) return false;
  terrain::Material v = m;
  v.roughness = std::isfinite(v.roughness) ? std::clamp(v.roughness, 0.0f, 1.0f) : t->materials[size_t(layer)].roughness;
  if (!(v.tilingMetres > 0.0f) || !std::isfinite(v.tilingMetres)) v.tilingMetres = t->materials[size_t(layer)].tilingMetres;
  for (int c = 0; c < 3; ++c)
    v.albedo[c] = std::isfinite(v.albedo[c]) ? std::clamp(v.albedo[c], 0.0f, 1.0f) : t->materials[size_t(layer)].albedo[c];
  // A layer needs a name: exports and menus are labelled with it.
  if (v.name.find_first_not_of(" \t") == std::string::npos) v.name = t->materials[size_t(layer)].name;
  Edit e(doc, QString("Terrain material %1").arg(QString::fromStdString(v.name)), mergeKey);
  e.terrain(id).materials[size_t(layer)] = v;
  return e.commit();
}

bool setTerrainPaintRules(Document& doc, TerrainId id, std::vector<terrain::PaintRule> rules, const QString& mergeKey) {
  const TerrainAsset* t = doc.state().findTerrain(id);
  if (!t) return false;
  for (auto& r : rules) {
    if (r.layer < 0 || r.layer >= int(t->materials.size())) return false;
    for (double v : {r.altitudeMin, r.altitudeMax, r.altitudeBlend, r.slopeMin, r.slopeMax, r.slopeBlend})
      if (!std::isfinite(v)) return false;
    if (!std::isfinite(r.strength)) return false;
    r.altitudeBlend = std::max(0.0, r.altitudeBlend);
    r.slopeBlend = std::max(0.0, r.slopeBlend);
    r.strength = std::clamp(r.strength, 0.0f, 1.0f);
  }
  Edit e(doc, "Terrain paint rules", mergeKey);
  e.terrain(id).paintRules = std::move(rules);
  return e.commit();
}

bool setShownTerrain(Document& doc, EntityId entity, TerrainId terrain) {
  if (!doc.state().find(entity) || !doc.state().findTerrain(terrain)) return false;
  Edit e(doc, "Show terrain");
  auto& shown = e.entity(entity).terrain;
  const TerrainId before = shown ? shown->terrain : kNoTerrain;
  if (shown) shown->terrain = terrain;
  else shown = TerrainInstance{terrain, 1.0};
  e.removeTerrainIfUnused(before);
  return e.commit();
}

EntityId findTerrainEntity(const SceneState& state, const std::string& name, std::string& error) {
  const std::vector<EntityId> all = terrainEntities(state, false);
  if (all.empty()) {
    error = "the scene has no terrain (make one with: hybridscape-cli terrain new)";
    return kNoEntity;
  }
  if (name.empty()) {
    if (all.size() == 1) return all.front();
    error = "the scene has " + std::to_string(all.size()) + " terrains; say which with --terrain NAME (";
    for (size_t i = 0; i < all.size(); ++i) error += (i ? ", " : "") + ("'" + state.find(all[i])->name + "'");
    error += ")";
    return kNoEntity;
  }
  for (EntityId id : all)
    if (state.find(id)->name == name || terrainOf(state, id)->name == name) return id;
  error = "no terrain named '" + name + "' (terrains:";
  for (EntityId id : all) error += " '" + state.find(id)->name + "'";
  error += ")";
  return kNoEntity;
}

terrain::Result<std::vector<std::string>> exportPaintWeights(const TerrainAsset& t, const std::string& dir,
                                                             const std::string& extension, int bits) {
  using R = terrain::Result<std::vector<std::string>>;
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec)) return R::failure(dir + ": cannot create the folder for the weight images");
  std::vector<std::string> files;
  const terrain::PaintLayers& paint = t.data->terrain().paint;
  for (int l = 0; l < paint.layerCount(); ++l) {
    const std::string material = l < int(t.materials.size()) ? t.materials[size_t(l)].name : paint.material(l).name;
    const std::string file = (fs::path(dir) / (fileSafe(t.name) + "_" + std::to_string(l) + "_" + fileSafe(material) +
                                               "." + extension)).string();
    auto r = terrain::exportPaintLayerImage(paint, l, file, bits);
    if (!r) return R::failure(r.error());
    files.push_back(file);
  }
  return files;
}

}  // namespace hs::scene::ops
