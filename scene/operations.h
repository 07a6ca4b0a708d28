#pragma once
// The named edits the editor's menus, the CLI and tests call. Each is one
// undo step built with Edit (edit.h); each refuses bad arguments without
// touching the document and says why through its return value.
#include <string>
#include <vector>

#include <QString>

#include "mesh/mesh_import.h"
#include "scene/document.h"
#include "scene/fields.h"

namespace hs::scene {
struct ImportedMesh;
}

namespace hs::scene::ops {

struct Placement {
  // Unset: the mesh lands at its own (e.g. UTM) coordinates. Set: the centre
  // of the base of its bounding box goes to this world position.
  std::optional<glm::dvec3> at;
  EntityId parent = kNoEntity;
};

// Adds the mesh as an asset and an entity showing it, in one undo step.
// Returns the entity id.
EntityId addImportedMesh(Document& doc, mesh::MeshData mesh, const std::string& name,
                         const std::string& sourcePath, const mesh::ImportReport& report,
                         const Placement& placement = {});
// The same for what scene::importMeshFiles made (import_pipeline.h): the
// asset carries its LOD levels and processing report too. Undo removes
// all of it. Returns kNoEntity (and changes nothing) if `imported` has no mesh.
EntityId addImportedMesh(Document& doc, ImportedMesh imported, const std::string& name,
                         const std::string& sourcePath, const Placement& placement = {});

EntityId addEmpty(Document& doc, const std::string& name, const Transform& t = {},
                  EntityId parent = kNoEntity);
EntityId addCamera(Document& doc, const std::string& name, const Transform& t, const Camera& c = {});
EntityId addLight(Document& doc, const std::string& name, const Transform& t, const Light& l = {});

bool rename(Document& doc, EntityId id, const std::string& name);
// Sets several transforms at once (a gizmo drag on a multi-selection).
bool setTransforms(Document& doc, const std::vector<std::pair<EntityId, Transform>>& transforms,
                   const QString& text, const QString& mergeKey = {});
// What setField / setSettingsField did with a value outside its field's
// range or rule (scene/fields.cpp): the value the field holds afterwards and
// a message for the user ("Camera: Vertical field of view 500 must be from
// 1 to 170 °; set to 170"; "...; unchanged" where nothing was stored).
// `message` is empty when the value was stored as given.
struct FieldChange {
  FieldValue value;
  std::string message;
};
// The field's setter clamps what it is handed (a zero scale becomes a tiny
// one, a non-finite value keeps the old one); `change`, when given, says
// so. The CLI prints the message, the editor shows it in Messages.
bool setField(Document& doc, EntityId id, const EntityField& field, const FieldValue& value,
              const QString& mergeKey = {}, FieldChange* change = nullptr);
bool setSettingsField(Document& doc, const SettingsField& field, const FieldValue& value,
                      const QString& mergeKey = {}, FieldChange* change = nullptr);
// Removes camera `id`'s override of a post setting ("bloom.intensity",
// scene/camera_post.h): the camera shows the scene's value again. False if
// it had none. A track keying "camera.post.<key>" sets it again at its times.
bool clearCameraPost(Document& doc, EntityId id, const std::string& key);
bool addComponent(Document& doc, EntityId id, const ComponentInfo& component);
bool removeComponent(Document& doc, EntityId id, const ComponentInfo& component);
bool reparent(Document& doc, EntityId id, EntityId newParent, int index = -1);
// Removes the entities (and their subtrees); ids below another listed id are fine.
bool remove(Document& doc, const std::vector<EntityId>& ids);
// Duplicates each (top-most) entity with its subtree; returns the copies.
std::vector<EntityId> duplicate(Document& doc, const std::vector<EntityId>& ids);

// Keeps only ids that are not below another id of the list.
std::vector<EntityId> topMost(const SceneState& state, const std::vector<EntityId>& ids);

}  // namespace hs::scene::ops
