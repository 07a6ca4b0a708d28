#include "scene/demo_materials.h"

#include "mesh/primitives.h"
#include "mesh/procedural_textures.h"
#include "scene/demo_mesh.h"
#include "scene/texture_blob.h"
#include "scene/transform.h"

namespace hs::scene {
namespace {

TextureId addTexture(SceneState& s, mesh::Texture image, bool srgb) {
  TextureAsset t;
  t.id = s.maxTextureId() + 1;
  t.name = image.name;
  t.srgb = srgb;
  t.contentHash = textureContentHash(image);
  t.image = std::make_shared<const mesh::Texture>(std::move(image));
  s.textures.emplace(t.id, t);
  return t.id;
}

// A 3 x 3 m slab lying on the ground at `position` (facing up, where the
// sun reaches it and a standing viewer sees it at a glancing angle, which
// is where parallax shows), its material named by the asset; returns that
// material for the caller to fill.
Material& addSlab(SceneState& s, const std::string& name, const glm::dvec3& position, float uvRepeat, EntityId parent) {
  return addDemoMesh(s, name, mesh::gridPlane(3.0f, 1, uvRepeat), position, parent, "scene/demo_materials.cpp");
}

}  // namespace

void addDemoDetailSamples(SceneState& s) {
  const EntityId group = addDemoGroup(s, "Surface detail samples");

  // Bricks, 8 courses per 1.5 m texture repeat (19 cm courses): normal map only.
  const mesh::Texture bricks = mesh::brickHeightMap(256, 8, 4);
  const TextureId brickColour = addTexture(s, mesh::tintByHeight(bricks, {0.33f, 0.31f, 0.28f}, {0.45f, 0.16f, 0.09f}), true);
  const TextureId brickNormals = addTexture(s, mesh::normalMapFromHeight(bricks, 0.02f), false);
  Material& wall = addSlab(s, "Brick paving (normal map)", {-2.2, -12.5, 0.02}, 2.0f, group);
  wall.baseColor = glm::vec3(0.6f);  // the texture at full sun stays below white
  wall.baseColorTexture = brickColour;
  wall.normalMap = brickNormals;
  wall.roughness = 0.85f;
  wall.twoSided = false;

  // Stones in a rock slab, 6 cm deep crevices, drawn with parallax occlusion mapping.
  const mesh::Texture rock = mesh::stoneHeightMap(256, 6, 21);
  const TextureId rockColour = addTexture(s, mesh::tintByHeight(rock, {0.2f, 0.18f, 0.16f}, {0.62f, 0.56f, 0.47f}), true);
  const TextureId rockNormals = addTexture(s, mesh::normalMapFromHeight(rock, 0.03f), false);
  const TextureId rockHeight = addTexture(s, rock, false);
  Material& face = addSlab(s, "Rock slab (parallax)", {2.2, -12.5, 0.02}, 1.0f, group);
  face.baseColor = glm::vec3(0.6f);
  face.baseColorTexture = rockColour;
  face.normalMap = rockNormals;
  face.heightMap = rockHeight;
  face.heightScale = 0.06f;
  face.roughness = 0.9f;
  face.twoSided = false;
}

}  // namespace hs::scene
