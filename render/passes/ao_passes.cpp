#include "render/passes/ao_passes.h"

#include <algorithm>

#include "render/passes/fullscreen_pass.h"
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
  FullscreenPass ao;
  ao.name = v.named("ao");
  ao.fragment = shader;
  ao.inputs = {{0, depth}};
  ao.outputName = v.named("ao");
  ao.output = TextureDesc{aw, ah, GL_R8};
  ao.bindView = true;
  ao.uniforms = [&frame, inv = glm::mat4(glm::inverse(v.view.projection()))](GlProgram& p) {
    p.set("uInvProjection", inv);
    p.set("uRadius", frame.settings.aoRadius);
    p.set("uStrength", frame.settings.aoStrength);
  };
  const TextureRef occlusion = addFullscreenPass(graph, frame, v, std::move(ao));
  FullscreenPass apply;
  apply.name = v.named("ao_apply");
  apply.fragment = "ssao_apply.frag";
  apply.inputs = {{0, hdr}, {1, occlusion}, {2, depth}};
  apply.outputName = v.named("hdr_ao");
  apply.output = TextureDesc{v.view.width, v.view.height, GL_RGBA16F};
  return addFullscreenPass(graph, frame, v, std::move(apply));
}

}  // namespace hs::render
