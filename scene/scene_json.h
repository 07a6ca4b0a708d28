#pragma once
// The scene description as JSON (hs::Json, core/json.h): the text part of a
// .hscene file, and the canonical form tests compare documents by. Bulk
// data (mesh arrays, textures, terrain tiles) is not in it; assets carry
// their content hash instead. Members are written in a fixed order
// (format, version, settings, roots, entities, assets, materials,
// textures, terrains, foliage, sequence),
// so files diff cleanly.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/json.h"
#include "scene/scene_state.h"

namespace hs::scene {

// 2: terrains (description "terrains", tile blobs "terrain/<id>/..."). A
// version-1 reader would drop them silently, so it is told the file is newer.
// 3: mesh LODs (assets' "lods", blobs "mesh/<id>/lod<k>") and processing
// reports; a version-2 reader would drop the LODs on its next save.
// 4: content hashes by XXH3 (hscene_file.cpp).
// 5: materials and textures as document objects ("materials", "textures",
// assets' "material_slots", blobs "texture/<id>"); a version-4 reader would
// drop them on its next save. Older files get their materials from their
// meshes on load (mesh_materials.h).
// 6: lights in physical units (lux, lumens; light_units.h), spot lights and
// their cones, shadow flags, and the exposure as "exposure_ev100" instead of
// a multiplier ("exposure"). Older files are converted on load so that they
// render as before (migrateToPhysicalLightUnits); a version-5 reader would
// take lux for its old intensities.
// 7: each light's casts_shadows is read (settings.shadows stays the master
// switch). Before, a sun cast shadows whenever settings.shadows was on and
// the flag was stored unread, so older files get casts_shadows true on
// every sun (migratePerLightShadows); point and spot lights keep what the
// user stored. A version-6 reader would give back sun shadows a file turned off.
// 8: the shaders return physical radiance (the BRDF's 1/π, docs/rendering.md
// "Lights and exposure") and the reference EV100 moved from 15.2 to 15.2 −
// log2 π. Files of versions 6 and 7 keep their look: their exposure and
// the keys of its track move by −log2 π, lights keep their values
// (migrateToPhysicalBrdf); files 1-5 go straight to this format's units
// (migrateToPhysicalLightUnits). The analytic sky is brighter against the
// sun than before (it is now tied to the lights' unit): that is the fix.
// A version-7 reader would show a version-8 file π times too bright.
// 9: foliage (the description's "foliage" manifest, blobs
// "foliage/cell/X_Y_Z"; foliage_file.h). A version-8 reader ignores the
// member and its next save would drop the foliage.
// 10: particle emitters (an entity's "particles" component: the emitter's
// JSON, particles/emitter.h). A version-9 reader refuses the unknown component.
// 11: the emitter's "space" and "draw_mesh" (a format-10 emitter takes their
// defaults: local space, sprites). A version-10 reader refuses the keys.
// 12: a mesh asset's baked impostor (its "impostor_hash", blob
// "mesh/<id>/impostor"). A version-11 reader ignores both and its next save
// drops the impostor, which the renderer then bakes again when drawing.
// 13: a colour grading LUT (settings "post.lut": file name and hash, blob
// "lut/<hash>" with the file's bytes; scene/color_lut.h). A version-12
// reader ignores both and its next save drops the LUT.
// 14: a camera's own post settings (the camera component's "post" object;
// scene/camera_post.h). A version-13 reader ignores it and its next save
// drops the overrides.
// 15: an OpenColorIO config (settings "post.ocio_config": file name, bundle
// hash and its files' paths and hashes, a blob "ocio/<hash>" per file;
// scene/ocio_config.h) and its view transform's settings. A version-14
// reader ignores the config and its next save drops it.
// 16: cluster hierarchies of huge scans (a mesh asset's "clusters_hash",
// blobs "clusters/<hash>" for its index and pages; scene/cluster_file.h)
// and the settings "clusters.gpu_budget_mb" / "clusters.cpu_budget_mb". A
// version-15 reader would show the asset's coarse mesh alone and its next
// save would drop the hierarchy.
constexpr int kSceneFormatVersion = 16;
constexpr int kFirstPhysicalLightsFormat = 6;
constexpr int kFirstPerLightShadowsFormat = 7;
constexpr int kFirstPhysicalBrdfFormat = 8;
constexpr int kFirstMaterialsFormat = 5;

Json sceneToJson(const SceneState& state);
// Canonical compact text of sceneToJson (stable member order and number format).
std::string canonicalJson(const SceneState& state);

// Reads a description. Assets come back without mesh data (the file loader
// fills it from blobs). On failure returns nullopt and sets `error`: a bad
// value's JSON path and what is wrong with it ("entities[3].transform.scale:
// expected [x, y, z], not a string"), or what does not fit together
// ("inconsistent hierarchy: ...").
std::optional<SceneState> sceneFromJson(const Json& json, std::string& error);

// The same from the description's text (what a .hscene holds). A text that
// is not JSON sets `notJson` and an error with its line and column; a bad
// value is named by its path and placed in the text
// ("entities[3].transform.scale (line 40, column 18): expected ...").
// Values outside their fields' ranges (fields.h fieldValueProblem) are not
// refused: each is clamped or repaired and named in `warnings` ("entity 2
// 'Camera': camera.fov_deg 0 must be from 1 to 170 °; now 1").
std::optional<SceneState> sceneFromJsonText(std::string_view text, std::string& error, bool& notJson,
                                            std::vector<std::string>* warnings = nullptr);

}  // namespace hs::scene
