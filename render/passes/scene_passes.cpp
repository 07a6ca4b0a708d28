#include "render/passes/scene_passes.h"

#include "render/fog_block.h"
#include "render/gpu_mesh_cache.h"
#include "render/passes/light_culling.h"
#include "render/passes/shadow_passes.h"

namespace hs::render {

gl::ProgramDesc meshProgramDesc(scene::ShadingMode mode, bool normalMap, bool parallax, bool debugNormal,
                                const std::vector<std::string>& extra) {
  gl::ProgramDesc d{"mesh.vert", "mesh.frag", "", extra};
  if (mode == scene::ShadingMode::Gouraud) d.defines.push_back("SHADING_GOURAUD");
  if (mode == scene::ShadingMode::Flat) d.defines.push_back("SHADING_FLAT");
  // Gouraud lights its vertices, some off screen where no cluster is: it
  // loops over every light of the frame.
  if (mode == scene::ShadingMode::Gouraud) std::erase(d.defines, std::string("LIGHTS_CLUSTERED"));
  if (mode != scene::ShadingMode::Gouraud) {
    if (normalMap || parallax) d.defines.push_back("HAS_TANGENTS");
    if (normalMap) d.defines.push_back("HAS_NORMAL_MAP");
    if (parallax) d.defines.push_back("HAS_PARALLAX");
    if (debugNormal) d.defines.push_back("DEBUG_SHADING_NORMAL");
  }
  return d;
}

SceneTargets addOpaquePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v) {
  const int samples = frame.settings.antialiasing == scene::Antialiasing::Msaa4 ? 4 : 1;
  return graph.addPass<SceneTargets>(
      v.named("opaque"),
      [&](PassBuilder& b, SceneTargets& t) {
        // Linear HDR colour: RGBA16F; 32-bit float depth for reversed Z.
        t.samples = samples;
        t.color = b.create(v.named("scene_color"), TextureDesc{v.view.width, v.view.height, GL_RGBA16F, samples});
        t.depth = b.create(v.named("scene_depth"),
                           TextureDesc{v.view.width, v.view.height, GL_DEPTH_COMPONENT32F, samples});
        readShadowMaps(b, frame);
        readLightGrid(b, frame);
        for (DrawSource* s : frame.sources)
          if (s->ownPass().empty() && s->has(DrawVariant::Surface, SurfaceSet::Opaque)) s->declare(b, DrawVariant::Surface);
      },
      [&frame, index = v.index, w = v.view.width, h = v.view.height](const SceneTargets& t, const PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({t.color}, t.depth));
        glViewport(0, 0, w, h);
        const float clearColor[4] = {0, 0, 0, 1};
        const float clearDepth = 0.0f;
        glDepthMask(GL_TRUE);
        glClearBufferfv(GL_COLOR, 0, clearColor);
        glClearBufferfv(GL_DEPTH, 0, &clearDepth);
        DrawCall call{DrawVariant::Surface, SurfaceSet::Opaque, index, surfaceDefines(frame)};
        bool bound = false;
        for (DrawSource* s : frame.sources) {
          if (!s->ownPass().empty() || !s->has(DrawVariant::Surface, SurfaceSet::Opaque)) continue;
          if (!bound) {
            frame.res.bindView(index);
            bindShadowMaps(frame, r);
            bindLightGrid(frame, r, index);
            bound = true;
          }
          s->draw(frame, call, r);
        }
      });
}

SceneTargets addSourcePasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, SceneTargets targets) {
  for (DrawSource* source : frame.sources) {
    if (source->ownPass().empty() || !source->has(DrawVariant::Surface, SurfaceSet::Opaque)) continue;
    struct Data {
      SceneTargets t;
    };
    targets = graph.addPass<Data>(
        v.named(source->ownPass()),
        [&](PassBuilder& b, Data& d) {
          d.t = targets;
          d.t.color = b.write(b.read(targets.color));
          d.t.depth = b.write(b.read(targets.depth));
          readShadowMaps(b, frame);
          readLightGrid(b, frame);
          source->declare(b, DrawVariant::Surface);
        },
        [&frame, source, index = v.index](const Data& d, const PassResources& r) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.t.color}, d.t.depth));
          frame.res.bindView(index);
          bindShadowMaps(frame, r);
          bindLightGrid(frame, r, index);
          source->draw(frame, DrawCall{DrawVariant::Surface, SurfaceSet::Opaque, index, surfaceDefines(frame)}, r);
        }).t;
  }
  return targets;
}

}  // namespace hs::render
