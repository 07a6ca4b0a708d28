#include "render/passes/dof_passes.h"

#include <algorithm>
#include <cmath>

#include "render/draw_source.h"
#include "render/gpu_mesh_cache.h"
#include "render/passes/dof_layered.h"
#include "render/passes/fullscreen_pass.h"
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
  FullscreenPass p;
  p.name = v.named("dof_tiles");
  p.fragment = "dof_tiles.frag";
  p.inputs = {{25, depth}};
  p.outputName = v.named("dof_tiles");
  p.output = TextureDesc{tw, th, GL_R16F};
  p.uniforms = [view = v.view, lens, nearest](GlProgram& prog) { setCocUniforms(prog, view, lens, nearest); };
  return addFullscreenPass(graph, frame, v, std::move(p));
}

TextureRef addGatherPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& scene,
                         TextureRef hdr, const DofLens& lens, double nearest) {
  const TextureRef depth = addDepthResolvePass(graph, frame, v, scene);
  const TextureRef tiles = addCocTilePass(graph, frame, v, depth, lens, nearest);
  FullscreenPass p;
  p.name = v.named("dof_gather");
  p.fragment = "dof_gather.frag";
  p.inputs = {{24, hdr}, {25, depth}, {26, tiles}};
  p.outputName = v.named("dof_color");
  p.output = TextureDesc{v.view.width, v.view.height, GL_RGBA16F};
  p.uniforms = [view = v.view, lens, nearest](GlProgram& prog) { setCocUniforms(prog, view, lens, nearest); };
  return addFullscreenPass(graph, frame, v, std::move(p));
}

}  // namespace

double nearestDrawnDepth(const RenderWorld& world, const VisibleSet& visible, const RenderView& view) {
  if (!world.terrains.empty()) return view.nearClip;  // a terrain can reach the camera
  double nearest = INFINITY;
  const glm::dvec3 fwd = view.forward();
  // The nearest corner of each drawn mesh's box (tighter than its sphere
  // for long thin things).
  forEachInViewCorner(visible, [&](const glm::dvec3& p) { nearest = std::min(nearest, glm::dot(p - view.eye, fwd)); });
  return std::max(nearest, view.nearClip);
}

double framesNearestDepth(const FrameContext& frame, const RenderView& view) {
  double nearest = nearestDrawnDepth(frame.world, frame.visible, view);
  for (const DrawSource* s : frame.sources) nearest = std::min(nearest, s->nearestDepth(view));
  return std::max(nearest, view.nearClip);
}

bool depthOfFieldNeeded(const scene::SceneSettings& settings, RenderResources& res, const RenderView& view,
                        double nearest, DofLens* out) {
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
  return maxCocPixels(lens, nearest) >= 0.5;
}

bool layeredDepthOfField(FrameContext& frame, const RenderView& view) {
  return frame.settings.depthOfField == scene::DepthOfField::Layered &&
         depthOfFieldNeeded(frame.settings, frame.res, view, framesNearestDepth(frame, view)) &&
         anySource(frame, DrawVariant::Surface, SurfaceSet::All);
}

TextureRef addDepthOfFieldPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                                 const SceneTargets& scene, TextureRef hdr) {
  const scene::DepthOfField mode = frame.settings.depthOfField;
  if (mode != scene::DepthOfField::Gather && mode != scene::DepthOfField::Layered) return hdr;
  DofLens lens;
  const double nearest = framesNearestDepth(frame, v.view);
  if (!depthOfFieldNeeded(frame.settings, frame.res, v.view, nearest, &lens)) return hdr;
  // Layered needs meshes to capture; without one in view the opaque image
  // is the only layer, which is what gather blurs.
  if (mode == scene::DepthOfField::Layered && anySource(frame, DrawVariant::Surface, SurfaceSet::All))
    return addLayeredDofPasses(graph, frame, v, hdr, addDepthResolvePass(graph, frame, v, scene), lens, nearest);
  return addGatherPass(graph, frame, v, scene, hdr, lens, nearest);
}

}  // namespace hs::render
