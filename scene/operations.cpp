#include "scene/operations.h"

#include <algorithm>

#include "scene/asset_reports.h"
#include "scene/camera_post.h"
#include "scene/edit.h"
#include "scene/import_pipeline.h"
#include "scene/mesh_materials.h"

namespace hs::scene::ops {

namespace {

// One undo step: the asset (with whatever levels and reports it carries)
// and an entity showing it.
EntityId addMeshAsset(Document& doc, MeshAsset asset, const std::string& name, const Placement& placement) {
  const mesh::Bounds b = asset.data->bounds();
  const glm::dvec3 origin = asset.data->origin;
  Edit e(doc, QString("Import %1").arg(QString::fromStdString(name)));
  // The mesh's materials and textures become document objects in the same step.
  if (asset.id == kNoAsset) asset.id = doc.allocateAssetId();
  if (asset.name.empty()) asset.name = name;
  MeshMaterials made = makeMeshMaterials(
      asset, {[&doc] { return doc.allocateMaterialId(); }, [&doc] { return doc.allocateTextureId(); },
              [&doc](const std::string& n) { return doc.state().findMaterialByName(n) != kNoMaterial; }});
  for (TextureAsset& t : made.textures) e.addTexture(std::move(t));
  for (Material& m : made.materials) e.addMaterial(std::move(m));
  asset.materialSlots = std::move(made.slotIds);
  const AssetId assetId = e.addAsset(std::move(asset));
  Entity ent;
  ent.name = name;
  ent.mesh = MeshInstance{assetId};
  // The mesh's vertices are relative to its origin: an entity at the origin
  // puts it exactly where the file had it.
  ent.transform.translation = origin;
  if (placement.at) {
    const glm::dvec3 baseCentre(b.center().x, b.center().y, b.min.z);
    ent.transform.translation = *placement.at - baseCentre;
  }
  const EntityId id = e.addEntity(std::move(ent), placement.parent);
  e.commit();
  return id;
}

}  // namespace

EntityId addImportedMesh(Document& doc, mesh::MeshData meshData, const std::string& name,
                         const std::string& sourcePath, const mesh::ImportReport& report,
                         const Placement& placement) {
  MeshAsset asset;
  asset.name = name;
  asset.sourcePath = sourcePath;
  asset.contentHash = mesh::contentHash(meshData);
  asset.importReport = toJson(AssetImportReport{report, {}});
  asset.data = std::make_shared<const mesh::MeshData>(std::move(meshData));
  return addMeshAsset(doc, std::move(asset), name, placement);
}

EntityId addImportedMesh(Document& doc, ImportedMesh imported, const std::string& name,
                         const std::string& sourcePath, const Placement& placement) {
  if (!imported.mesh) return kNoEntity;
  MeshAsset asset;
  asset.name = name;
  asset.sourcePath = sourcePath;
  asset.contentHash = mesh::contentHash(*imported.mesh);
  asset.importReport = std::move(imported.importReport);
  asset.processReport = std::move(imported.processReport);
  asset.lods = std::move(imported.lods);
  asset.clusters = std::move(imported.clusters);
  asset.clustersHash = imported.clustersHash;
  asset.data = std::make_shared<const mesh::MeshData>(std::move(*imported.mesh));
  return addMeshAsset(doc, std::move(asset), name, placement);
}

EntityId addEmpty(Document& doc, const std::string& name, const Transform& t, EntityId parent) {
  Edit e(doc, QString("Add %1").arg(QString::fromStdString(name)));
  Entity ent;
  ent.name = name;
  ent.transform = t;
  const EntityId id = e.addEntity(std::move(ent), parent);
  e.commit();
  return id;
}

EntityId addCamera(Document& doc, const std::string& name, const Transform& t, const Camera& c) {
  Edit e(doc, QString("Add camera %1").arg(QString::fromStdString(name)));
  Entity ent;
  ent.name = name;
  ent.transform = t;
  ent.camera = c;
  const EntityId id = e.addEntity(std::move(ent));
  e.commit();
  return id;
}

EntityId addLight(Document& doc, const std::string& name, const Transform& t, const Light& l) {
  Edit e(doc, QString("Add light %1").arg(QString::fromStdString(name)));
  Entity ent;
  ent.name = name;
  ent.transform = t;
  ent.light = l;
  const EntityId id = e.addEntity(std::move(ent));
  e.commit();
  return id;
}

bool rename(Document& doc, EntityId id, const std::string& name) {
  if (!doc.state().find(id) || name.empty()) return false;
  Edit e(doc, QString("Rename to %1").arg(QString::fromStdString(name)));
  e.entity(id).name = name;
  return e.commit();
}

bool setTransforms(Document& doc, const std::vector<std::pair<EntityId, Transform>>& transforms,
                   const QString& text, const QString& mergeKey) {
  Edit e(doc, text, mergeKey);
  for (const auto& [id, t] : transforms) {
    if (!e.exists(id)) return false;
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(t.translation[i]) || !std::isfinite(t.scale[i])) return false;
    e.entity(id).transform = t;
  }
  return e.commit();
}

namespace {

// The message of a FieldChange: `who` the entity ("" for settings), the
// value asked for, why it could not be kept, and what the field holds now.
template <class Target>
std::string clampMessage(const std::string& who, const FieldInfo<Target>& field, const FieldValue& asked,
                         const std::string& problem, const FieldValue& held, bool stored) {
  const auto shown = [&field](const FieldValue& x) {
    const std::string text = formatFieldValue(field.type, x, field.enumNames, 6);
    return field.type == FieldType::String ? "'" + text + "'" : text;
  };
  return (who.empty() ? "" : who + ": ") + field.label + " " + shown(asked) + " " + problem +
         (!stored ? "; unchanged" : held != asked ? "; set to " + shown(held) : "; stored as given");
}

}  // namespace

bool setField(Document& doc, EntityId id, const EntityField& field, const FieldValue& value,
              const QString& mergeKey, FieldChange* change) {
  if (!doc.state().find(id)) return false;
  Edit e(doc, QString("Set %1").arg(QString::fromStdString(field.label)), mergeKey);
  Entity& ent = e.entity(id);
  // A component field on an entity without that component: refuse.
  for (const auto& c : entityComponents())
    for (const auto& f : c.fields)
      if (&f == &field && !c.has(ent)) return false;
  // A mesh reference must name an asset of this scene (0: none); anything
  // else leaves a document that fails validate() and a file that will not open.
  if (field.type == FieldType::AssetRef && std::get<int64_t>(value) > 0 &&
      !doc.state().findAsset(AssetId(std::get<int64_t>(value))))
    return false;
  const std::string problem = fieldValueProblem(field, value, &ent);
  const std::string who = ent.name;
  field.set(ent, value);
  const FieldValue held = field.get(ent);
  const bool stored = e.commit();
  if (change) {
    change->value = held;
    change->message = problem.empty() ? std::string() : clampMessage(who, field, value, problem, held, stored);
  }
  return stored;
}

bool clearCameraPost(Document& doc, EntityId id, const std::string& key) {
  const Entity* now = doc.state().find(id);
  if (!now || !now->camera || !now->camera->post.count(key)) return false;
  const EntityField* field = findCameraPostField(key);
  Edit e(doc, QString("Reset %1").arg(QString::fromStdString(field ? field->label : key)));
  e.entity(id).camera->post.erase(key);
  return e.commit();
}

bool setSettingsField(Document& doc, const SettingsField& field, const FieldValue& value,
                      const QString& mergeKey, FieldChange* change) {
  Edit e(doc, QString("Set %1").arg(QString::fromStdString(field.label)), mergeKey);
  const std::string problem = fieldValueProblem(field, value, &e.settings());
  field.set(e.settings(), value);
  const FieldValue held = field.get(e.settings());
  const bool stored = e.commit();
  if (change) {
    change->value = held;
    change->message = problem.empty() ? std::string() : clampMessage("", field, value, problem, held, stored);
  }
  return stored;
}

bool addComponent(Document& doc, EntityId id, const ComponentInfo& component) {
  if (!doc.state().find(id) || !component.optional) return false;
  Edit e(doc, QString("Add %1").arg(QString::fromStdString(component.label)));
  component.add(e.entity(id));
  return e.commit();
}

bool removeComponent(Document& doc, EntityId id, const ComponentInfo& component) {
  if (!doc.state().find(id) || !component.optional) return false;
  Edit e(doc, QString("Remove %1").arg(QString::fromStdString(component.label)));
  const auto& shown = e.entity(id).terrain;
  const TerrainId terrain = shown ? shown->terrain : kNoTerrain;
  component.remove(e.entity(id));
  e.removeTerrainIfUnused(terrain);  // a terrain nothing shows leaves the document (undo brings it back)
  return e.commit();
}

bool reparent(Document& doc, EntityId id, EntityId newParent, int index) {
  Edit e(doc, "Reparent");
  if (!e.reparent(id, newParent, index, true)) return false;
  return e.commit();
}

std::vector<EntityId> topMost(const SceneState& state, const std::vector<EntityId>& ids) {
  std::vector<EntityId> out;
  for (EntityId id : ids) {
    if (!state.find(id)) continue;
    bool below = false;
    for (EntityId other : ids)
      if (other != id && state.isAncestorOrSelf(other, id)) below = true;
    if (!below && std::find(out.begin(), out.end(), id) == out.end()) out.push_back(id);
  }
  return out;
}

bool remove(Document& doc, const std::vector<EntityId>& ids) {
  const auto top = topMost(doc.state(), ids);
  if (top.empty()) return false;
  Edit e(doc, top.size() == 1 ? QString("Delete %1").arg(QString::fromStdString(doc.state().find(top[0])->name))
                              : QString("Delete %1 entities").arg(top.size()));
  for (EntityId id : top) e.removeEntity(id);
  return e.commit();
}

std::vector<EntityId> duplicate(Document& doc, const std::vector<EntityId>& ids) {
  const auto top = topMost(doc.state(), ids);
  std::vector<EntityId> out;
  if (top.empty()) return out;
  Edit e(doc, top.size() == 1 ? QString("Duplicate %1").arg(QString::fromStdString(doc.state().find(top[0])->name))
                              : QString("Duplicate %1 entities").arg(top.size()));
  for (EntityId id : top) {
    const EntityId copy = e.duplicate(id);
    e.entity(copy).name = e.peek(id)->name + " copy";
    out.push_back(copy);
  }
  e.commit();
  return out;
}

}  // namespace hs::scene::ops
