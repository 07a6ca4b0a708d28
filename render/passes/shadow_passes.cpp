#include "render/passes/shadow_passes.h"

#include <algorithm>
#include <cstring>

#include "render/gpu_mesh_cache.h"
#include "render/passes/local_shadow_pass.h"
#include "render/passes/shadow_casters.h"

namespace hs::render {
namespace {

// The cascade's box as planes (relative to the frame origin, the LOD eye)
// for the sources' caster culling; the sun's side stays open.
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
  BufferRef views;
  SunCascades cascades;
  size_t firstView = 0;  // the cascades' shadow views (FrameContext::shadowViews)
  int resolution = 0;
};

}  // namespace

ShadowPlan planShadows(FrameContext& frame) {
  ShadowResources& sh = frame.res.shadows;
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  std::string problem;
  ShadowPlan plan;
  plan.config = resolveShadowConfig(frame.settings, maxTexture, &problem);
  const ShadowConfig& config = plan.config;
  if (!problem.empty() && problem != sh.problem) sh.newProblems.push_back(problem);
  sh.problem = problem;

  ShadowBlock block;
  sh.sun = {};
  // settings.shadows is the master switch; then each light's own casts_shadows.
  if (config.enabled && frame.world.sun && frame.world.sun->castsShadows)
    sh.sun = computeSunCascades(frame.lodView, frame.world.sun->direction, config, frame.visible.origin);
  std::vector<Frustum> volumes;
  for (size_t i = 0; i < sh.sun.cascades.size(); ++i) {
    block.sunCascade[i] = glm::mat4(sh.sun.cascades[i].frameToMap);
    block.sunTexelMetres[int(i)] = float(sh.sun.cascades[i].texelMetres);
    volumes.push_back(cascadeVolume(sh.sun.cascades[i]));
  }
  block.sunParams = glm::vec4(float(sh.sun.cascades.size()), float(config.pcfRadius), 1.0f / float(config.resolution), 0.0f);
  if (!volumes.empty()) plan.sunFirstView = addShadowViews(frame, volumes);
  // Spot and point lights (local_shadow_pass.h): their layers, and their
  // entries of the block (none: localParams.x = 0).
  planLocalShadows(frame, maxTexture, block, plan);
  sh.block.upload(&block, sizeof block);
  glBindBufferRange(GL_UNIFORM_BUFFER, kShadowBlockBinding, sh.block.buffer.id(), 0, sizeof(ShadowBlock));
  return plan;
}

void addShadowPasses(FrameGraph& graph, FrameContext& frame, const ShadowPlan& plan) {
  addLocalShadowPass(graph, frame, plan);
  ShadowResources& sh = frame.res.shadows;
  if (sh.sun.cascades.empty()) return;
  const ShadowConfig& config = plan.config;
  const size_t viewStride = frame.res.viewStride;
  const SunShadowData& data = graph.addPass<SunShadowData>(
      "shadow_sun",
      [&](PassBuilder& b, SunShadowData& d) {
        d.cascades = sh.sun;
        d.resolution = config.resolution;
        d.firstView = plan.sunFirstView;
        declareSources(b, frame, DrawVariant::Depth);
        const int layers = int(d.cascades.cascades.size());
        TextureDesc map{config.resolution, config.resolution, GL_DEPTH_COMPONENT32F, 1, layers};
        map.array = true;  // sampler2DArrayShadow, also for one cascade
        d.map = b.create("sun_shadow_map", map);
        d.views = b.create("sun_shadow_views", BufferDesc{shadowBufferBytes(size_t(layers) * viewStride)});
      },
      [&frame, viewStride](const SunShadowData& d, const PassResources& r) {
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
          DrawCall call;
          call.variant = DrawVariant::Depth;
          call.shadowView = d.firstView + c;
          drawSources(frame, call, r);
        }
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDisable(GL_DEPTH_CLAMP);
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
