#include "scene/camera_post.h"

#include "scene/components.h"

namespace hs::scene {

bool cameraOverridable(const SettingsField& field) {
  return field.key.rfind("post.", 0) == 0 || field.key == "exposure_ev100" || field.key == "tonemap" ||
         field.key == "antialiasing";
}

std::string cameraPostKey(std::string_view settingsKey) {
  if (settingsKey.substr(0, 5) == "post.") settingsKey.remove_prefix(5);
  return std::string(settingsKey);
}

const SettingsField* cameraPostSetting(std::string_view key) {
  for (const SettingsField& f : settingsFields())
    if (cameraOverridable(f) && cameraPostKey(f.key) == key) return &f;
  return nullptr;
}

namespace {

std::vector<EntityField> buildCameraPostFields() {
  std::vector<EntityField> out;
  for (const SettingsField& s : settingsFields()) {
    if (!cameraOverridable(s)) continue;
    const std::string key = cameraPostKey(s.key);
    const SettingsField* setting = &s;
    EntityField f;
    f.key = "post." + key;
    f.label = s.label;
    f.type = s.type;
    f.min = s.min;
    f.max = s.max;
    f.step = s.step;
    f.unit = s.unit;
    f.enumNames = s.enumNames;
    f.animatable = s.animatable;
    f.serialized = false;  // written as the camera's "post" object (scene_json.cpp)
    f.get = [setting, key](const Entity& e) {
      if (e.camera)
        if (auto it = e.camera->post.find(key); it != e.camera->post.end()) return it->second;
      return setting->get(SceneSettings{});
    };
    // Through the setting's own setter on a scratch copy, so a camera's
    // value is clamped and rounded exactly as the scene's would be.
    f.set = [setting, key](Entity& e, const FieldValue& v) {
      if (!e.camera) return;
      SceneSettings scratch;
      if (auto it = e.camera->post.find(key); it != e.camera->post.end()) setting->set(scratch, it->second);
      setting->set(scratch, v);
      e.camera->post[key] = setting->get(scratch);
    };
    // Rules of the setting that the value alone decides (those between
    // settings have no other value to compare with here).
    if (s.check)
      f.check = [setting](const FieldValue& v, const Entity*) { return setting->check(v, nullptr); };
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace

const std::vector<EntityField>& cameraPostFields() {
  static const std::vector<EntityField> table = buildCameraPostFields();
  return table;
}

const EntityField* findCameraPostField(std::string_view key) {
  for (const EntityField& f : cameraPostFields())
    if (std::string_view(f.key).substr(5) == key) return &f;
  return nullptr;
}

SceneSettings settingsThrough(const SceneSettings& settings, const Camera& camera) {
  SceneSettings s = settings;
  const float ev = s.exposureEv100;
  for (const auto& [key, value] : camera.post)
    if (const SettingsField* f = cameraPostSetting(key)) f->set(s, value);
  if (s.post.autoExposure) s.exposureEv100 = ev;
  return s;
}

SceneSettings settingsFor(const SceneState& state, EntityId camera) {
  const Entity* e = camera == kNoEntity ? nullptr : state.find(camera);
  if (!e || !e->camera || e->camera->post.empty()) return state.settings;
  return settingsThrough(state.settings, *e->camera);
}

bool samePostChain(const SceneSettings& a, const SceneSettings& b) {
  if (a.post.lut != b.post.lut) return false;  // the table itself is no field
  for (const SettingsField& f : settingsFields())
    if (cameraOverridable(f) && f.get(a) != f.get(b)) return false;
  return true;
}

}  // namespace hs::scene
