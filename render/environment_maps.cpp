#include "render/environment_maps.h"

#include <algorithm>

#include "render/frame_blocks.h"
#include "render/render_resources.h"
#include "scene/light_units.h"

namespace hs::render {

bool EnvironmentMaps::prepare(const EnvironmentKey& key) {
  if (!key_ || !(*key_ == key)) sky_ = PreethamSky::make(key.sunDir, key.turbidity, key.groundAlbedo);
  key_ = key;
  return !built_ || !(*built_ == key) || !allocated();
}

void setSkyUniforms(GlProgram& p, const PreethamSky& sky) {
  const glm::vec3 perez[5] = {glm::vec3(sky.perez[0]), glm::vec3(sky.perez[1]), glm::vec3(sky.perez[2]),
                              glm::vec3(sky.perez[3]), glm::vec3(sky.perez[4])};
  glProgramUniform3fv(p.id(), p.loc("uPerez"), 5, &perez[0].x);
  p.set("uZenith", glm::vec3(sky.zenith));
  p.set("uNormaliser", glm::vec3(sky.normaliser));
  p.set("uSkySun", glm::vec4(glm::vec3(sky.sunDir), float(sky.sunFade)));
  p.set("uSkyGround", glm::vec4(glm::vec3(sky.zenithRgb * sky.groundAlbedo), float(scene::sceneUnitsPerNit())));
}

void EnvironmentMaps::allocate(ResourcePool& pool) {
  if (allocated()) return;
  int levels = 1;
  while ((kRadianceSize >> levels) > 0) ++levels;
  radiance_ = pool.persistentTexture(TextureDesc{kRadianceSize, kRadianceSize, GL_RGBA16F, 1, 1, levels, true},
                                     "environment_radiance");
  specular_ = pool.persistentTexture(
      TextureDesc{kSpecularSize, kSpecularSize, GL_RGBA16F, 1, 1, kSpecularLevels, true}, "environment_specular");
  block_ = pool.persistentBuffer(BufferDesc{sizeof(EnvironmentBlock)}, "environment_block");
  EnvironmentBlock b;
  b.params.x = float(kSpecularLevels - 1);
  glNamedBufferSubData(block_, 0, sizeof b, &b);
}

void EnvironmentMaps::update(RenderResources& res) {
  allocate(res.pool);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  auto groups = [](int size) { return GLuint((size + 7) / 8); };
  // 1. The sky into level 0 of the radiance cube, then its mips.
  GlProgram& sky = res.program({"", "", "env_sky_cube.comp", {}});
  setSkyUniforms(sky, sky_);
  sky.set("uSize", kRadianceSize);
  sky.use();
  glBindImageTexture(0, radiance_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  glDispatchCompute(groups(kRadianceSize), groups(kRadianceSize), 6);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  glGenerateTextureMipmap(radiance_);
  // 2. Irradiance: 9 coefficients into the block.
  GlProgram& sh = res.program({"", "", "env_sh.comp", {}});
  sh.set("uSize", kRadianceSize);
  sh.use();
  glBindImageTexture(0, radiance_, 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, block_, 0, sizeof(glm::vec4) * 9);
  glDispatchCompute(1, 1, 1);
  // 3. Specular: each level its roughness.
  GlProgram& pre = res.program({"", "", "env_prefilter.comp", {}});
  pre.use();
  glBindTextureUnit(0, radiance_);
  pre.set("uSourceSize", float(kRadianceSize));
  for (int level = 0; level < kSpecularLevels; ++level) {
    const int size = std::max(kSpecularSize >> level, 1);
    pre.set("uSize", size);
    pre.set("uRoughness", float(level) / float(kSpecularLevels - 1));
    glBindImageTexture(0, specular_, level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(groups(size), groups(size), 6);
  }
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  glBindTextureUnit(0, 0);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  built_ = key_;
}

void EnvironmentMaps::bind() const {
  if (!allocated()) return;
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  glBindBufferRange(GL_UNIFORM_BUFFER, kEnvironmentBlockBinding, block_, 0, sizeof(EnvironmentBlock));
  glBindTextureUnit(kEnvironmentTextureUnit, specular_);
}

void EnvironmentMaps::release(ResourcePool& pool) {
  if (!allocated()) return;
  pool.releaseTexture(radiance_);
  pool.releaseTexture(specular_);
  pool.releaseBuffer(block_);
  glBindTextureUnit(kEnvironmentTextureUnit, 0);
  radiance_ = specular_ = block_ = 0;
  built_.reset();
}

}  // namespace hs::render
