#pragma once
// Materials and textures as document objects: a mesh asset's submeshes draw
// with materials of the document (MeshAsset::materialSlots), editable by
// name in the editor's Materials panel and with `hybridscape-cli material`,
// saved in the .hscene, undoable like every other edit. Their editable
// values are declared once in fields.cpp (materialFields()).
//
// Textures: a texture either lives in a mesh asset (the images a mesh file
// embeds or names: `asset` + `meshTexture`, its bytes stay in the mesh's
// blob and are not stored twice) or stands alone (normal and height maps
// made or loaded apart from a mesh: `image`, stored in a blob of its own,
// "texture/<id>").
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "mesh/mesh_data.h"
#include "scene/ids.h"

namespace hs::scene {

// The lighting model a material is shaded with (shaders/brdf.glsl); the
// order is the shader's MODEL_* constants (shaders/surface.glsl).
enum class LightingModel { Pbr = 0, Lambert = 1, Phong = 2, BlinnPhong = 3 };
// Where lighting is evaluated: once per triangle (flat), per vertex and
// interpolated (Gouraud), or per pixel (Phong shading).
enum class ShadingMode { Phong = 0, Gouraud = 1, Flat = 2 };

struct Material {
  MaterialId id = kNoMaterial;
  std::string name;             // "<asset> / <material>" for imported ones
  AssetId asset = kNoAsset;     // the mesh asset it came with (0: none)
  glm::vec3 baseColor{0.8f};    // linear RGB
  TextureId baseColorTexture = kNoTexture;  // sRGB, multiplies baseColor
  float opacity = 1.0f;         // 0..1
  TextureId normalMap = kNoTexture;  // tangent space, OpenGL convention (+Y up)
  float normalStrength = 1.0f;  // 0: flat, 1: as painted, up to 4
  TextureId heightMap = kNoTexture;  // parallax occlusion mapping; white is high
  float heightScale = 0.02f;    // metres of relief at white
  float roughness = 0.5f;       // perceptual, 0..1 (PBR)
  float metallic = 0.0f;        // 0..1 (PBR)
  float specular = 0.5f;        // PBR: F0 scale (0.5 = 4%); Phong/Blinn-Phong: highlight strength
  float shininess = 32.0f;      // Phong/Blinn-Phong exponent
  glm::vec3 emission{0.0f};     // linear RGB
  float emissionStrength = 1.0f;
  bool alphaCutout = false;     // discard where opacity x texture alpha < threshold
  float alphaThreshold = 0.5f;
  bool twoSided = true;         // scans are open surfaces seen from behind
  // Share of the diffuse light a thin two-sided surface (a leaf) lets
  // through to its other side (shaders/brdf.glsl): lit from behind it glows
  // with transmission x albedo, and its lit side reflects 1 - transmission
  // of its diffuse light. 0: opaque, as every surface before.
  float transmission = 0.0f;
  bool unlit = false;           // photogrammetry textures already hold their light
  LightingModel model = LightingModel::Pbr;
  ShadingMode shading = ShadingMode::Phong;

  bool operator==(const Material&) const = default;
};

struct TextureAsset {
  TextureId id = kNoTexture;
  std::string name;
  // In a mesh asset: the asset and the index into its MeshData::textures.
  AssetId asset = kNoAsset;
  int meshTexture = -1;
  // The image (for a mesh's texture, an alias into the mesh's data). Null
  // while a loaded description waits for its blobs.
  std::shared_ptr<const mesh::Texture> image;
  uint64_t contentHash = 0;  // standalone textures: hash of the blob
  // True for colour data (sRGB); false for normal and height maps (linear).
  bool srgb = true;

  bool standalone() const { return asset == kNoAsset; }
  // The image is not compared: a standalone texture's hash stands for it,
  // a mesh texture's asset and index do.
  bool operator==(const TextureAsset& o) const {
    return id == o.id && name == o.name && asset == o.asset && meshTexture == o.meshTexture &&
           contentHash == o.contentHash && srgb == o.srgb;
  }
};

}  // namespace hs::scene
