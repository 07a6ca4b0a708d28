#include "render/passes/light_culling.h"

#include <algorithm>
#include <cstdint>

#include <glm/gtc/matrix_inverse.hpp>

#include "render/fog_block.h"

namespace hs::render {
namespace {

constexpr size_t kGridBytes = size_t(kLightClusters) * sizeof(uint32_t);
constexpr size_t kIndexBytes = size_t(kLightClusters) * size_t(kLightClusterCap) * sizeof(uint32_t);
// Each view's part of the buffers starts at a multiple of this (GL's
// largest possible GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT is 256).
static_assert(kGridBytes % 256 == 0 && kIndexBytes % 256 == 0);

struct CullStats {
  uint32_t clustersOverCap = 0;
  uint32_t maxLightsInCluster = 0;
};

}  // namespace

size_t pointLightsInView(const RenderWorld& world, const std::vector<RenderView>& views) {
  std::vector<Frustum> frusta;
  for (const RenderView& v : views) frusta.push_back(frustumOf(v));
  size_t n = 0;
  for (const WorldLight& l : world.lights)
    for (size_t i = 0; i < views.size(); ++i)
      if (frusta[i].intersectsSphere(l.position - views[i].eye, double(l.range))) {
        ++n;
        break;
      }
  return n;
}

void addLightCullingPass(FrameGraph& graph, FrameContext& frame, const std::vector<ViewContext>& views) {
  frame.stats.lightsInView = frame.lightsInView;
  if (frame.lightsInView == 0 || frame.options.bruteForceLights || views.empty()) return;
  struct Data {
    BufferRef grid, indices, stats;
  };
  const size_t viewCount = views.size();
  std::vector<glm::mat4> invProjections;
  for (const ViewContext& v : views) invProjections.push_back(glm::mat4(glm::inverse(v.view.projection())));
  const Data& data = graph.addPass<Data>(
      "light_culling",
      [&](PassBuilder& b, Data& d) {
        d.grid = b.create("light_grid", BufferDesc{kGridBytes * viewCount});
        d.indices = b.create("light_indices", BufferDesc{kIndexBytes * viewCount});
        d.stats = b.create("light_cull_stats", BufferDesc{sizeof(CullStats)});
      },
      [&frame, invProjections, lightCount = frame.world.lights.size()](const Data& d, const PassResources& r) {
        const GLuint statsBuffer = r.buffer(d.stats);
        const CullStats zero;
        glNamedBufferSubData(statsBuffer, 0, sizeof zero, &zero);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightCullStatsBinding, statsBuffer);
        GlProgram& p = frame.res.program({"", "", "light_culling.comp", {}});
        p.set("uLightCount", int(lightCount));
        p.use();
        for (size_t v = 0; v < invProjections.size(); ++v) {
          frame.res.bindView(v);
          p.set("uInvProjection", invProjections[v]);
          glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kLightGridBinding, r.buffer(d.grid), GLintptr(v * kGridBytes),
                            GLsizeiptr(kGridBytes));
          glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kLightIndexBinding, r.buffer(d.indices),
                            GLintptr(v * kIndexBytes), GLsizeiptr(kIndexBytes));
          glDispatchCompute(GLuint((kLightClusters + 63) / 64), 1, 1);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        // Only a frame with more lights than the cap can overflow a
        // cluster; only then is the count read back (it waits for the GPU).
        if (lightCount > size_t(kLightClusterCap)) {
          CullStats s;
          glGetNamedBufferSubData(statsBuffer, 0, sizeof s, &s);
          frame.stats.lightClustersOverCap = s.clustersOverCap;
          frame.stats.lightsMaxPerCluster = s.maxLightsInCluster;
          if (s.clustersOverCap > 0 && !frame.res.lightOverflowReported) {
            frame.res.lightProblems.push_back(
                "lights: " + std::to_string(s.clustersOverCap) + " light clusters are reached by more than " +
                std::to_string(kLightClusterCap) + " point/spot lights (up to " +
                std::to_string(s.maxLightsInCluster) + "); each is lit by the first " +
                std::to_string(kLightClusterCap) + " in outliner order, the others are left out there");
          }
          frame.res.lightOverflowReported = s.clustersOverCap > 0;
        } else {
          frame.res.lightOverflowReported = false;
        }
      });
  frame.lightGrid = data.grid;
  frame.lightIndices = data.indices;
}

std::vector<std::string> surfaceDefines(const FrameContext& frame) {
  std::vector<std::string> d = fogDefines(frame.settings);
  if (frame.lightGrid.valid()) d.push_back("LIGHTS_CLUSTERED");
  return d;
}

void readLightGrid(PassBuilder& b, const FrameContext& frame) {
  if (!frame.lightGrid.valid()) return;
  b.read(frame.lightGrid);
  b.read(frame.lightIndices);
}

void bindLightGrid(const FrameContext& frame, const PassResources& r, size_t view) {
  if (!frame.lightGrid.valid()) return;
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kLightGridBinding, r.buffer(frame.lightGrid), GLintptr(view * kGridBytes),
                    GLsizeiptr(kGridBytes));
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kLightIndexBinding, r.buffer(frame.lightIndices),
                    GLintptr(view * kIndexBytes), GLsizeiptr(kIndexBytes));
}

}  // namespace hs::render
