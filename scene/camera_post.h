#pragma once
// A camera's own post settings (Camera::post): which scene settings a
// camera may override, the entity fields that edit them
// ("camera.post.bloom.intensity" for the setting "post.bloom.intensity"),
// and the settings a view through a camera renders with. As in Unreal's
// camera post-process settings, an override replaces the scene's value of
// that one field; the rest stays the scene's.
#include <string>
#include <string_view>
#include <vector>

#include "scene/fields.h"
#include "scene/scene_state.h"

namespace hs::scene {

// The settings a camera may override: the post chain (post.*), the
// exposure, the tone map and the anti-aliasing mode.
bool cameraOverridable(const SettingsField& field);
// "post.bloom.intensity" -> "bloom.intensity", "tonemap" -> "tonemap": the
// key in Camera::post and after "camera.post." in a field path.
std::string cameraPostKey(std::string_view settingsKey);
// The settings field a Camera::post key overrides; null if none may.
const SettingsField* cameraPostSetting(std::string_view key);

// One entity field per overridable setting, key "post.<camera post key>",
// found by findEntityField("camera.post.<key>") (so `set`, animation
// tracks and files take them like any camera field). Not in the camera
// component's own list: absent overrides are no values. `get` answers the
// override, or the setting's default where the camera has none; `set`
// clamps as the setting does and adds the override; entities without a
// camera are left alone.
const std::vector<EntityField>& cameraPostFields();
const EntityField* findCameraPostField(std::string_view key);  // "bloom.intensity"

// `settings` with the camera's overrides applied. The exposure EV100 is
// the manual exposure: with automatic exposure on in the result, the
// camera's exposure_ev100 is not applied (the caller's metered EV in
// settings.exposureEv100 stands).
SceneSettings settingsThrough(const SceneSettings& settings, const Camera& camera);
// The settings a view through entity `camera` renders with: the scene's
// where it is no camera (kNoEntity, a free view).
SceneSettings settingsFor(const SceneState& state, EntityId camera);
// True if the two settings give the same post chain (every overridable
// field equal): two shots of a transition then combine in linear light
// before one chain; otherwise each shot runs its own chain and the
// transition combines the finished pictures (render/renderer.h).
bool samePostChain(const SceneSettings& a, const SceneSettings& b);

}  // namespace hs::scene
