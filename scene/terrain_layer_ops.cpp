#include "scene/terrain_layer_ops.h"

#include "scene/edit.h"

namespace hs::scene::ops {
namespace {

// The terrain if a layer edit may run on it now, else nullptr with `error`.
const TerrainAsset* editable(const Document& doc, TerrainId id, std::string& error) {
  const TerrainAsset* t = doc.state().findTerrain(id);
  if (!t || !t->data) {
    error = "no terrain " + std::to_string(id) + " in the scene";
    return nullptr;
  }
  // A job works on a snapshot and commits into this object: swapping the
  // object under it would throw its result away.
  if (t->data->jobRunning) {
    error = "terrain '" + t->name + "' is busy with another operation; try again when it has finished";
    return nullptr;
  }
  if (int(t->materials.size()) != t->data->terrain().paint.layerCount()) {
    error = "terrain '" + t->name + "': its materials and paint layers disagree";
    return nullptr;
  }
  return t;
}

}  // namespace

std::vector<terrain::PaintRule> rulesWithoutLayer(const std::vector<terrain::PaintRule>& rules, int layer) {
  std::vector<terrain::PaintRule> out;
  for (terrain::PaintRule r : rules) {
    if (r.layer == layer) continue;
    if (r.layer > layer) --r.layer;
    out.push_back(r);
  }
  return out;
}

int addTerrainLayer(Document& doc, TerrainId id, const terrain::Material& material, std::string& error) {
  const TerrainAsset* t = editable(doc, id, error);
  if (!t) return -1;
  terrain::Terrain copy = t->data->terrain().clone();
  terrain::Material m = material;
  if (m.name.empty()) m.name = "Layer " + std::to_string(copy.paint.layerCount() + 1);
  auto added = copy.paint.addLayer(m);
  if (!added) {
    error = "terrain '" + t->name + "': " + added.error();
    return -1;
  }
  Edit e(doc, QString("Add paint layer %1").arg(QString::fromStdString(m.name)));
  TerrainAsset& a = e.terrain(id);
  a.data = std::make_shared<TerrainData>(std::move(copy));
  a.materials.push_back(m);
  e.commit();
  return *added;
}

bool removeTerrainLayer(Document& doc, TerrainId id, int layer, std::string& error) {
  const TerrainAsset* t = editable(doc, id, error);
  if (!t) return false;
  if (layer < 0 || layer >= int(t->materials.size())) {
    error = "terrain '" + t->name + "' has no paint layer " + std::to_string(layer);
    return false;
  }
  terrain::Terrain copy = t->data->terrain().clone();
  if (terrain::Status st = copy.paint.removeLayer(layer); !st) {
    error = "terrain '" + t->name + "': " + st.error;
    return false;
  }
  const std::string name = t->materials[size_t(layer)].name;
  Edit e(doc, QString("Remove paint layer %1").arg(QString::fromStdString(name)));
  TerrainAsset& a = e.terrain(id);
  a.data = std::make_shared<TerrainData>(std::move(copy));
  a.materials.erase(a.materials.begin() + layer);
  a.paintRules = rulesWithoutLayer(a.paintRules, layer);
  return e.commit();
}

}  // namespace hs::scene::ops
