#include "render/passes/output_passes.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "render/color_lut.h"
#include "render/passes/bloom_passes.h"
#include "render/passes/fullscreen_pass.h"
#include "render/passes/smaa_passes.h"
#include "render/passes/stylised_passes.h"
#include "scene/light_units.h"

namespace hs::render {

TextureRef addResolvePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& targets) {
  (void)frame;
  if (targets.samples <= 1) return targets.color;
  struct Data {
    TextureRef from, to;
  };
  return graph
      .addPass<Data>(
          v.named("resolve"),
          [&](PassBuilder& b, Data& d) {
            d.from = b.read(targets.color);
            d.to = b.create(v.named("hdr_color"), TextureDesc{v.view.width, v.view.height, GL_RGBA16F});
          },
          [w = v.view.width, h = v.view.height](const Data& d, const PassResources& r) {
            glBlitNamedFramebuffer(r.framebuffer({d.from}), r.framebuffer({d.to}), 0, 0, w, h, 0, 0, w, h,
                                   GL_COLOR_BUFFER_BIT, GL_NEAREST);
          })
      .to;
}

TextureRef addDepthResolvePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                               const SceneTargets& targets) {
  (void)frame;
  if (targets.samples <= 1) return targets.depth;
  struct Data {
    TextureRef from, to;
  };
  return graph
      .addPass<Data>(
          v.named("depth_resolve"),
          [&](PassBuilder& b, Data& d) {
            d.from = b.read(targets.depth);
            d.to = b.create(v.named("depth"), TextureDesc{v.view.width, v.view.height, GL_DEPTH_COMPONENT32F});
          },
          [w = v.view.width, h = v.view.height](const Data& d, const PassResources& r) {
            // Depth is not averaged: one sample per pixel, which is what a
            // parallax extreme should come from (an averaged edge depth
            // belongs to no surface).
            glBlitNamedFramebuffer(r.framebuffer({}, d.from), r.framebuffer({}, d.to), 0, 0, w, h, 0, 0, w, h,
                                   GL_DEPTH_BUFFER_BIT, GL_NEAREST);
          })
      .to;
}

std::vector<std::string> postDefines(const scene::SceneSettings& settings) {
  const scene::PostSettings& post = settings.post;
  std::vector<std::string> d;
  switch (settings.tonemap) {
    case scene::Tonemap::Aces: d.push_back("HS_TONEMAP_ACES"); break;
    case scene::Tonemap::AgX: d.push_back("HS_TONEMAP_AGX"); break;
    case scene::Tonemap::PbrNeutral: d.push_back("HS_TONEMAP_NEUTRAL"); break;
    case scene::Tonemap::None: break;
  }
  if (post.bloom && post.bloomIntensity > 0.0f) d.push_back("HS_BLOOM");
  if (post.chromaticAberration && post.chromaticAberrationPx > 0.0f) d.push_back("HS_CA");
  if (post.grade) d.push_back("HS_GRADE");
  if (post.vignette && post.vignetteIntensity > 0.0f) d.push_back("HS_VIGNETTE");
  if (post.grain && post.grainIntensity > 0.0f) d.push_back("HS_GRAIN");
  return d;
}

glm::vec3 whiteBalanceGains(float temperature, float tint) {
  // Warm raises red and lowers blue, tint trades green for magenta; the
  // gains are scaled so that white keeps its luminance (Rec.709 weights).
  const glm::vec3 g(1.0f + 0.3f * temperature, 1.0f - 0.3f * tint, 1.0f - 0.3f * temperature);
  return g / glm::dot(g, glm::vec3(0.2126f, 0.7152f, 0.0722f));
}

namespace {
// Whether the tone map pass's program builds with `defines` and
// OpenColorIO's `generated` text (built here, before the frame draws, so
// that a program OpenColorIO's text breaks leaves the transform out
// instead of stopping the renderer).
bool programBuilds(FrameContext& frame, const std::vector<std::string>& defines, const std::string& generated,
                   std::string& error) {
  return frame.res.shaders.get({"fullscreen.vert", "tonemap.frag", "", defines, generated}, error) != nullptr;
}

// Reports a colour transform left out of the frame once until the problem
// changes (Renderer::takeLutProblems).
void reportColourProblem(FrameContext& frame, std::string& last, const std::string& problem) {
  if (!problem.empty() && problem != last) frame.res.lutProblems.push_back(problem);
  last = problem;
}

// The GPU form of the config's view transform when it is on and can be
// drawn; `defines` then has HS_VIEW_TRANSFORM in the tone curve's place.
const GpuLut* viewTransformForFrame(FrameContext& frame, std::vector<std::string>& defines) {
  const scene::PostSettings& post = frame.settings.post;
  RenderResources& res = frame.res;
  if (!post.viewTransform) {
    res.lastViewProblem.clear();
    return nullptr;
  }
  if (post.ocioConfig.empty() || !post.ocioConfig.loaded()) {
    reportColourProblem(frame, res.lastViewProblem,
                        "post.view_transform: on, but the scene stores no OpenColorIO config (`hybridscape-cli ocio "
                        "import`); the frame uses its tone map");
    return nullptr;
  }
  std::string error;
  const GpuLut* view = res.viewTransforms.get(post.ocioConfig, post.display, post.view, error);
  const std::string key = std::to_string(post.ocioConfig.contentHash) + '\n' + post.display + '\n' + post.view;
  std::vector<std::string> with = defines;
  std::erase_if(with, [](const std::string& d) { return d.rfind("HS_TONEMAP_", 0) == 0; });
  with.push_back("HS_VIEW_TRANSFORM");
  if (view && res.viewProgramRefused == key) {
    view = nullptr;  // its program did not build: not tried again every frame
    error = res.viewProgramError;
  } else if (view && !programBuilds(frame, with, view->shaderText, error)) {
    view = nullptr;
    res.viewProgramRefused = key;
    res.viewProgramError = error;
  }
  reportColourProblem(frame, res.lastViewProblem,
                      view ? std::string()
                           : "post.view_transform ('" + post.ocioConfig.fileName +
                                 "'): the view transform is left out of the frame, which uses its tone map: " + error);
  if (view) defines = std::move(with);
  return view;
}

// The GPU form of the scene's LUT when it is on and can be drawn (after
// the view transform's text `before` in the program); a LUT that cannot is
// reported once and the frame is drawn without it.
const GpuLut* lutForFrame(FrameContext& frame, const std::vector<std::string>& defines, const std::string& before) {
  const scene::PostSettings& post = frame.settings.post;
  if (!post.lutEnabled || post.lut.empty() || !post.lut.bytes) return nullptr;
  std::string error;
  const GpuLut* lut = frame.res.luts.get(post.lut, error);
  std::vector<std::string> with = defines;
  with.push_back("HS_LUT");
  if (lut && frame.res.lutProgramRefused == post.lut.contentHash) {
    lut = nullptr;  // its program did not build: not tried again every frame
    error = frame.res.lutProgramError;
  } else if (lut && !programBuilds(frame, with, before + lut->shaderText, error)) {
    lut = nullptr;
    frame.res.lutProgramRefused = post.lut.contentHash;
    frame.res.lutProgramError = error;
  }
  reportColourProblem(frame, frame.res.lastLutProblem,
                      lut ? std::string()
                          : "post.lut '" + post.lut.fileName + "': the grading LUT is left out of the frame: " + error);
  return lut;
}

// An OpenColorIO transform's tables as the tone map pass takes them: 3D
// and 2D ones imported into the graph as inputs, 1D ones (shapers) bound
// by the uniforms beside them, on units from `unit` on.
struct LutTable {
  std::string sampler;
  unsigned unit;
  GLuint texture1d;  // nonzero: bound by the uniforms, not an input
};
void addTables(FrameGraph& graph, const ViewContext& v, const GpuLut& gpu, const std::string& prefix, unsigned& unit,
               std::vector<std::pair<unsigned, TextureRef>>& inputs, std::vector<LutTable>& tables) {
  for (size_t i = 0; i < gpu.tables.size(); ++i, ++unit) {
    const GpuLut::Table& t = gpu.tables[i];
    if (t.target == GL_TEXTURE_1D) {
      tables.push_back({t.sampler, unit, t.texture});
    } else {
      inputs.push_back({unit, graph.importTexture(v.named(prefix + std::to_string(i)), t.texture, t.desc)});
      tables.push_back({t.sampler, unit, 0});
    }
  }
}
}  // namespace

void addToneMapPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef hdr,
                      TextureRef depth) {
  const bool fxaa = frame.settings.antialiasing == scene::Antialiasing::Fxaa;
  const bool smaa = frame.settings.antialiasing == scene::Antialiasing::Smaa;
  const scene::PostSettings& post = frame.settings.post;
  FullscreenPass tm;
  tm.name = v.named("tonemap");
  tm.fragment = "tonemap.frag";
  tm.defines = postDefines(frame.settings);
  tm.inputs = {{0, hdr}};
  BloomChain bloom;
  if (post.bloom && post.bloomIntensity > 0.0f) {
    bloom = addBloomPasses(graph, frame, v, hdr);
    if (bloom.light.valid()) tm.inputs.push_back({1, bloom.light});
    else std::erase(tm.defines, std::string("HS_BLOOM"));
  }
  // OpenColorIO's transforms: the config's view transform (in the tone
  // curve's place) and the grading LUT. Their functions go into the
  // program, their 3D (and 2D) tables into the graph as imported textures
  // from unit 2 on; 1D tables (shapers) are bound beside them.
  std::vector<LutTable> lutTables;
  std::vector<std::pair<unsigned, TextureRef>> viewInputs;
  unsigned unit = 2;
  std::string viewText;
  if (const GpuLut* view = viewTransformForFrame(frame, tm.defines)) {
    viewText = view->shaderText;
    addTables(graph, v, *view, "view_table", unit, viewInputs, lutTables);
    tm.inputs.insert(tm.inputs.end(), viewInputs.begin(), viewInputs.end());
  }
  tm.generated = viewText;
  if (const GpuLut* lut = lutForFrame(frame, tm.defines, viewText)) {
    tm.defines.push_back("HS_LUT");
    tm.generated += lut->shaderText;
    addTables(graph, v, *lut, "lut_table", unit, tm.inputs, lutTables);
  }
  // The last pass of the chain draws into the caller's framebuffer; the
  // tone map does when neither FXAA nor a stylised effect follows.
  const bool stylised = stylisedEffectsOn(post);
  if (fxaa || smaa || stylised) {
    tm.outputName = v.named("ldr_color");
    tm.output = TextureDesc{v.view.width, v.view.height, GL_RGBA8};
  } else {
    tm.toTarget = true;
  }
  const float diagonal = std::hypot(float(v.view.width), float(v.view.height));
  const float lines = float(v.view.height) / 1080.0f;  // the pixel sizes are per 1080 lines
  tm.uniforms = [&frame, fxaa, post, diagonal, lines, w = v.view.width, h = v.view.height,
                 bloomWeight = bloom.weightSum, lutTables](GlProgram& p) {
    p.set("uExposure", float(scene::exposureMultiplier(frame.settings.exposureEv100)));
    p.set("uLumaInAlpha", fxaa);
    p.set("uBloomIntensity", post.bloomIntensity / bloomWeight);
    // The corner is half the diagonal from the centre: a fringe of px there.
    p.set("uCaScale", post.chromaticAberrationPx * lines / (0.5f * diagonal));
    p.set("uWhiteBalance", whiteBalanceGains(post.temperature, post.tint));
    p.set("uLift", post.lift);
    p.set("uGamma", post.gamma);
    p.set("uGain", post.gain);
    p.set("uSaturation", post.saturation);
    p.set("uVignette", post.vignetteIntensity);
    const glm::vec2 aspect(float(w) / float(h), 1.0f);
    p.set("uAspect", aspect / glm::length(aspect));
    p.set("uGrain", post.grainIntensity);
    p.set("uGrainCell", std::max(1.0f, post.grainSizePx * lines));
    p.set("uLutIntensity", post.lutIntensity);
    for (const LutTable& t : lutTables) {
      p.set(t.sampler.c_str(), int(t.unit));
      glBindSampler(t.unit, 0);  // the texture's own filtering, as OpenColorIO asks
      // (A 1D table stays bound on its unit after the draw: no other pass
      // samples a 1D texture.)
      if (t.texture1d) glBindTextureUnit(t.unit, t.texture1d);
    }
  };
  // The editor's before/after split: the same exposure and tone map with
  // no effect, drawn over the left part at the end. Only when some effect
  // is on (otherwise both halves are the same frame).
  // (The view transform is the tone curve there too.)
  const float split = frame.options.postSplit;
  std::vector<std::string> curveOnly = tm.defines;
  std::erase_if(curveOnly,
                [](const std::string& d) { return d.rfind("HS_TONEMAP_", 0) != 0 && d != "HS_VIEW_TRANSFORM"; });
  const bool splitShown = split > 0.0f && split < 1.0f &&
                          (tm.defines != curveOnly || fxaa || smaa || stylised || tm.generated != viewText);
  TextureRef before;
  if (splitShown) {
    FullscreenPass plain;
    plain.name = v.named("post_before");
    plain.fragment = "tonemap.frag";
    plain.defines = curveOnly;
    plain.generated = viewText;
    plain.inputs = {{0, hdr}};
    plain.inputs.insert(plain.inputs.end(), viewInputs.begin(), viewInputs.end());
    plain.outputName = v.named("post_before");
    plain.output = TextureDesc{v.view.width, v.view.height, GL_RGBA8};
    plain.uniforms = tm.uniforms;
    before = addFullscreenPass(graph, frame, v, std::move(plain));
  }
  TextureRef ldr = addFullscreenPass(graph, frame, v, std::move(tm));
  if (fxaa) {
    // Anti-aliasing before the stylised effects: it smooths the rendered
    // edges, not the dither's or the halftone's pattern.
    FullscreenPass aa;
    aa.name = v.named("fxaa");
    aa.fragment = "fxaa.frag";
    aa.inputs = {{0, ldr}};
    if (stylised) {
      aa.outputName = v.named("ldr_antialiased");
      aa.output = TextureDesc{v.view.width, v.view.height, GL_RGBA8};
    } else {
      aa.toTarget = true;
    }
    aa.uniforms = [w = v.view.width, h = v.view.height](GlProgram& p) {
      p.set("uTexel", glm::vec2(1.0f / float(w), 1.0f / float(h)));
    };
    ldr = addFullscreenPass(graph, frame, v, std::move(aa));
  }
  if (smaa) ldr = addSmaaPasses(graph, frame, v, ldr, !stylised);  // before the stylised effects too
  if (stylised) addStylisedPasses(graph, frame, v, ldr, depth);
  if (splitShown) {
    FullscreenPass over;
    over.name = v.named("post_split");
    over.fragment = "post_split.frag";
    over.inputs = {{0, before}};
    over.toTarget = true;
    over.uniforms = [x = split * float(v.view.width)](GlProgram& p) { p.set("uSplitX", x); };
    addFullscreenPass(graph, frame, v, std::move(over));
  }
}

}  // namespace hs::render
