#pragma once
// The analytic sky's image-based light, with no bake (docs/rendering.md,
// "Sky and environment"): the sky rendered into a small radiance cube
// (with mips), projected onto 9 spherical-harmonic coefficients of
// irradiance (EnvironmentBlock, binding 6) and prefiltered into a specular
// cube (GGX, one roughness per mip level, unit 12). Remade only when what
// the sky depends on changes (the sun's direction, turbidity, ground
// albedo), at most once per frame and never per eye; with the gradient sky
// nothing here is allocated. The textures and the block are the resource
// pool's persistent entries ("environment_radiance", "environment_specular",
// "environment_block"), so the registry and --stats list them. Include only
// inside render/.
#include <optional>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "render/sky_model.h"

namespace hs::render {

class GlProgram;
class ResourcePool;
struct RenderResources;

// What the maps are a function of: equal keys give equal maps.
struct EnvironmentKey {
  glm::dvec3 sunDir{0.0};
  double turbidity = 0.0;
  double groundAlbedo = 0.0;
  bool operator==(const EnvironmentKey&) const = default;
};

class EnvironmentMaps {
 public:
  static constexpr int kRadianceSize = 32;    // level 0 of the radiance cube (mips down to 1)
  static constexpr int kSpecularSize = 32;    // level 0 of the specular cube
  static constexpr int kSpecularLevels = 5;   // roughness 0, 0.25, .., 1

  // The frame's sky; true if the maps must be remade for it (first use,
  // or its key differs from the one the maps hold).
  bool prepare(const EnvironmentKey& key);
  const PreethamSky& sky() const { return sky_; }
  // Makes the maps (GL compute; called from the environment pass).
  void update(RenderResources& res);
  // Binds the block and the specular cube where environment.glsl reads them.
  void bind() const;
  // Frees the maps (the gradient sky needs none).
  void release(ResourcePool& pool);
  bool allocated() const { return block_ != 0; }
  GLuint blockBuffer() const { return block_; }
  GLuint specularCube() const { return specular_; }

 private:
  void allocate(ResourcePool& pool);
  PreethamSky sky_;
  std::optional<EnvironmentKey> key_;    // of the frame being prepared
  std::optional<EnvironmentKey> built_;  // of what the maps hold
  GLuint radiance_ = 0, specular_ = 0, block_ = 0;
};

// Sets shaders/sky_model.glsl's uniforms on `p` for `sky`.
void setSkyUniforms(GlProgram& p, const PreethamSky& sky);

}  // namespace hs::render
