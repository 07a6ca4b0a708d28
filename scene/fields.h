#pragma once
// Reflection of every editable value: one table drives the property panel,
// the JSON in .hscene files, `hybridscape-cli set`, and (later) animation
// tracks, so a field added here is editable, saved and animatable at once.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "scene/entity.h"
#include "scene/field_value.h"
#include "scene/scene_state.h"

namespace hs::scene {

enum class FieldType {
  Double,   // double
  Bool,     // bool
  Enum,     // int64 index into enumNames
  Vec3,     // dvec3 (positions, angles, scales)
  Color,    // dvec3, linear RGB 0..1
  String,   // std::string
  AssetRef  // int64 asset id
};

template <class Target>
struct FieldInfo {
  std::string key;    // "fov_deg"; full path is "<component>.<key>"
  std::string label;  // "Field of view"
  FieldType type = FieldType::Double;
  double min = -1e300, max = 1e300, step = 0.1;
  std::string unit;   // "m", "°", ...
  std::vector<std::string> enumNames;
  std::function<FieldValue(const Target&)> get;
  std::function<void(Target&, const FieldValue&)> set;  // clamps to [min,max]
  // A rule beyond [min, max], declared with the field (names non-empty,
  // scale non-zero, far beyond near): why `v` is no valid value, or "".
  // `current` is the object it would go into, or null where the other
  // values are not known (a key's value, parsed text); rules that compare
  // with another field apply only with it.
  std::function<std::string(const FieldValue& v, const Target* current)> check;
  // What the file loader puts in place of a value that breaks `check` (the
  // setter already clamps to [min, max]); null where the setter fixes it.
  std::function<void(Target&)> repair;
  bool animatable = true;
  // False for a field derived from another (focal length from field of
  // view): shown and animatable, but not written to files twice.
  bool serialized = true;
};

using EntityField = FieldInfo<Entity>;
using SettingsField = FieldInfo<SceneSettings>;
using MaterialField = FieldInfo<Material>;

// A group of fields on an entity: "entity" (name, visible), "transform",
// and one per optional component ("mesh", "light", "camera").
struct ComponentInfo {
  std::string key;
  std::string label;
  bool optional = true;  // false for entity/transform: always present
  std::function<bool(const Entity&)> has;
  std::function<void(Entity&)> add;     // default-constructed
  std::function<void(Entity&)> remove;
  std::vector<EntityField> fields;
};

const std::vector<ComponentInfo>& entityComponents();
const std::vector<SettingsField>& settingsFields();
// A material's editable values (scene/material.h); keys as `hybridscape-cli
// material list` prints them ("opacity", "roughness", "model"). Texture
// references are AssetRef fields holding a texture id (0: none).
const std::vector<MaterialField>& materialFields();

const ComponentInfo* findComponent(std::string_view key);
// "camera.fov_deg" -> the field; nullptr if unknown.
const EntityField* findEntityField(std::string_view path);
const SettingsField* findSettingsField(std::string_view key);
const MaterialField* findMaterialField(std::string_view key);

// Parses a value for `type` from text ("1,2,3" for vectors, "true"/"1",
// enum names or indices). Returns nullopt with `error` set if it does not fit.
template <class Target>
std::optional<FieldValue> parseFieldValue(const FieldInfo<Target>& field, std::string_view text,
                                          std::string& error);
// Why `v` is no valid value of the field (out of [min, max], not finite,
// against its `check`), "" if it is valid. With `current` null, only what
// the value alone decides. The CLI (set, key), the editor (ops::setField)
// and the file loader all ask this one function.
template <class Target>
std::string fieldValueProblem(const FieldInfo<Target>& field, const FieldValue& v, const Target* current);

// `digits` significant digits: 17 (the default) reads back exactly; messages use 6.
std::string formatFieldValue(FieldType type, const FieldValue& v,
                             const std::vector<std::string>& enumNames = {}, int digits = 17);

}  // namespace hs::scene
