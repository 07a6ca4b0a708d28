#include "render/passes/dof_passes.h"

#include <algorithm>
#include <cmath>

#include "render/gpu_mesh_cache.h"
#include "render/passes/dof_layered.h"
#include "render/passes/output_passes.h"

namespace hs::render {
namespace {

// The reversed-Z projection's 1/z = (depth + x) / y (render_view.cpp:
// depth = n f / ((f - n) z) - n / (f - n)).
glm::vec2 depthToInvZ(const RenderView& v) {
  const glm::dmat4 p = v.projection();
  return {float(p[2][2]), float(p[3][2])};
}

// The uniforms of shaders/dof_common.glsl.
// `nearest`: the nearest drawn depth, which bounds the blur radius.
void setCocUniforms(GlProgram& p, const RenderView& view, const DofLens& lens, double nearest) {
  p.set("uCocScale", float(lens.cocScale));
  p.set("uInvFocus", float(1.0 / lens.focusDistance));
  p.set("uDepthToInvZ", depthToInvZ(view));
  p.set("uMaxRadius", float(std::min(0.5 * maxCocPixels(lens, nearest), kDofMaxRadiusPixels)));
}

// The largest CoC radius per 16 x 16 tile (shaders/dof_tiles.frag).
TextureRef addCocTilePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef depth,
                          const DofLens& lens, double nearest) {
  const int tw = (v.view.width + 15) / 16, th = (v.view.height + 15) / 16;
  struct Data {
    TextureRef depth, tiles;
  };
  return graph
      .addPass<Data>(
          v.named("dof_tiles"),
          [&](PassBuilder& b, Data& d) {
            d.depth = b.read(depth);
            d.tiles = b.create(v.named("dof_tiles"), TextureDesc{tw, th, GL_R16F});
          },
          [&frame, view = v.view, lens, nearest, tw, th](const Data& d, const PassResources& r) {
            glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.tiles}));
            glViewport(0, 0, tw, th);
            glDisable(GL_DEPTH_TEST);
            GlProgram& p = frame.res.program({"fullscreen.vert", "dof_tiles.frag", "", {}});
            setCocUniforms(p, view, lens, nearest);
            p.use();
            glBindTextureUnit(25, r.texture(d.depth));
            glBindVertexArray(frame.res.emptyVao.id());
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindTextureUnit(25, 0);
            glEnable(GL_DEPTH_TEST);
          })
      .tiles;
}

TextureRef addGatherPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& scene,
                         TextureRef hdr, const DofLens& lens, double nearest) {
  const TextureRef depth = addDepthResolvePass(graph, frame, v, scene);
  const TextureRef tiles = addCocTilePass(graph, frame, v, depth, lens, nearest);
  struct Data {
    TextureRef hdr, depth, tiles, out;
  };
  return graph
      .addPass<Data>(
          v.named("dof_gather"),
          [&](PassBuilder& b, Data& d) {
            d.hdr = b.read(hdr);
            d.depth = b.read(depth);
            d.tiles = b.read(tiles);
            d.out = b.create(v.named("dof_color"), TextureDesc{v.view.width, v.view.height, GL_RGBA16F});
          },
          [&frame, view = v.view, lens, nearest](const Data& d, const PassResources& r) {
            glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.out}));
            glViewport(0, 0, view.width, view.height);
            glDisable(GL_DEPTH_TEST);
            GlProgram& p = frame.res.program({"fullscreen.vert", "dof_gather.frag", "", {}});
            setCocUniforms(p, view, lens, nearest);
            p.use();
            glBindTextureUnit(24, r.texture(d.hdr));
            glBindTextureUnit(25, r.texture(d.depth));
            glBindTextureUnit(26, r.texture(d.tiles));
            glBindVertexArray(frame.res.emptyVao.id());
            glDrawArrays(GL_TRIANGLES, 0, 3);
            for (unsigned u = 24; u <= 26; ++u) glBindTextureUnit(u, 0);
            glEnable(GL_DEPTH_TEST);
          })
      .out;
}

}  // namespace

double nearestDrawnDepth(const RenderWorld& world, const VisibleSet& visible, const RenderView& view) {
  if (!world.terrains.empty()) return view.nearClip;  // a terrain can reach the camera
  double nearest = INFINITY;
  const glm::dvec3 fwd = view.forward();
  // The nearest corner of each drawn mesh's box (tighter than its sphere
  // for long thin things).
  for (const DrawItem& it : visible.draws) {
    const glm::dmat4 m(visible.objects[it.object].model);
    const mesh::Bounds& b = it.mesh->bounds;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 local(c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z);
      const glm::dvec3 p = visible.origin + glm::dvec3(m * glm::dvec4(local, 1.0));
      nearest = std::min(nearest, glm::dot(p - view.eye, fwd));
    }
  }
  return std::max(nearest, view.nearClip);
}

bool depthOfFieldNeeded(const scene::SceneSettings& settings, RenderResources& res, const RenderWorld& world,
                        const VisibleSet& visible, const RenderView& view, DofLens* out) {
  if (settings.depthOfField == scene::DepthOfField::Off) return false;
  const DofLens lens = dofLensOf(view);
  if (!lens.problem.empty() && lens.problem != res.lastDofProblem) {
    res.dofProblems.push_back(lens.problem);  // once, until the problem changes
    res.lastDofProblem = lens.problem;
  }
  if (lens.problem.empty()) res.lastDofProblem.clear();
  if (!lens.valid) return false;
  if (out) *out = lens;
  // The blur's diameter reaches half a pixel somewhere in view.
  return maxCocPixels(lens, nearestDrawnDepth(world, visible, view)) >= 0.5;
}

TextureRef addDepthOfFieldPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                                 const SceneTargets& scene, TextureRef hdr) {
  const scene::DepthOfField mode = frame.settings.depthOfField;
  if (mode != scene::DepthOfField::Gather && mode != scene::DepthOfField::Layered) return hdr;
  DofLens lens;
  if (!depthOfFieldNeeded(frame.settings, frame.res, frame.world, frame.visible, v.view, &lens)) return hdr;
  const double nearest = nearestDrawnDepth(frame.world, frame.visible, v.view);
  // Layered needs meshes to capture; without one in view the opaque image
  // is the only layer, which is what gather blurs.
  if (mode == scene::DepthOfField::Layered && !frame.visible.draws.empty())
    return addLayeredDofPasses(graph, frame, v, hdr, addDepthResolvePass(graph, frame, v, scene), lens, nearest);
  return addGatherPass(graph, frame, v, scene, hdr, lens, nearest);
}

}  // namespace hs::render
