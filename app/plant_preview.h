#pragma once
// The scenes the editor's plant previews draw through a PreviewRenderer:
// the Generate Plant dialog's live preview and the Foliage panel's type
// thumbnails. A mesh asset with its materials and textures at full detail,
// lit by a sun over a neutral backdrop, framed whole by the camera (entity
// kPreviewCamera, preview_renderer.h) from the south-west and a little above.
#include <optional>
#include <string>

#include "app/preview_renderer.h"
#include "foliage/plants.h"
#include "scene/scene_state.h"

namespace hs::app {

// Mesh asset `asset` of `from` (with the materials on its slots and their
// textures); empty when `from` has no such asset with data.
std::optional<scene::SceneState> meshPreviewScene(const scene::SceneState& from, scene::AssetId asset);
// The plant `params` grows (level 0 only: no LOD chain), its materials
// given the plant look (scene::ops::applyPlantLook); empty with `error`
// when the generator refuses the parameters.
std::optional<scene::SceneState> plantPreviewScene(const foliage::PlantParams& params, std::string& error);

}  // namespace hs::app
