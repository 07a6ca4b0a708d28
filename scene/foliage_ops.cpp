#include "scene/foliage_ops.h"

#include <cmath>

#include "scene/edit.h"
#include "scene/foliage_command.h"
#include "scene/mesh_materials.h"

namespace hs::scene::ops {
namespace {

FoliageOutcome refused(std::string error) {
  FoliageOutcome out;
  out.ok = false;
  out.error = std::move(error);
  return out;
}

std::string count(size_t n, const char* what) { return std::to_string(n) + " " + what; }

// The edit's result as an outcome, its undo data pushed as one step.
FoliageOutcome record(Document& doc, foliage::EditResult r, const QString& text) {
  FoliageOutcome out;
  out.stats = r.stats;
  out.messages = r.stats.messages;
  pushFoliageEdit(doc, std::move(r.undo), text);
  out.summary = count(r.stats.placed, "placed") + ", " + count(r.stats.removed, "removed") + "; " +
                count(doc.foliage().store().instanceCount(), "instances") + " in " +
                count(doc.foliage().store().cellCount(), "cells");
  return out;
}

// Work done on the document's own store: refused, or recorded as one step.
FoliageOutcome recordWork(Document& doc, FoliageWork work) {
  if (!work.error.empty()) return refused(std::move(work.error));
  return record(doc, std::move(work.result), work.text);
}

std::string checkTypes(const foliage::FoliageStore& store, const foliage::TypeSet& types) {
  for (uint16_t t : types)
    if (t >= store.types().size()) return "foliage type " + std::to_string(t) + " does not exist";
  return {};
}

}  // namespace

FoliageOutcome addFoliageType(Document& doc, const foliage::FoliageType& type) {
  if (foliageTypeAsset(doc.state(), type) == kNoAsset)
    return refused("foliage type \"" + type.name + "\": mesh: no mesh asset named \"" + type.mesh +
                   "\" in the scene (add one with `foliage plant` or `import`)");
  if (const std::vector<std::string> problems = foliage::validate(type); !problems.empty())
    return refused(problems.front());
  foliage::FoliageStore& store = doc.foliage().store();
  std::vector<foliage::FoliageType> before = store.types();
  FoliageOutcome out;
  if (store.addType(type, out.messages) < 0) return refused(out.messages.back());
  pushFoliageTypes(doc, std::move(before), {}, QString("Add foliage type %1").arg(QString::fromStdString(type.name)));
  out.summary = "foliage type \"" + type.name + "\" draws \"" + type.mesh + "\"";
  return out;
}

FoliageOutcome setFoliageType(Document& doc, size_t index, const foliage::FoliageType& type) {
  foliage::FoliageStore& store = doc.foliage().store();
  if (index >= store.types().size()) return refused("foliage type " + std::to_string(index) + " does not exist");
  if (const int other = store.findType(type.name); other >= 0 && size_t(other) != index)
    return refused("foliage type \"" + type.name + "\": name: a type of that name exists");
  if (foliageTypeAsset(doc.state(), type) == kNoAsset)
    return refused("foliage type \"" + type.name + "\": mesh: no mesh asset named \"" + type.mesh + "\"");
  if (const std::vector<std::string> problems = foliage::validate(type); !problems.empty())
    return refused(problems.front());
  std::vector<foliage::FoliageType> before = store.types();
  FoliageOutcome out;
  foliage::FoliageUndo cells;
  store.setType(index, type, &cells, out.messages);
  pushFoliageTypes(doc, std::move(before), std::move(cells),
                   QString("Change foliage type %1").arg(QString::fromStdString(type.name)));
  out.summary = "foliage type \"" + type.name + "\" changed";
  return out;
}

FoliageWork scatterOnStore(foliage::FoliageStore& store, const FoliageGround& ground, const foliage::TypeSet& types,
                           uint64_t seed, const std::optional<foliage::Region2>& region,
                           const std::optional<foliage::FoliageType>& rules, unsigned threads,
                           const Progress* progress) {
  FoliageWork work;
  foliage::TypeSet set = types;
  if (set.empty())
    for (size_t t = 0; t < store.types().size(); ++t) set.push_back(uint16_t(t));
  if (set.empty()) work.error = "the scene has no foliage types (add one with `foliage type add`)";
  else work.error = checkTypes(store, set);
  if (work.error.empty() && ground.empty()) work.error = "the scene has nothing to scatter on (no visible terrain or mesh)";
  if (!work.error.empty()) return work;
  // The overrides stand in for the type's rules during this scatter only.
  std::optional<foliage::FoliageType> saved;
  std::vector<std::string> warnings;
  if (rules && set.size() == 1) {
    saved = store.type(set[0]);
    foliage::FoliageType r = *rules;
    r.name = saved->name;
    r.mesh = saved->mesh;
    r.scaleMode = saved->scaleMode;  // the records' encoding stays
    store.setType(set[0], r, nullptr, warnings);
  }
  work.result = foliage::scatter(store, ground.ground(), set, seed, region, threads, set.size() > 1, progress);
  if (saved) store.setType(set[0], *saved, nullptr, warnings);
  work.result.stats.messages.insert(work.result.stats.messages.end(), warnings.begin(), warnings.end());
  const std::string name = set.size() == 1 ? store.type(set[0]).name : std::to_string(set.size()) + " types";
  work.text = QString("Scatter %1").arg(QString::fromStdString(name));
  return work;
}

FoliageOutcome scatterFoliage(Document& doc, const FoliageGround& ground, const foliage::TypeSet& types,
                              uint64_t seed, const std::optional<foliage::Region2>& region,
                              const std::optional<foliage::FoliageType>& rules, unsigned threads) {
  return recordWork(doc, scatterOnStore(doc.foliage().store(), ground, types, seed, region, rules, threads));
}

FoliageOutcome commitFoliageWork(Document& doc, foliage::FoliageStore& worked, FoliageWork work) {
  if (!work.error.empty()) return refused(std::move(work.error));
  if (work.result.cancelled) {
    FoliageOutcome out;
    out.stats = work.result.stats;
    out.summary = "cancelled: nothing changed";
    out.cancelled = true;
    return out;
  }
  // The edit's undo data holds the cells as the document has them: swapped
  // with the copy it takes the copy's new cells (and the copy is the
  // document's again); swapped with the document's store it puts them there
  // and holds the document's old cells, the step's undo data.
  work.result.undo.swap(worked);
  // The work was computed from the cells as they were copied: where the
  // document's differ now (an edit while it ran), nothing changes.
  foliage::FoliageStore& store = doc.foliage().store();
  bool same = worked.nextId() == store.nextId() && worked.types() == store.types();
  for (const foliage::CellKey& k : work.result.undo.keys()) {
    const foliage::Cell *was = worked.cell(k), *now = store.cell(k);
    same = same && (was == nullptr) == (now == nullptr) && (!was || *was == *now);
  }
  if (!same)
    return refused(work.text.toStdString() + ": the foliage changed while it ran: nothing changed (run it again)");
  work.result.undo.swap(store);
  return record(doc, std::move(work.result), work.text);
}

FoliageOutcome paintFoliage(Document& doc, const FoliageGround& ground, const foliage::PaintParams& params,
                            bool fill, const QString& text) {
  foliage::FoliageStore& store = doc.foliage().store();
  if (params.types.empty()) return refused("no foliage type chosen to paint");
  if (std::string e = checkTypes(store, params.types); !e.empty()) return refused(e);
  foliage::EditResult r = fill ? foliage::fill(store, ground.ground(), params.region, params.types, params.seed,
                                               params.threads)
                               : foliage::paint(store, ground.ground(), params);
  return record(doc, std::move(r), text);
}

FoliageOutcome fillFoliageLayer(Document& doc, const FoliageGround& ground, const foliage::TypeSet& types,
                                const std::string& layer, double minWeight, uint64_t seed,
                                const std::optional<foliage::Region2>& region) {
  return recordWork(doc, fillLayerOnStore(doc.foliage().store(), ground, types, layer, minWeight, seed, region));
}

FoliageWork fillLayerOnStore(foliage::FoliageStore& store, const FoliageGround& ground, const foliage::TypeSet& types,
                             const std::string& layer, double minWeight, uint64_t seed,
                             const std::optional<foliage::Region2>& region, const Progress* progress) {
  FoliageWork work;
  if (types.empty()) work.error = "no foliage type chosen to fill";
  else work.error = checkTypes(store, types);
  if (work.error.empty() && !ground.ground().terrain) work.error = "fill: the scene has no visible terrain";
  if (work.error.empty() && foliage::terrainLayerIndex(*ground.ground().terrain, layer) < 0)
    work.error = "fill: the terrain has no paint layer \"" + layer + "\"";
  if (!work.error.empty()) return work;
  work.result = foliage::fillLayer(store, ground.ground(), layer, minWeight, types, seed, region, 0, progress);
  work.text = QString("Fill paint layer %1").arg(QString::fromStdString(layer));
  return work;
}

namespace {

// The region, or everywhere: the rectangle around every cell.
foliage::Region2 areaOf(const foliage::FoliageStore& store, const std::optional<foliage::Region2>& region) {
  if (region) return *region;
  if (store.cells().empty()) return foliage::Region2::rect(glm::dvec2(0.0), glm::dvec2(0.0));
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
  for (const auto& [k, c] : store.cells()) {
    lo = glm::min(lo, glm::dvec2(k.origin()));
    hi = glm::max(hi, glm::dvec2(k.origin()) + foliage::kCellSize);
  }
  return foliage::Region2::rect(lo, hi);
}

}  // namespace

FoliageOutcome eraseFoliage(Document& doc, const std::optional<foliage::Region2>& region,
                            const foliage::TypeSet& types, const QString& text) {
  foliage::FoliageStore& store = doc.foliage().store();
  if (std::string e = checkTypes(store, types); !e.empty()) return refused(e);
  return record(doc, foliage::erase(store, areaOf(store, region), types), text);
}

FoliageOutcome moveFoliage(Document& doc, const FoliageGround& ground, const foliage::TypeSet& types,
                           const std::optional<foliage::Region2>& region, const glm::dvec3& offset, bool snap) {
  foliage::FoliageStore& store = doc.foliage().store();
  if (std::string e = checkTypes(store, types); !e.empty()) return refused(e);
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(offset.z))
    return refused("the offset is not a finite number of metres");
  foliage::Selection selection = foliage::selectRegion(store, areaOf(store, region), types);
  if (selection.empty() || offset == glm::dvec3(0.0)) {
    FoliageOutcome out;
    out.summary = "nothing moved";
    return out;
  }
  FoliageOutcome out = record(doc, foliage::moveSelection(store, ground.ground(), selection, offset, snap), "Move foliage");
  out.summary = count(out.stats.moved, "moved") + "; " + count(store.instanceCount(), "instances") + " in " +
                count(store.cellCount(), "cells");
  return out;
}

std::optional<MeshAsset> makePlantAsset(const std::string& name, const foliage::PlantParams& params,
                                        std::string& error, foliage::PlantStats* stats) {
  mesh::LodChain chain = foliage::generatePlantLods(params, {}, stats);
  if (!chain.error.empty() || chain.levels.empty()) {
    error = "foliage plant \"" + name + "\": " + (chain.error.empty() ? "no mesh made" : chain.error);
    return std::nullopt;
  }
  MeshAsset asset;
  asset.name = name;
  asset.sourcePath = std::string("generated: ") + foliage::plantKindName(params.kind) + ", seed " +
                     std::to_string(params.seed);
  for (size_t k = 1; k < chain.levels.size(); ++k) {
    MeshLod l;
    l.contentHash = mesh::contentHash(chain.levels[k].mesh);
    l.triangles = chain.levels[k].mesh.triangleCount();
    l.hausdorff = chain.levels[k].hausdorff;
    l.data = std::make_shared<const mesh::MeshData>(std::move(chain.levels[k].mesh));
    asset.lods.push_back(std::move(l));
  }
  asset.contentHash = mesh::contentHash(chain.levels[0].mesh);
  asset.data = std::make_shared<const mesh::MeshData>(std::move(chain.levels[0].mesh));
  return asset;
}

void applyPlantLook(Material& m) {
  const bool card = m.baseColorTexture != kNoTexture;
  m.twoSided = card;
  m.alphaCutout = card;
  m.alphaThreshold = 0.5f;
  m.roughness = 0.8f;
  // A leaf lets about a third of the light through (back-lit crowns glow);
  // bark none.
  m.transmission = card ? 0.3f : 0.0f;
}

AssetId addPlantAsset(Document& doc, const std::string& name, const foliage::PlantParams& params,
                      std::string& error, foliage::PlantStats* stats) {
  if (name.empty()) {
    error = "foliage plant: the asset needs a name";
    return kNoAsset;
  }
  for (const auto& [id, a] : doc.state().assets)
    if (a.name == name) {
      error = "foliage plant: a mesh asset named \"" + name + "\" exists";
      return kNoAsset;
    }
  std::optional<MeshAsset> asset = makePlantAsset(name, params, error, stats);
  if (!asset) return kNoAsset;
  asset->id = doc.allocateAssetId();
  Edit e(doc, QString("Generate plant %1").arg(QString::fromStdString(name)));
  MeshMaterials made = makeMeshMaterials(
      *asset, {[&doc] { return doc.allocateMaterialId(); }, [&doc] { return doc.allocateTextureId(); },
               [&doc](const std::string& n) { return doc.state().findMaterialByName(n) != kNoMaterial; }});
  for (TextureAsset& t : made.textures) e.addTexture(std::move(t));
  for (Material& m : made.materials) {
    applyPlantLook(m);
    e.addMaterial(std::move(m));
  }
  asset->materialSlots = std::move(made.slotIds);
  const AssetId id = e.addAsset(std::move(*asset));
  e.commit();
  return id;
}

}  // namespace hs::scene::ops
