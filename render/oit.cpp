#include "render/oit.h"

#include "render/passes/fullscreen_pass.h"

#include <algorithm>
#include <functional>
#include <string>

#include "render/passes/light_culling.h"
#include "render/passes/shadow_passes.h"
#include "scene/light_units.h"

namespace hs::render {
namespace {

// Texture units of the transparency passes (reserved for oit: 20-23).
constexpr unsigned kOitTextureUnit = 20;
// Depth peeling stops here even if fragments are left (reported as peels).
constexpr int kMaxPeels = 4096;
// Image units of the K-buffer (shaders/oit_kbuffer.glsl).
constexpr unsigned kOitImage2 = 2, kOitImage3 = 3;
// The thesis's fixed-depth array: 16 layers per pixel (fewer when the cap says so).
constexpr int kFixedArrayLayers = 16;

size_t capBytes(const FrameContext& frame) {
  return size_t(std::max(frame.settings.oitMemoryMb, 1.0) * double(size_t(1) << 20));
}

// Depth tested against the opaque depth, never written (the drawing passes).
void opaqueDepthTest() {
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_GREATER);
}
void restoreDepth() {
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);
}

std::vector<std::string> drawDefines(const FrameContext& frame, std::initializer_list<std::string> mine) {
  std::vector<std::string> d = surfaceDefines(frame);
  d.push_back("HS_OIT");
  d.insert(d.end(), mine.begin(), mine.end());
  return d;
}

void clearUint(GLuint texture, GLuint value) {
  glClearTexImage(texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
}
void clearBuffer(GLuint buffer) {
  const GLuint zero = 0;
  glClearNamedBufferData(buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

ABufferCounters readCounters(GLuint buffer) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  ABufferCounters c;
  glGetNamedBufferSubData(buffer, 0, sizeof c, &c);
  return c;
}

// Fills the view's info from the counters a mode's passes left.
void takeCounters(OitViewInfo& info, const ABufferCounters& c, bool counts) {
  info.overflow = c.overflow;
  info.tailShare = double(c.tailShare) / 65536.0;
  info.tailPixels = c.tailPixels;
  if (counts && info.counts) {
    info.counts->fragments = c.fragments;
    info.counts->maxPerPixel = c.maxPerPixel;
    info.counts->coveredPixels = c.coveredPixels;
  }
  info.ran = true;
}

// The resolve: oit_resolve.frag's variant `defines` blended over `hdr`
// (colour + transmittance x opaque). `setup` binds and sets what the
// variant reads.
void runResolve(FrameContext& frame, const PassResources& r, TextureRef hdr, int w, int h,
                const std::vector<std::string>& defines, const std::function<void(GlProgram&)>& setup) {
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);  // the opaque colour's alpha (AO's) stays
  FullscreenDraw draw;
  draw.fragment = "oit_resolve.frag";
  draw.defines = defines;
  draw.framebuffer = r.framebuffer({hdr});
  draw.width = w;
  draw.height = h;
  draw.uniforms = setup;  // binds the variant's inputs too
  drawFullscreen(frame.res, draw);
  glDisable(GL_BLEND);
  restoreDepth();
  for (unsigned u = 0; u < 4; ++u) glBindTextureUnit(kOitTextureUnit + u, 0);
}

// The sorting modes' resolve: oit_resolve.comp's variant `defines` into
// `result` (colour, transmittance per pixel), then that blended over `hdr`
// by oit_resolve.frag's OIT_RESOLVE_REFERENCE (which reads such an image).
void runComputeResolve(FrameContext& frame, const PassResources& r, TextureRef hdr, TextureRef result, int w, int h,
                       const std::vector<std::string>& defines, const std::function<void(GlProgram&)>& setup) {
  GlProgram& p = frame.res.program({"", "", "oit_resolve.comp", defines});
  p.use();
  setup(p);
  p.set("uOitSize", glm::ivec2(w, h));
  glBindImageTexture(0, r.texture(result), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(GLuint(w + 7) / 8, GLuint(h + 7) / 8, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  glBindTextureUnit(kOitTextureUnit, r.texture(result));
  runResolve(frame, r, hdr, w, h, {"OIT_RESOLVE_REFERENCE"}, [](GlProgram&) {});
}

// The A-buffer, or with `fixedLayers` the thesis's fixed-depth array (the
// same capture with every pixel's range that long: render/abuffer.h).
TextureRef addABufferMode(FrameGraph& graph, FrameContext& frame, const ViewContext& v, SurfaceSet draws,
                          TextureRef depth, TextureRef hdr, const std::shared_ptr<OitViewInfo>& info,
                          int fixedLayers) {
  ABufferRequest req;
  req.name = "oit";
  req.draws = draws;
  req.depth = depth;
  req.depthTest = ABufferDepthTest::Opaque;
  req.memoryCapBytes = capBytes(frame);
  req.tail = true;
  req.fixedLayers = fixedLayers;
  const ABuffer a = addABufferCapture(graph, frame, v, req);
  info->counts = a.info;
  struct Data {
    ABuffer a;
    TextureRef hdr, result;
  };
  return graph
      .addPass<Data>(
          v.named("oit_resolve"),
          [&](PassBuilder& b, Data& d) {
            d.a = a;
            readABuffer(b, a);
            b.write(a.counters);
            d.result = b.create(v.named("oit_result"), TextureDesc{v.view.width, v.view.height, GL_RGBA32F});
            d.hdr = b.write(b.read(hdr));
          },
          [&frame, info, w = v.view.width, h = v.view.height](const Data& d, const PassResources& r) {
            bindABuffer(d.a, r);
            runComputeResolve(frame, r, d.hdr, d.result, w, h, {"OIT_RESOLVE_ABUFFER"}, [&](GlProgram& p) {
              p.set("uOitTail", d.a.info->overflow > 0);
            });
            takeCounters(*info, readCounters(r.buffer(d.a.counters)), false);
            info->bytes = d.a.info->bytes;  // the result image included (sizePool)
            const ABufferInfo& got = *d.a.info;
            info->layers =
                int(got.fixedLayers ? got.fixedLayers : got.perPixelCap == kABufferNoCap ? 0 : got.perPixelCap);
          })
      .hdr;
}

TextureRef addKBufferMode(FrameGraph& graph, FrameContext& frame, const ViewContext& v, SurfaceSet draws,
                          TextureRef depth, TextureRef hdr, const std::shared_ptr<OitViewInfo>& info) {
  const int w = v.view.width, h = v.view.height;
  const size_t pixels = size_t(w) * size_t(h);
  // Per pixel: K keys, K colours (8 bytes), a count, the tail. K shrinks
  // to what the cap holds.
  const size_t perPixel = capBytes(frame) / std::max<size_t>(pixels, 1);
  const int k = int(std::clamp<size_t>(perPixel > 52 ? (perPixel - 52) / 12 : 1, 1,
                                       size_t(std::clamp(frame.settings.kbufferK, 1, 32))));
  info->layers = k;
  info->counts = std::make_shared<ABufferInfo>();
  info->counts->width = w;
  info->counts->height = h;
  info->bytes = pixels * (12 * size_t(k) + 4 + kOitTailBytesPerPixel + 16) + sizeof(ABufferCounters);
  const std::string kDefine = "OIT_K " + std::to_string(k);
  struct Depth {
    TextureRef depth, slots, counts;
    BufferRef counters;
  };
  const Depth& dp = graph.addPass<Depth>(
      v.named("oit_kbuffer_depth"),
      [&](PassBuilder& b, Depth& d) {
        declareSources(b, frame, DrawVariant::Surface, draws);
        d.depth = b.read(depth);
        d.slots = b.create(v.named("oit_kbuffer_keys"), TextureDesc{w, h, GL_R32UI, 1, k, 1, false, true});
        d.counts = b.create(v.named("oit_counts"), TextureDesc{w, h, GL_R32UI});
        d.counters = b.create(v.named("oit_counters"), BufferDesc{sizeof(ABufferCounters)});
      },
      [&frame, draws, w, h, index = v.index, kDefine](const Depth& d, const PassResources& r) {
        clearUint(r.texture(d.slots), 0xFFFFFFFFu);
        clearUint(r.texture(d.counts), 0);
        resetABufferCounters(r.buffer(d.counters), w);
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.depth));
        glViewport(0, 0, w, h);
        opaqueDepthTest();
        frame.res.bindView(index);
        glBindImageTexture(kABufferCountsImage, r.texture(d.counts), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
        glBindImageTexture(kOitImage2, r.texture(d.slots), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCountersBinding, r.buffer(d.counters));
        drawSurfaces(frame, r, index, draws, {kDefine}, "oit_kbuffer_depth.frag");
        restoreDepth();
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
      });
  struct Color {
    TextureRef depth, slots, colors;
    BufferRef counters, tail;
  };
  const Color& cp = graph.addPass<Color>(
      v.named("oit_kbuffer_color"),
      [&](PassBuilder& b, Color& d) {
        declareSources(b, frame, DrawVariant::Surface, draws);
        d.depth = b.read(depth);
        d.slots = b.read(dp.slots);
        b.read(dp.counts);
        d.counters = b.write(b.read(dp.counters));
        d.colors = b.create(v.named("oit_kbuffer_colors"), TextureDesc{w, h, GL_RG32UI, 1, k, 1, false, true});
        d.tail = b.create(v.named("oit_tail"), BufferDesc{pixels * kOitTailBytesPerPixel});
        readShadowMaps(b, frame);
        readLightGrid(b, frame);
      },
      [&frame, draws, w, h, index = v.index, kDefine](const Color& d, const PassResources& r) {
        clearBuffer(r.buffer(d.tail));
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.depth));
        glViewport(0, 0, w, h);
        opaqueDepthTest();
        frame.res.bindView(index);
        bindShadowMaps(frame, r);
        bindLightGrid(frame, r, index);
        glBindImageTexture(kOitImage2, r.texture(d.slots), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
        glBindImageTexture(kOitImage3, r.texture(d.colors), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCountersBinding, r.buffer(d.counters));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOitTailBinding, r.buffer(d.tail));
        drawSurfaces(frame, r, index, draws, drawDefines(frame, {"HS_OIT_KBUFFER", "HS_OIT_TAIL", kDefine}));
        restoreDepth();
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
      });
  struct Data {
    Color c;
    TextureRef hdr, result;
  };
  return graph
      .addPass<Data>(
          v.named("oit_resolve"),
          [&](PassBuilder& b, Data& d) {
            d.c = cp;
            b.read(cp.slots);
            b.read(cp.colors);
            b.write(b.read(cp.counters));
            b.read(cp.tail);
            d.result = b.create(v.named("oit_result"), TextureDesc{w, h, GL_RGBA32F});
            d.hdr = b.write(b.read(hdr));
          },
          [&frame, info, w, h, kDefine](const Data& d, const PassResources& r) {
            glBindImageTexture(kOitImage2, r.texture(d.c.slots), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
            glBindImageTexture(kOitImage3, r.texture(d.c.colors), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32UI);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCountersBinding, r.buffer(d.c.counters));
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOitTailBinding, r.buffer(d.c.tail));
            runComputeResolve(frame, r, d.hdr, d.result, w, h, {"OIT_RESOLVE_KBUFFER", kDefine}, [&](GlProgram& p) {
              p.set("uOitTail", true);
            });
            takeCounters(*info, readCounters(r.buffer(d.c.counters)), true);
          })
      .hdr;
}

TextureRef addWeightedMode(FrameGraph& graph, FrameContext& frame, const ViewContext& v, SurfaceSet draws,
                           TextureRef depth, TextureRef hdr, const std::shared_ptr<OitViewInfo>& info) {
  const int w = v.view.width, h = v.view.height;
  info->bytes = size_t(w) * size_t(h) * (8 + 2);
  struct Draw {
    TextureRef depth, accum, revealage;
  };
  const Draw& dr = graph.addPass<Draw>(
      v.named("oit_weighted"),
      [&](PassBuilder& b, Draw& d) {
        declareSources(b, frame, DrawVariant::Surface, draws);
        d.depth = b.read(depth);
        d.accum = b.create(v.named("oit_accum"), TextureDesc{w, h, GL_RGBA16F});
        d.revealage = b.create(v.named("oit_revealage"), TextureDesc{w, h, GL_R16F});
        readShadowMaps(b, frame);
        readLightGrid(b, frame);
      },
      [&frame, draws, w, h, index = v.index](const Draw& d, const PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.accum, d.revealage}, d.depth));
        glViewport(0, 0, w, h);
        const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_COLOR, 1, one);
        opaqueDepthTest();
        frame.res.bindView(index);
        bindShadowMaps(frame, r);
        bindLightGrid(frame, r, index);
        glEnable(GL_BLEND);
        glBlendFunci(0, GL_ONE, GL_ONE);
        glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
        drawSurfaces(frame, r, index, draws, drawDefines(frame, {"HS_OIT_WEIGHTED"}));
        glDisable(GL_BLEND);
        restoreDepth();
      });
  struct Data {
    TextureRef accum, revealage, hdr;
  };
  return graph
      .addPass<Data>(
          v.named("oit_resolve"),
          [&](PassBuilder& b, Data& d) {
            d.accum = b.read(dr.accum);
            d.revealage = b.read(dr.revealage);
            d.hdr = b.write(b.read(hdr));
          },
          [&frame, info, w, h](const Data& d, const PassResources& r) {
            glBindTextureUnit(kOitTextureUnit, r.texture(d.accum));
            glBindTextureUnit(kOitTextureUnit + 1, r.texture(d.revealage));
            runResolve(frame, r, d.hdr, w, h, {"OIT_RESOLVE_WEIGHTED"}, [](GlProgram&) {});
            info->ran = true;
          })
      .hdr;
}

TextureRef addReferenceMode(FrameGraph& graph, FrameContext& frame, const ViewContext& v, SurfaceSet draws,
                            TextureRef depth, TextureRef hdr, const std::shared_ptr<OitViewInfo>& info) {
  const int w = v.view.width, h = v.view.height;
  info->bytes = size_t(w) * size_t(h) * (16 + 4 + 4 + 16);
  struct Peel {
    TextureRef depth, color, depthA, depthB, accum;
  };
  const Peel& pe = graph.addPass<Peel>(
      v.named("oit_reference"),
      [&](PassBuilder& b, Peel& d) {
        declareSources(b, frame, DrawVariant::Surface, draws);
        d.depth = b.read(depth);
        d.color = b.create(v.named("oit_peel_color"), TextureDesc{w, h, GL_RGBA32F});
        d.depthA = b.create(v.named("oit_peel_depth_a"), TextureDesc{w, h, GL_DEPTH_COMPONENT32F});
        d.depthB = b.create(v.named("oit_peel_depth_b"), TextureDesc{w, h, GL_DEPTH_COMPONENT32F});
        d.accum = b.create(v.named("oit_accum"), TextureDesc{w, h, GL_RGBA32F});
        readShadowMaps(b, frame);
        readLightGrid(b, frame);
      },
      [&frame, draws, w, h, index = v.index, info](const Peel& d, const PassResources& r) {
        // Front to back: each peel draws the nearest fragment behind the
        // last peel's depth, then blends it under the accumulation
        // (rgb += T a c, T *= 1 - a with T in alpha), until a peel finds
        // no fragment (an occlusion query says so).
        const float clearAccum[4] = {0, 0, 0, 1}, zero[4] = {0, 0, 0, 0}, nearest = 1.0f, farthest = 0.0f;
        glClearTexImage(r.texture(d.accum), 0, GL_RGBA, GL_FLOAT, clearAccum);
        glClearTexImage(r.texture(d.depthB), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &nearest);
        gl::Query query = gl::createQuery(GL_ANY_SAMPLES_PASSED);
        const std::vector<std::string> defines = drawDefines(frame, {"HS_OIT_PEEL"});
        glBindTextureUnit(kOitTextureUnit + 1, r.texture(d.depth));
        int peels = 0;
        for (; peels < kMaxPeels; ++peels) {
          const TextureRef into = peels % 2 == 0 ? d.depthA : d.depthB;
          const TextureRef last = peels % 2 == 0 ? d.depthB : d.depthA;
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.color}, into));
          glViewport(0, 0, w, h);
          glClearBufferfv(GL_COLOR, 0, zero);
          glDepthMask(GL_TRUE);
          glClearBufferfv(GL_DEPTH, 0, &farthest);
          glEnable(GL_DEPTH_TEST);
          glDepthFunc(GL_GREATER);
          frame.res.bindView(index);
          bindShadowMaps(frame, r);
          bindLightGrid(frame, r, index);
          glBindTextureUnit(kOitTextureUnit, r.texture(last));
          glBindTextureUnit(kOitTextureUnit + 1, r.texture(d.depth));
          glBeginQuery(GL_ANY_SAMPLES_PASSED, query.id());
          drawSurfaces(frame, r, index, draws, defines);
          glEndQuery(GL_ANY_SAMPLES_PASSED);
          GLuint any = 0;
          glGetQueryObjectuiv(query.id(), GL_QUERY_RESULT, &any);
          if (!any) break;
          glEnable(GL_BLEND);
          glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
          FullscreenDraw accumulate;
          accumulate.fragment = "oit_resolve.frag";
          accumulate.defines = {"OIT_PEEL_ACCUMULATE"};
          accumulate.framebuffer = r.framebuffer({d.accum});
          accumulate.width = w;
          accumulate.height = h;
          accumulate.textures = {{kOitTextureUnit, r.texture(d.color)}};
          drawFullscreen(frame.res, accumulate);
          glDisable(GL_BLEND);
        }
        restoreDepth();
        for (unsigned u = 0; u < 2; ++u) glBindTextureUnit(kOitTextureUnit + u, 0);
        info->peels = peels;
      });
  struct Data {
    TextureRef accum, hdr;
  };
  return graph
      .addPass<Data>(
          v.named("oit_resolve"),
          [&](PassBuilder& b, Data& d) {
            d.accum = b.read(pe.accum);
            d.hdr = b.write(b.read(hdr));
          },
          [&frame, info, w, h](const Data& d, const PassResources& r) {
            glBindTextureUnit(kOitTextureUnit, r.texture(d.accum));
            runResolve(frame, r, d.hdr, w, h, {"OIT_RESOLVE_REFERENCE"}, [](GlProgram&) {});
            info->ran = true;
          })
      .hdr;
}

}  // namespace

TextureRef addTransparencyPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, SurfaceSet draws,
                                 TextureRef depth, TextureRef hdr, bool counted, std::shared_ptr<OitViewInfo>& info) {
  info = std::make_shared<OitViewInfo>();
  if (!anySource(frame, DrawVariant::Surface, draws)) return hdr;
  // The translucent surfaces, once, however many passes draw them.
  frame.stats.trianglesDrawn += sourceTriangles(frame, draws);
  switch (frame.settings.transparency) {
    case scene::Transparency::ABuffer: return addABufferMode(graph, frame, v, draws, depth, hdr, info, 0);
    case scene::Transparency::ABufferFixed:
      return addABufferMode(graph, frame, v, draws, depth, hdr, info, kFixedArrayLayers);
    case scene::Transparency::KBuffer: return addKBufferMode(graph, frame, v, draws, depth, hdr, info);
    case scene::Transparency::Weighted:
    case scene::Transparency::Reference: break;
  }
  if (counted) {
    const FragmentCount c = addFragmentCountPass(graph, frame, v, "oit", draws, depth, ABufferDepthTest::Opaque);
    info->counts = c.info;
    // The count must run though nothing reads it: the resolve reads its counters.
    hdr = graph
              .addPass<TextureRef>(
                  v.named("oit_count_kept"),
                  [&](PassBuilder& b, TextureRef& t) {
                    b.read(c.counters);
                    b.read(c.counts);
                    t = b.write(b.read(hdr));
                  },
                  [](const TextureRef&, const PassResources&) {})
              ;
  }
  if (frame.settings.transparency == scene::Transparency::Weighted)
    return addWeightedMode(graph, frame, v, draws, depth, hdr, info);
  return addReferenceMode(graph, frame, v, draws, depth, hdr, info);
}

TextureRef addDepthComplexityPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, SurfaceSet draws,
                                  TextureRef depth, TextureRef hdr) {
  const FragmentCount c = addFragmentCountPass(graph, frame, v, "depth_complexity", draws, depth,
                                               ABufferDepthTest::Opaque);
  struct Data {
    TextureRef counts, hdr;
  };
  return graph
      .addPass<Data>(
          v.named("depth_complexity_view"),
          [&](PassBuilder& b, Data& d) {
            d.counts = b.read(c.counts);
            b.read(c.counters);
            d.hdr = b.write(b.read(hdr));
          },
          [&frame, w = v.view.width, h = v.view.height, info = c.info](const Data& d, const PassResources& r) {
            FullscreenDraw draw;
            draw.fragment = "oit_heatmap.frag";
            draw.framebuffer = r.framebuffer({d.hdr});
            draw.width = w;
            draw.height = h;
            draw.uniforms = [&](GlProgram& p) {
              glBindImageTexture(kABufferCountsImage, r.texture(d.counts), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
              p.set("uMaxCount", float(std::max<uint32_t>(info->maxPerPixel, 1)));
              p.set("uInvExposure", float(1.0 / scene::exposureMultiplier(frame.settings.exposureEv100)));
            };
            drawFullscreen(frame.res, draw);
            restoreDepth();
          })
      .hdr;
}

}  // namespace hs::render
