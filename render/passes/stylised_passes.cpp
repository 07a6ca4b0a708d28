#include "render/passes/stylised_passes.h"

#include <algorithm>

#include "core/blue_noise.h"
#include "core/srgb.h"
#include "render/passes/fullscreen_pass.h"
#include "render/passes/stipple_passes.h"
#include "render/stereo_views.h"

namespace hs::render {

namespace {

bool kuwaharaOn(const scene::PostSettings& post) { return post.kuwahara && post.kuwaharaRadiusPx > 0.0f; }

// The blue-noise map as thresholds (rank + 0.5) / count: computed once per
// process (a pure function), uploaded into a texture that lives across
// frames in the pool.
const std::vector<float>& blueNoiseThresholds() {
  static const std::vector<float> values = [] {
    const std::vector<uint32_t> ranks = blueNoiseRanks(kBlueNoiseSide);
    std::vector<float> v(ranks.size());
    for (size_t i = 0; i < ranks.size(); ++i) v[i] = (float(ranks[i]) + 0.5f) / float(ranks.size());
    return v;
  }();
  return values;
}

TextureRef addBlueNoise(FrameGraph& graph, const ViewContext& v) {
  struct Data {
    TextureRef map;
  };
  // Kept 600 frames without use before the pool frees it (32 KB).
  const TextureRef kept =
      graph.persistentTexture(v.named("blue_noise"), TextureDesc{kBlueNoiseSide, kBlueNoiseSide, GL_R32F}, 600);
  return graph
      .addPass<Data>(
          v.named("blue_noise"), [&](PassBuilder& b, Data& d) { d.map = b.write(b.read(kept)); },
          [](const Data& d, const PassResources& r) {
            if (!r.fresh(d.map)) return;  // filled once
            glTextureSubImage2D(r.texture(d.map), 0, 0, 0, kBlueNoiseSide, kBlueNoiseSide, GL_RED, GL_FLOAT,
                                blueNoiseThresholds().data());
          })
      .map;
}

// Floyd-Steinberg on `ldr` into a new texture (shaders/error_diffusion.comp:
// one workgroup, a wavefront of rows).
TextureRef addErrorDiffusion(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr,
                             TextureRef depth) {
  struct Data {
    TextureRef in, forced, out;
    BufferRef carry;
  };
  const int w = v.view.width, h = v.view.height;
  // A stereo pair (depth given, two views): the second eye takes the first
  // eye's levels where it sees the same surface.
  const int eye = stereoEye(frame, v, depth);
  const FrameContext::FirstEye& first = frame.firstEye;
  TextureRef forced;
  if (eye == 1 && first.dithered.valid() && first.depth.valid() && first.view) {
    FullscreenPass reproject;
    reproject.name = v.named("dither_reproject");
    reproject.fragment = "dither_reproject.frag";
    reproject.inputs = {{0, depth}, {1, first.depth}, {2, first.dithered}};
    reproject.outputName = v.named("dither_forced");
    reproject.output = TextureDesc{w, h, GL_RGBA8};
    reproject.uniforms = [m = windowToClip(v.view, *first.view)](GlProgram& p) { p.set("uThisToFirst", m); };
    forced = addFullscreenPass(graph, frame, v, std::move(reproject));
  }
  const TextureRef out =
      graph
          .addPass<Data>(
              v.named("error_diffusion"),
              [&](PassBuilder& b, Data& d) {
                d.in = b.read(ldr);
                if (forced.valid()) d.forced = b.read(forced);
                d.out = b.create(v.named("dithered"), TextureDesc{w, h, GL_RGBA8}, Usage::Storage);
                d.carry = b.create(v.named("dither_carry"), BufferDesc{size_t(w) * 2 * 16});
              },
              [&frame, levels = frame.settings.post.ditherLevels](const Data& d, const PassResources& r) {
                const bool taking = d.forced.valid();
                GlProgram& p = frame.res.program(
                    {"", "", "error_diffusion.comp", taking ? std::vector<std::string>{"HS_DITHER_FORCED"}
                                                            : std::vector<std::string>{}});
                p.set("uLevels", levels);
                p.use();
                glBindTextureUnit(0, r.texture(d.in));
                if (taking) glBindTextureUnit(1, r.texture(d.forced));
                glBindImageTexture(0, r.texture(d.out), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, r.buffer(d.carry));
                glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
                glDispatchCompute(1, 1, 1);
                glBindTextureUnit(0, 0);
                if (taking) glBindTextureUnit(1, 0);
              })
          .out;
  if (eye == 0) frame.firstEye.dithered = out;
  return out;
}

}  // namespace

bool stylisedEffectsOn(const scene::PostSettings& post) {
  return kuwaharaOn(post) || !stylisePassDefines(post).empty() || post.stipple ||
         post.dither == scene::DitherMode::ErrorDiffusion;
}

std::vector<std::string> stylisePassDefines(const scene::PostSettings& post) {
  std::vector<std::string> d;
  if (post.comic) d.push_back("HS_COMIC");  // draws the outlines itself
  else if (post.outlines) d.push_back("HS_OUTLINES");
  if (post.crt) d.push_back("HS_CRT");
  if (post.dither == scene::DitherMode::Bayer) d.push_back("HS_DITHER_BAYER");
  if (post.dither == scene::DitherMode::BlueNoise) d.push_back("HS_DITHER_BLUE");
  return d;
}

void addStylisedPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr,
                       TextureRef depth) {
  const scene::PostSettings& post = frame.settings.post;
  const int w = v.view.width, h = v.view.height;
  const float lines = float(h) / 1080.0f;
  const std::vector<std::string> defines = stylisePassDefines(post);
  const bool diffuse = post.dither == scene::DitherMode::ErrorDiffusion;
  // A full-screen stage of the chain: into the target when nothing follows,
  // else into a new texture the next stage reads.
  auto stage = [&](FullscreenPass pass, bool last, const char* output) {
    if (last) {
      pass.toTarget = true;
    } else {
      pass.outputName = v.named(output);
      pass.output = TextureDesc{w, h, GL_RGBA8};
    }
    return addFullscreenPass(graph, frame, v, std::move(pass));
  };
  if (kuwaharaOn(post)) {
    FullscreenPass tensor;
    tensor.name = v.named("kuwahara_tensor");
    tensor.fragment = "kuwahara_tensor.frag";
    tensor.inputs = {{0, ldr}};
    tensor.outputName = v.named("kuwahara_tensor");
    tensor.output = TextureDesc{w, h, GL_RGBA16F};
    FullscreenPass orient;
    orient.name = v.named("kuwahara_orient");
    orient.fragment = "kuwahara_orient.frag";
    orient.inputs = {{0, addFullscreenPass(graph, frame, v, std::move(tensor))}};
    orient.outputName = v.named("kuwahara_orientation");
    orient.output = TextureDesc{w, h, GL_RGBA16F};
    FullscreenPass filter;
    filter.name = v.named("kuwahara");
    filter.fragment = "kuwahara.frag";
    filter.inputs = {{0, ldr}, {1, addFullscreenPass(graph, frame, v, std::move(orient))}};
    filter.uniforms = [radius = std::max(1.0f, post.kuwaharaRadiusPx * lines),
                       q = std::clamp(post.kuwaharaSharpness, 1.0f, 16.0f)](GlProgram& p) {
      p.set("uRadius", radius);
      p.set("uQ", q);
    };
    ldr = stage(std::move(filter), defines.empty() && !post.stipple && !diffuse, "kuwahara_color");
  }
  if (!defines.empty()) {
    FullscreenPass pass;
    pass.name = v.named("stylise");
    pass.fragment = "stylise.frag";
    pass.defines = defines;
    pass.inputs = {{0, ldr}};
    if (post.dither == scene::DitherMode::BlueNoise) pass.inputs.push_back({1, addBlueNoise(graph, v)});
    const glm::vec3 outline(linearToSrgbFloat(post.outlineColor.r), linearToSrgbFloat(post.outlineColor.g),
                            linearToSrgbFloat(post.outlineColor.b));
    pass.uniforms = [post, lines, outline](GlProgram& p) {
      p.set("uLines", lines);
      p.set("uLevels", post.comicLevels);
      p.set("uDotCell", std::max(2.0f, post.comicDotPx * lines));
      p.set("uOutlineThreshold", std::max(1e-3f, post.outlineThreshold));
      p.set("uOutlineColor", outline);
      p.set("uCurvature", post.crtCurvature);
      p.set("uScanlines", post.crtScanlines);
      // At least 3 rows a line: finer lines than that alias into moiré (a
      // small viewport shows fewer lines than the film, not a pattern).
      p.set("uScanCount", std::clamp(post.crtLinesPer1080, 1.0f, std::max(1.0f, lines * 360.0f)));
      p.set("uMask", post.crtMask);
      p.set("uDitherLevels", post.ditherLevels);
    };
    ldr = stage(std::move(pass), !post.stipple && !diffuse, "stylised_color");
  }
  if (post.stipple) ldr = addStipplePasses(graph, frame, v, ldr, !diffuse, depth);
  if (diffuse) {
    // A compute pass cannot draw into the caller's framebuffer: a copy ends the chain.
    FullscreenPass copy;
    copy.name = v.named("dither_copy");
    copy.fragment = "copy.frag";
    copy.inputs = {{0, addErrorDiffusion(graph, frame, v, ldr, depth)}};
    stage(std::move(copy), true, "");
  }
}

}  // namespace hs::render
