#include "render/draw_source.h"

#include "render/frame_context.h"

namespace hs::render {

void drawSources(FrameContext& frame, const DrawCall& call, const PassResources& resources) {
  for (DrawSource* s : frame.sources)
    if (s->has(call.variant, call.surfaces)) s->draw(frame, call, resources);
}

void drawSurfaces(FrameContext& frame, const PassResources& resources, size_t view, SurfaceSet surfaces,
                  std::vector<std::string> defines, std::string fragment) {
  DrawCall call;
  call.surfaces = surfaces;
  call.view = view;
  call.defines = std::move(defines);
  call.fragment = std::move(fragment);
  drawSources(frame, call, resources);
}

void declareSources(PassBuilder& builder, const FrameContext& frame, DrawVariant variant, SurfaceSet surfaces) {
  for (DrawSource* s : frame.sources)
    if (s->has(variant, surfaces)) s->declare(builder, variant);
}

bool anySource(const FrameContext& frame, DrawVariant variant, SurfaceSet surfaces) {
  for (DrawSource* s : frame.sources)
    if (s->has(variant, surfaces)) return true;
  return false;
}

size_t sourceTriangles(const FrameContext& frame, SurfaceSet surfaces) {
  size_t n = 0;
  for (DrawSource* s : frame.sources) n += s->triangles(surfaces);
  return n;
}

size_t addShadowViews(FrameContext& frame, const std::vector<Frustum>& volumes) {
  const size_t first = frame.shadowViews.size();
  frame.shadowViews.insert(frame.shadowViews.end(), volumes.begin(), volumes.end());
  for (DrawSource* s : frame.sources) s->cullShadowViews(frame, first, volumes.size());
  return first;
}

}  // namespace hs::render
