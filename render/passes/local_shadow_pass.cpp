#include "render/passes/local_shadow_pass.h"

#include <algorithm>
#include <cstring>

#include "render/local_shadows.h"
#include "render/passes/shadow_casters.h"

namespace hs::render {
namespace {

struct LocalShadowData {
  TextureRef maps;
  BufferRef data, views;
  std::vector<LocalShadow> shadows;
  size_t firstView = 0;  // the layers' shadow views (FrameContext::shadowViews)
  size_t layers = 0;
  int layerSize = 0;
};

std::string lightName(const FrameContext& frame, const WorldLight& l) {
  const scene::Entity* e = frame.world.state ? frame.world.state->find(l.entity) : nullptr;
  return e ? e->name : "#" + std::to_string(l.entity);
}

}  // namespace

void planLocalShadows(FrameContext& frame, int maxTextureSize, ShadowBlock& block, ShadowPlan& plan) {
  const ShadowConfig& config = plan.config;
  ShadowResources& sh = frame.res.shadows;
  sh.local.clear();
  std::string problem;
  if (config.enabled) {
    const std::vector<RenderView> lodOnly{frame.lodView};
    const std::vector<RenderView>& views = frame.views ? *frame.views : lodOnly;
    for (size_t i = 0; i < frame.world.lights.size(); ++i) {
      const WorldLight& l = frame.world.lights[i];
      if (!l.castsShadows || !lightReachesViews(l, views)) continue;
      const int resolution = localShadowResolution(l, lightName(frame, l), config, maxTextureSize, &problem);
      sh.local.push_back(computeLocalShadow(l, i, resolution, config.pcfRadius, frame.visible.origin));
    }
  }
  if (!problem.empty() && problem != sh.localProblem) sh.newProblems.push_back(problem);
  sh.localProblem = problem;
  block.localParams = glm::vec4(0.0f);
  if (sh.local.empty()) return;

  int layerSize = 0, layers = 0;
  for (const LocalShadow& s : sh.local) {
    layerSize = std::max(layerSize, s.resolution);
    layers += int(s.faces.size());
  }
  block.localParams =
      glm::vec4(float(frame.world.lights.size()), 1.0f / float(layerSize), float(config.pcfRadius), 0.0f);
  std::vector<Frustum> volumes;
  for (const LocalShadow& s : sh.local)
    for (const LocalShadowFace& f : s.faces) volumes.push_back(localShadowVolume(s, f));
  plan.localLayers = volumes.size();
  plan.localLayerSize = layerSize;
  plan.localFirstView = addShadowViews(frame, volumes);
}

void addLocalShadowPass(FrameGraph& graph, FrameContext& frame, const ShadowPlan& plan) {
  ShadowResources& sh = frame.res.shadows;
  if (sh.local.empty()) return;
  const int layerSize = plan.localLayerSize, layers = int(plan.localLayers);
  const size_t viewStride = frame.res.viewStride;
  const LocalShadowData& data = graph.addPass<LocalShadowData>(
      "shadow_local",
      [&frame, &sh, &plan, layerSize, layers, viewStride](PassBuilder& b, LocalShadowData& d) {
        d.shadows = sh.local;
        d.layerSize = layerSize;
        d.layers = plan.localLayers;
        d.firstView = plan.localFirstView;
        declareSources(b, frame, DrawVariant::Depth);
        // Every layer at the largest light's size; a smaller light draws
        // into its corner (params.w says how much of the layer it uses).
        TextureDesc maps{layerSize, layerSize, GL_DEPTH_COMPONENT32F, 1, layers};
        maps.array = true;  // sampler2DArrayShadow, also for one spot
        d.maps = b.create("local_shadow_maps", maps);
        d.data = b.create("local_shadow_data",
                          BufferDesc{shadowBufferBytes(frame.world.lights.size() * sizeof(GpuLocalShadow))});
        d.views = b.create("local_shadow_views", BufferDesc{shadowBufferBytes(size_t(layers) * viewStride)});
      },
      [&frame, viewStride](const LocalShadowData& d, const PassResources& r) {
        const GLuint maps = r.texture(d.maps);
        glTextureParameteri(maps, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(maps, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
        // The lookup data, one entry per light of the light buffer.
        std::vector<GpuLocalShadow> entries(frame.world.lights.size());
        int layer = 0;
        for (const LocalShadow& s : d.shadows) {
          GpuLocalShadow& e = entries[s.light];
          for (size_t f = 0; f < s.faces.size(); ++f) e.faces[f] = glm::mat4(s.faces[f].frameToMap);
          e.params = glm::vec4(float(layer), float(s.faces.size()), float(s.texelPerMetre()),
                               float(s.resolution) / float(d.layerSize));
          layer += int(s.faces.size());
        }
        glNamedBufferSubData(r.buffer(d.data), 0, GLsizeiptr(entries.size() * sizeof(GpuLocalShadow)), entries.data());
        // One view block per layer: the face's clip matrix as the projection
        // (positions are already relative to the frame origin).
        const GLuint views = r.buffer(d.views);
        std::vector<uint8_t> blocks(d.layers * viewStride);
        std::vector<int> sizes;
        for (const LocalShadow& s : d.shadows)
          for (const LocalShadowFace& f : s.faces) {
            ViewBlock vb;
            vb.projection = glm::mat4(f.frameToClip);
            const float n = float(s.resolution);
            vb.viewport = glm::vec4(n, n, 1.0f / n, 1.0f / n);
            std::memcpy(blocks.data() + sizes.size() * viewStride, &vb, sizeof vb);
            sizes.push_back(s.resolution);
          }
        glNamedBufferSubData(views, 0, GLsizeiptr(blocks.size()), blocks.data());
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(kCasterSlopeOffset, kCasterConstantOffset);
        glDisable(GL_CULL_FACE);  // open scans cast from both sides
        for (size_t l = 0; l < d.layers; ++l) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.maps, int(l)));
          const float clearDepth = 0.0f;  // far: lit
          glClearBufferfv(GL_DEPTH, 0, &clearDepth);
          glViewport(0, 0, sizes[l], sizes[l]);
          glBindBufferRange(GL_UNIFORM_BUFFER, kViewBlockBinding, views, GLintptr(l * viewStride), sizeof(ViewBlock));
          DrawCall call;
          call.variant = DrawVariant::Depth;
          call.shadowView = d.firstView + l;
          drawSources(frame, call, r);
        }
        glDisable(GL_POLYGON_OFFSET_FILL);
      });
  frame.localShadowMaps = data.maps;
  frame.localShadowData = data.data;
}

void readLocalShadowMaps(PassBuilder& b, const FrameContext& frame) {
  if (frame.localShadowMaps.valid()) b.read(frame.localShadowMaps);
  if (frame.localShadowData.valid()) b.read(frame.localShadowData);
}

void bindLocalShadowMaps(const FrameContext& frame, const PassResources& r) {
  glBindTextureUnit(kLocalShadowTextureUnit, frame.localShadowMaps.valid() ? r.texture(frame.localShadowMaps) : 0);
  if (frame.localShadowData.valid())
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLocalShadowBinding, r.buffer(frame.localShadowData));
}

}  // namespace hs::render
