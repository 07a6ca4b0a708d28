#include "render/passes/shadow_passes.h"

#include <algorithm>
#include <cstring>

#include "render/gpu_mesh_cache.h"
#include "render/passes/local_shadow_pass.h"
#include "render/passes/shadow_casters.h"

namespace hs::render {
namespace {

// Does a sphere (frame-relative) touch the cascade's box, open towards the sun?
bool touchesCascade(const ShadowCascade& c, const glm::dvec3& centre, double radius) {
  const glm::dvec4 clip = c.frameToClip * glm::dvec4(centre, 1.0);
  const double rx = radius / c.radius;
  return std::abs(clip.x) <= 1.0 + rx && std::abs(clip.y) <= 1.0 + rx && clip.z >= -0.5 * rx;
}

// The cascade's box as planes for the terrain's node culling (terrain_lod.h:
// relative to the LOD eye, the frame origin); the sun's side stays open.
Frustum cascadeVolume(const ShadowCascade& c) {
  const glm::dmat4& m = c.frameToClip;
  auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  Frustum f;
  f.planes[0] = row(3) + row(0);
  f.planes[1] = row(3) - row(0);
  f.planes[2] = row(3) + row(1);
  f.planes[3] = row(3) - row(1);
  f.planes[4] = row(2);                  // depth >= 0
  f.planes[5] = glm::dvec4(0, 0, 0, 1);  // no limit towards the sun
  for (int i = 0; i < 5; ++i) f.planes[i] /= glm::length(glm::dvec3(f.planes[i]));
  return f;
}

struct SunShadowData {
  TextureRef map;
  BufferRef views, casters;
  SunCascades cascades;
  std::vector<ShadowCaster> meshes;
  std::vector<GpuObject> objects;
  std::vector<std::vector<uint32_t>> perCascade;  // caster indices
  int resolution = 0;
};

}  // namespace

void addShadowPasses(FrameGraph& graph, FrameContext& frame) {
  RenderResources& res = frame.res;
  ShadowResources& sh = res.shadows;
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  std::string problem;
  const ShadowConfig config = resolveShadowConfig(frame.settings, maxTexture, &problem);
  if (!problem.empty() && problem != sh.problem) sh.newProblems.push_back(problem);
  sh.problem = problem;

  ShadowBlock block;
  sh.sun = {};
  // settings.shadows is the master switch; then each light's own casts_shadows.
  if (config.enabled && frame.world.sun && frame.world.sun->castsShadows)
    sh.sun = computeSunCascades(frame.lodView, frame.world.sun->direction, config, frame.visible.origin);
  for (size_t i = 0; i < sh.sun.cascades.size(); ++i) {
    block.sunCascade[i] = glm::mat4(sh.sun.cascades[i].frameToMap);
    block.sunTexelMetres[int(i)] = float(sh.sun.cascades[i].texelMetres);
  }
  block.sunParams = glm::vec4(float(sh.sun.cascades.size()), float(config.pcfRadius), 1.0f / float(config.resolution), 0.0f);
  // Spot and point lights (local_shadow_pass.h): their pass, and their
  // entries of the block (none: localParams.x = 0).
  addLocalShadowPass(graph, frame, config, maxTexture, block);
  sh.block.upload(&block, sizeof block);
  glBindBufferRange(GL_UNIFORM_BUFFER, kShadowBlockBinding, sh.block.buffer.id(), 0, sizeof(ShadowBlock));
  if (sh.sun.cascades.empty()) return;

  const size_t viewStride = res.viewStride;
  const SunShadowData& data = graph.addPass<SunShadowData>(
      "shadow_sun",
      [&](PassBuilder& b, SunShadowData& d) {
        d.cascades = sh.sun;
        d.resolution = config.resolution;
        gatherShadowCasters(frame, d.meshes, d.objects);
        d.perCascade.resize(d.cascades.cascades.size());
        for (size_t c = 0; c < d.cascades.cascades.size(); ++c)
          for (size_t i = 0; i < d.meshes.size(); ++i)
            if (touchesCascade(d.cascades.cascades[c], d.meshes[i].centre, d.meshes[i].radius))
              d.perCascade[c].push_back(uint32_t(i));
        const int layers = int(d.cascades.cascades.size());
        TextureDesc map{config.resolution, config.resolution, GL_DEPTH_COMPONENT32F, 1, layers};
        map.array = true;  // sampler2DArrayShadow, also for one cascade
        d.map = b.create("sun_shadow_map", map);
        d.views = b.create("sun_shadow_views", BufferDesc{shadowBufferBytes(size_t(layers) * viewStride)});
        if (!d.objects.empty())
          d.casters = b.create("sun_shadow_casters", BufferDesc{shadowBufferBytes(d.objects.size() * sizeof(GpuObject))});
      },
      [&frame, viewStride](const SunShadowData& d, const PassResources& r) {
        RenderResources& resources = frame.res;
        const GLuint map = r.texture(d.map);
        glTextureParameteri(map, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(map, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
        // One view block per cascade: the light's clip matrix as the
        // projection, no rotation or eye offset (positions are already
        // relative to the frame origin).
        const GLuint views = r.buffer(d.views);
        std::vector<uint8_t> blocks(d.cascades.cascades.size() * viewStride);
        for (size_t c = 0; c < d.cascades.cascades.size(); ++c) {
          ViewBlock vb;
          vb.projection = glm::mat4(d.cascades.cascades[c].frameToClip);
          vb.viewport = glm::vec4(float(d.resolution), float(d.resolution), 1.0f / float(d.resolution),
                                  1.0f / float(d.resolution));
          std::memcpy(blocks.data() + c * viewStride, &vb, sizeof vb);
        }
        glNamedBufferSubData(views, 0, GLsizeiptr(blocks.size()), blocks.data());
        if (d.casters.valid()) {
          resources.ensureObjectIndices(d.objects.size());
          glNamedBufferSubData(r.buffer(d.casters), 0, GLsizeiptr(d.objects.size() * sizeof(GpuObject)), d.objects.data());
          glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBufferBinding, r.buffer(d.casters));
        }
        glEnable(GL_DEPTH_CLAMP);  // casters beyond the sun's side of the box still cast
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(kCasterSlopeOffset, kCasterConstantOffset);
        glDisable(GL_CULL_FACE);   // open scans cast from both sides
        glViewport(0, 0, d.resolution, d.resolution);
        for (size_t c = 0; c < d.cascades.cascades.size(); ++c) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.map, int(c)));
          const float clearDepth = 0.0f;
          glClearBufferfv(GL_DEPTH, 0, &clearDepth);
          glBindBufferRange(GL_UNIFORM_BUFFER, kViewBlockBinding, views, GLintptr(c * viewStride), sizeof(ViewBlock));
          drawShadowCasters(resources, d.meshes, d.perCascade[c]);
          if (!frame.world.terrains.empty())
            resources.terrain.drawShadow(*frame.world.state, frame.world.terrains, frame.lodView,
                                   cascadeVolume(d.cascades.cascades[c]));
        }
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDisable(GL_DEPTH_CLAMP);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBufferBinding, resources.objects.buffer.id());
      });
  frame.sunShadowMap = data.map;
}

void readShadowMaps(PassBuilder& b, const FrameContext& frame) {
  if (frame.sunShadowMap.valid()) b.read(frame.sunShadowMap);
  readLocalShadowMaps(b, frame);
}

void bindShadowMaps(const FrameContext& frame, const PassResources& r) {
  glBindTextureUnit(kShadowTextureUnit, frame.sunShadowMap.valid() ? r.texture(frame.sunShadowMap) : 0);
  bindLocalShadowMaps(frame, r);
}

}  // namespace hs::render
