#include "render/passes/ao_passes.h"

#include <algorithm>

#include "render/passes/output_passes.h"

namespace hs::render {

TextureRef addAmbientOcclusionPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                                     const SceneTargets& scene, TextureRef hdr) {
  if (frame.settings.ao == scene::AmbientOcclusion::Off) return hdr;
  const char* shader = frame.settings.ao == scene::AmbientOcclusion::Gtao ? "gtao.frag" : "ssao.frag";
  const TextureRef depth = addDepthResolvePass(graph, frame, v, scene);
  const bool half = frame.settings.aoResolution == scene::AoResolution::Half;
  const int aw = half ? std::max(1, v.view.width / 2) : v.view.width;
  const int ah = half ? std::max(1, v.view.height / 2) : v.view.height;
  struct AoData {
    TextureRef depth, ao;
  };
  const AoData& ao = graph.addPass<AoData>(
      v.named("ao"),
      [&](PassBuilder& b, AoData& d) {
        d.depth = b.read(depth);
        d.ao = b.create(v.named("ao"), TextureDesc{aw, ah, GL_R8});
      },
      [&frame, shader, index = v.index, inv = glm::mat4(glm::inverse(v.view.projection())), aw, ah](const AoData& d,
                                                                                           const PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.ao}));
        glViewport(0, 0, aw, ah);
        glDisable(GL_DEPTH_TEST);
        frame.res.bindView(index);
        GlProgram& p = frame.res.program({"fullscreen.vert", shader, "", {}});
        p.set("uInvProjection", inv);
        p.set("uRadius", frame.settings.aoRadius);
        p.set("uStrength", frame.settings.aoStrength);
        p.use();
        glBindTextureUnit(0, r.texture(d.depth));
        glBindVertexArray(frame.res.emptyVao.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindTextureUnit(0, 0);
        glEnable(GL_DEPTH_TEST);
      });
  struct ApplyData {
    TextureRef scene, ao, depth, out;
  };
  return graph
      .addPass<ApplyData>(
          v.named("ao_apply"),
          [&](PassBuilder& b, ApplyData& d) {
            d.scene = b.read(hdr);
            d.ao = b.read(ao.ao);
            d.depth = b.read(depth);
            d.out = b.create(v.named("hdr_ao"), TextureDesc{v.view.width, v.view.height, GL_RGBA16F});
          },
          [&frame, w = v.view.width, h = v.view.height](const ApplyData& d, const PassResources& r) {
            glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.out}));
            glViewport(0, 0, w, h);
            glDisable(GL_DEPTH_TEST);
            frame.res.program({"fullscreen.vert", "ssao_apply.frag", "", {}}).use();
            glBindTextureUnit(0, r.texture(d.scene));
            glBindTextureUnit(1, r.texture(d.ao));
            glBindTextureUnit(2, r.texture(d.depth));
            glBindVertexArray(frame.res.emptyVao.id());
            glDrawArrays(GL_TRIANGLES, 0, 3);
            for (unsigned u = 0; u < 3; ++u) glBindTextureUnit(u, 0);
            glEnable(GL_DEPTH_TEST);
          })
      .out;
}

}  // namespace hs::render
