#include "render/passes/background_passes.h"

#include "render/environment_maps.h"

#include <algorithm>
#include <cmath>

#include "render/fog_block.h"
#include "render/passes/fullscreen_pass.h"

namespace hs::render {
namespace {

// A pass that draws over the scene colour, testing against its depth.
struct Over {
  SceneTargets t;
};
void declareOver(PassBuilder& b, Over& d, const SceneTargets& t) {
  d.t = t;
  d.t.color = b.write(b.read(t.color));
  d.t.depth = b.read(t.depth);
}

}  // namespace

SceneTargets addSkyPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& targets) {
  return graph.addPass<Over>(
      v.named("sky"), [&](PassBuilder& b, Over& d) { declareOver(b, d, targets); },
      [&frame, index = v.index, w = v.view.width, h = v.view.height](const Over& d, const PassResources& r) {
        // Where the depth is still the cleared far value: covered pixels cost nothing.
        FullscreenDraw draw;
        draw.fragment = "sky.frag";
        draw.defines = fogDefines(frame.settings);
        if (frame.settings.sky == scene::SkyModel::Analytic) {
          draw.defines.push_back("SKY_ANALYTIC");
          draw.uniforms = [&frame](GlProgram& p) { setSkyUniforms(p, frame.res.environment.sky()); };
        }
        draw.framebuffer = r.framebuffer({d.t.color}, d.t.depth);
        draw.width = w;
        draw.height = h;
        draw.view = int(index);
        draw.depthFunc = GL_EQUAL;
        drawFullscreen(frame.res, draw);
      }).t;
}

SceneTargets addGridPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& targets) {
  return graph.addPass<Over>(
      v.named("grid"), [&](PassBuilder& b, Over& d) { declareOver(b, d, targets); },
      [&frame, &view = v.view, index = v.index](const Over& d, const PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.t.color}, d.t.depth));
        frame.res.bindView(index);
        GlProgram& p = frame.res.program({"grid.vert", "grid.frag", "", {}});
        p.use();
        const double extent = std::min(view.farClip, 20000.0);
        p.set("uExtent", float(extent));
        p.set("uCameraZ", float(view.eye.z));
        p.set("uCameraXY", glm::vec2(view.eye));
        // Camera position modulo the 100 m period of the two line spacings, in double.
        p.set("uOffset", glm::vec2(glm::mod(glm::dvec2(view.eye), glm::dvec2(100.0))));
        p.set("uFadeDistance", float(std::max(200.0, std::abs(view.eye.z) * 30.0)));
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glDepthMask(GL_FALSE);  // a grid is not a surface: later passes see through it
        glBindVertexArray(frame.res.emptyVao.id());
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        glDisable(GL_BLEND);
        glDepthMask(GL_TRUE);
      }).t;
}

SceneTargets addOverlayPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& targets,
                    const Overlay& overlay) {
  return graph.addPass<Over>(
      v.named("overlay"), [&](PassBuilder& b, Over& d) { declareOver(b, d, targets); },
      [&frame, &view = v.view, index = v.index, &o = overlay](const Over& d, const PassResources& r) {
        struct Vertex {
          glm::vec3 p;
          glm::vec4 c;
        };
        std::vector<Vertex> verts;
        verts.reserve(o.lines.size() + o.triangles.size());
        for (const auto& x : o.lines) verts.push_back({glm::vec3(x.position - view.eye), x.color});
        for (const auto& x : o.triangles) verts.push_back({glm::vec3(x.position - view.eye), x.color});
        GrowingBuffer& vb = frame.res.overlayVertices;
        if (vb.reserve(verts.size() * sizeof(Vertex), 64 * 1024))
          glVertexArrayVertexBuffer(frame.res.overlayVao.id(), 0, vb.buffer.id(), 0, sizeof(Vertex));
        vb.upload(verts.data(), verts.size() * sizeof(Vertex));
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.t.color}, d.t.depth));
        frame.res.bindView(index);
        frame.res.program({"overlay.vert", "overlay.frag", "", {}}).use();
        glBindVertexArray(frame.res.overlayVao.id());
        if (o.onTop) glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glDepthMask(GL_FALSE);
        if (!o.triangles.empty()) glDrawArrays(GL_TRIANGLES, GLint(o.lines.size()), GLsizei(o.triangles.size()));
        if (!o.lines.empty()) glDrawArrays(GL_LINES, 0, GLsizei(o.lines.size()));
        glDisable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
      }).t;
}

}  // namespace hs::render
