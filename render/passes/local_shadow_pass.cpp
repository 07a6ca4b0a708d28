#include "render/passes/local_shadow_pass.h"

#include <algorithm>
#include <cstring>

#include "render/local_shadows.h"
#include "render/passes/shadow_casters.h"

namespace hs::render {
namespace {

struct LocalShadowData {
  TextureRef maps;
  BufferRef data, views, casters;
  std::vector<LocalShadow> shadows;
  std::vector<ShadowCaster> meshes;
  std::vector<GpuObject> objects;
  std::vector<std::vector<uint32_t>> perLayer;  // caster indices per layer
  std::vector<Frustum> volumes;                 // per layer, frame-relative
  int layerSize = 0;
};

std::string lightName(const FrameContext& frame, const WorldLight& l) {
  const scene::Entity* e = frame.world.state ? frame.world.state->find(l.entity) : nullptr;
  return e ? e->name : "#" + std::to_string(l.entity);
}

}  // namespace

void addLocalShadowPass(FrameGraph& graph, FrameContext& frame, const ShadowConfig& config, int maxTextureSize,
                        ShadowBlock& block) {
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

  const size_t viewStride = frame.res.viewStride;
  const LocalShadowData& data = graph.addPass<LocalShadowData>(
      "shadow_local",
      [&frame, &sh, layerSize, layers, viewStride](PassBuilder& b, LocalShadowData& d) {
        d.shadows = sh.local;
        d.layerSize = layerSize;
        gatherShadowCasters(frame, d.meshes, d.objects);
        for (const LocalShadow& s : d.shadows)
          for (const LocalShadowFace& f : s.faces) {
            d.volumes.push_back(localShadowVolume(s, f));
            std::vector<uint32_t>& list = d.perLayer.emplace_back();
            for (size_t i = 0; i < d.meshes.size(); ++i)
              if (d.volumes.back().intersectsSphere(d.meshes[i].centre, d.meshes[i].radius))
                list.push_back(uint32_t(i));
          }
        // Every layer at the largest light's size; a smaller light draws
        // into its corner (params.w says how much of the layer it uses).
        TextureDesc maps{layerSize, layerSize, GL_DEPTH_COMPONENT32F, 1, layers};
        maps.array = true;  // sampler2DArrayShadow, also for one spot
        d.maps = b.create("local_shadow_maps", maps);
        d.data = b.create("local_shadow_data",
                          BufferDesc{shadowBufferBytes(frame.world.lights.size() * sizeof(GpuLocalShadow))});
        d.views = b.create("local_shadow_views", BufferDesc{shadowBufferBytes(size_t(layers) * viewStride)});
        if (!d.objects.empty())
          d.casters = b.create("local_shadow_casters", BufferDesc{shadowBufferBytes(d.objects.size() * sizeof(GpuObject))});
      },
      [&frame, viewStride](const LocalShadowData& d, const PassResources& r) {
        RenderResources& resources = frame.res;
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
        std::vector<uint8_t> blocks(d.perLayer.size() * viewStride);
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
        if (d.casters.valid()) {
          resources.ensureObjectIndices(d.objects.size());
          glNamedBufferSubData(r.buffer(d.casters), 0, GLsizeiptr(d.objects.size() * sizeof(GpuObject)), d.objects.data());
          glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBufferBinding, r.buffer(d.casters));
        }
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(kCasterSlopeOffset, kCasterConstantOffset);
        glDisable(GL_CULL_FACE);  // open scans cast from both sides
        for (size_t l = 0; l < d.perLayer.size(); ++l) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.maps, int(l)));
          const float clearDepth = 0.0f;  // far: lit
          glClearBufferfv(GL_DEPTH, 0, &clearDepth);
          glViewport(0, 0, sizes[l], sizes[l]);
          glBindBufferRange(GL_UNIFORM_BUFFER, kViewBlockBinding, views, GLintptr(l * viewStride), sizeof(ViewBlock));
          drawShadowCasters(resources, d.meshes, d.perLayer[l]);
          if (!frame.world.terrains.empty())
            resources.terrain.drawShadow(*frame.world.state, frame.world.terrains, frame.lodView, d.volumes[l]);
        }
        glDisable(GL_POLYGON_OFFSET_FILL);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBufferBinding, resources.objects.buffer.id());
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
