#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <epoxy/gl.h>

#include "render/frame_context.h"
#include "render/frame_graph.h"
#include "render/gl/gl_debug.h"
#include "render/fog_block.h"
#include "render/gpu_lights.h"
#include "render/oit.h"
#include "render/passes/ao_passes.h"
#include "render/passes/background_passes.h"
#include "render/passes/dof_passes.h"
#include "render/dof_reference.h"
#include "render/passes/environment_pass.h"
#include "render/passes/light_culling.h"
#include "render/passes/output_passes.h"
#include "render/passes/scene_passes.h"
#include "render/passes/shadow_passes.h"
#include "render/render_resources.h"
#include "scene/light_units.h"

namespace hs::render {
namespace {

// Every program the renderer uses, built (and so checked) at initialisation.
const std::vector<gl::ProgramDesc>& allPrograms() {
  static const std::vector<gl::ProgramDesc> programs = {
      {"mesh.vert", "mesh.frag", "", {}},         {"mesh.vert", "pick.frag", "", {}},
      {"fullscreen.vert", "sky.frag", "", {}},    {"grid.vert", "grid.frag", "", {}},
      {"overlay.vert", "overlay.frag", "", {}},   {"fullscreen.vert", "tonemap.frag", "", {}},
      {"fullscreen.vert", "fxaa.frag", "", {}},
      // Sky and environment
      {"fullscreen.vert", "sky.frag", "", {"SKY_ANALYTIC"}}, {"", "", "env_sky_cube.comp", {}},
      {"", "", "env_sh.comp", {}},                           {"", "", "env_prefilter.comp", {}},
      {"fullscreen.vert", "ssao.frag", "", {}},              {"fullscreen.vert", "ssao_apply.frag", "", {}},
      // Clustered lights
      {"", "", "light_culling.comp", {}},
      // GTAO (settings.ao = gtao)
      {"fullscreen.vert", "gtao.frag", "", {}},
      // Depth of field (passes/dof_passes.h, dof_reference.h)
      {"fullscreen.vert", "dof_gather.frag", "", {}}, {"fullscreen.vert", "dof_accumulate.frag", "", {}},
      {"fullscreen.vert", "dof_tiles.frag", "", {}}, {"", "", "dof_layers.comp", {}},
      {"fullscreen.vert", "dof_composite.frag", "", {}},
  };
  return programs;
}

ViewBlock viewBlockOf(const RenderView& v, const glm::dvec3& origin) {
  ViewBlock b;
  const glm::dmat3 rot = v.viewRotation();
  b.projection = glm::mat4(v.projection());
  b.viewRotation = glm::mat4(glm::dmat4(rot));
  b.invViewRotation = glm::mat4(glm::dmat4(glm::transpose(rot)));
  b.eyeOffset = glm::vec4(glm::vec3(v.eye - origin), 0.0f);
  b.viewport = glm::vec4(float(v.width), float(v.height), 1.0f / float(v.width), 1.0f / float(v.height));
  const double t = std::tan(v.fovY * 0.5);
  b.tanHalfFov = glm::vec4(float(t * v.aspect()), float(t), float(v.projectionShift.x), float(v.projectionShift.y));
  return b;
}

// The frame's transparency figures, summed over its views.
OitStats oitStats(const scene::SceneSettings& settings, const std::vector<std::shared_ptr<OitViewInfo>>& views) {
  static const char* const kModes[] = {"abuffer", "abuffer_fixed", "kbuffer", "weighted", "reference"};
  OitStats s;
  s.mode = kModes[int(settings.transparency)];
  double tailShare = 0.0;
  for (const auto& v : views) {
    if (!v || !v->ran) continue;
    s.active = true;
    s.bytes += v->bytes;
    s.overflow += v->overflow;
    tailShare += v->tailShare;
    s.tailPixels += v->tailPixels;
    s.layers = v->layers;
    s.peels = std::max(s.peels, v->peels);
    if (v->counts) {
      s.counted = true;
      s.fragments += v->counts->fragments;
      s.maxPerPixel = std::max(s.maxPerPixel, v->counts->maxPerPixel);
      s.coveredPixels += v->counts->coveredPixels;
    }
  }
  if (s.coveredPixels) s.meanPerPixel = double(s.fragments) / double(s.coveredPixels);
  if (s.tailPixels) s.tailShare = tailShare / double(s.tailPixels);
  return s;
}

}  // namespace

struct Renderer::Impl {
  bool ready = false;
  RenderResources res;
  gl::DebugMessages debug;
  // Timer queries in a ring so reading one never stalls on the current frame.
  gl::Query timers[3];
  std::chrono::steady_clock::time_point timerBegun[3];  // when each was begun, by the wall clock
  int timerFrame = 0;
  double lastGpuMs = -1.0;
  // The last frame's graph, holding what it keeps (HDR colour, depth) until
  // the next frame.
  std::unique_ptr<FrameGraph> lastFrame;
  std::vector<TextureRef> keptHdr, keptDepth;
  std::vector<glm::ivec2> keptSizes;
  // Depth of field's reference (dof_reference.h): true while the lens
  // samples render (each a plain pinhole frame), and the float sums the
  // last reference frame keeps (its HDR images) until the next frame.
  bool lensSampling = false;
  std::vector<GLuint> lensAccum;
  std::vector<GLuint> lensDepth;  // the reference's pinhole depth per view (with keepDepth)

  // `lightsInView`: the point and spot lights that can light a pixel of a
  // view (none: the shaders loop over no light).
  void uploadFrameData(const RenderWorld& world, const VisibleSet& visible, const scene::SceneSettings& settings,
                       const scene::SceneTime& time, const std::vector<ViewTarget>& views, size_t lightsInView) {
    FrameBlock f;
    if (world.sun) {
      f.sunDir = glm::vec4(glm::vec3(-world.sun->direction), 1.0f);
      f.sunColor = glm::vec4(world.sun->color, 0.0f);
    }
    f.skyZenith = glm::vec4(settings.skyZenith, 0.0f);
    f.skyHorizon = glm::vec4(settings.skyHorizon, 0.0f);
    f.groundColor = glm::vec4(settings.groundColor, 0.0f);
    f.params = glm::vec4(settings.ambientIntensity, float(scene::exposureMultiplier(settings.exposureEv100)), float(lightsInView ? world.lights.size() : 0), 0.0f);
    f.environment = glm::vec4(settings.sky == scene::SkyModel::Analytic ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
    f.time = frameTimeOf(time.seconds, time.frame, time.fps);

    res.frameBlock.upload(&f, sizeof f);

    std::vector<GpuLight> lights;
    for (const WorldLight& l : world.lights) lights.push_back(gpuLight(l, visible.origin));
    res.lights.reserve(std::max<size_t>(lights.size(), 1) * sizeof(GpuLight));
    res.lights.upload(lights.data(), lights.size() * sizeof(GpuLight));
    res.objects.reserve(std::max<size_t>(visible.objects.size(), 1) * sizeof(GpuObject));
    res.objects.upload(visible.objects.data(), visible.objects.size() * sizeof(GpuObject));
    res.ensureObjectIndices(visible.objects.size());

    std::vector<uint8_t> blocks(views.size() * res.viewStride);
    for (size_t i = 0; i < views.size(); ++i) {
      const ViewBlock b = viewBlockOf(views[i].view, visible.origin);
      std::memcpy(blocks.data() + i * res.viewStride, &b, sizeof b);
    }
    res.viewBlocks.upload(blocks.data(), blocks.size());
    res.bindFrame();
    // Fog: a block only for frames that have fog (shaders/fog.glsl).
    if (settings.fogMode != scene::FogMode::None) {
      const FogBlock fog = fogBlock(settings, visible.origin.z);
      res.fogBlock.upload(&fog, sizeof fog);
      glBindBufferRange(GL_UNIFORM_BUFFER, kFogBlockBinding, res.fogBlock.buffer.id(), 0, sizeof fog);
    }
  }
};

Renderer::Renderer() : d_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

bool Renderer::initialized() const { return d_->ready; }

std::string currentGlDescription() {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(r ? r : "?") + " | " + (v ? v : "?");
}

bool Renderer::initialize(std::string& error) {
  if (d_->ready) return true;
  if (epoxy_gl_version() < 45) {
    error = "OpenGL 4.5 is required, this context has " + currentGlDescription();
    return false;
  }
  RenderResources& res = d_->res;
  d_->debug.install();
  if (!res.shaders.prebuild(allPrograms(), error)) return false;
  if (!res.terrain.initialize(res.shaders, error)) return false;
  GLint align = 256;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &align);
  res.viewStride = (sizeof(ViewBlock) + size_t(align) - 1) / size_t(align) * size_t(align);
  res.emptyVao = gl::createVertexArray();
  res.overlayVao = gl::createVertexArray();
  const GLuint ov = res.overlayVao.id();
  glVertexArrayAttribFormat(ov, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(ov, 0, 0);
  glEnableVertexArrayAttrib(ov, 0);
  glVertexArrayAttribFormat(ov, 1, 4, GL_FLOAT, GL_FALSE, sizeof(glm::vec3));
  glVertexArrayAttribBinding(ov, 1, 0);
  glEnableVertexArrayAttrib(ov, 1);
  for (auto& t : d_->timers) t = gl::createQuery(GL_TIME_ELAPSED);
  d_->ready = true;
  return true;
}

FrameStats Renderer::render(const scene::SceneState& state, const RenderView& view, unsigned targetFbo,
                            const RenderOptions& options) {
  return renderViews(state, {ViewTarget{view, targetFbo, {}}}, options);
}

FrameStats Renderer::renderViews(const scene::SceneState& state, const std::vector<ViewTarget>& targets,
                                 const RenderOptions& options) {
  FrameStats stats;
  if (!d_->ready || targets.empty()) return stats;
  for (const ViewTarget& t : targets)
    if (t.view.width <= 0 || t.view.height <= 0) return stats;
  // Depth of field, reference: N pinhole frames over the lens, averaged
  // (none when no view needs it: the frame renders as below).
  if (state.settings.depthOfField == scene::DepthOfField::Reference && !d_->lensSampling)
    if (std::optional<FrameStats> s = renderLensReference(state, targets, options)) return *s;
  const auto t0 = std::chrono::steady_clock::now();
  Impl& d = *d_;
  RenderResources& res = d.res;
  const scene::SceneSettings& settings = state.settings;

  GLuint timer = 0;
  if (options.measureGpuTime) {
    // Read the query from two frames ago if it is done; never wait for it.
    const int oldSlot = (d.timerFrame + 1) % 3;
    const GLuint old = d.timers[oldSlot].id();
    GLint available = 0;
    if (d.timerFrame >= 2) glGetQueryObjectiv(old, GL_QUERY_RESULT_AVAILABLE, &available);
    if (available) {
      GLuint64 ns = 0;
      glGetQueryObjectui64v(old, GL_QUERY_RESULT, &ns);
      // No GPU interval is longer than the wall time since it was begun.
      // llvmpipe answered a renderer's first frame with its end timestamp
      // alone (95 minutes: the machine's uptime), its beginning not stamped
      // (probably queued before any framebuffer was bound, so in no tile).
      // Such a value is dropped (test_frame_graph).
      const double ms = double(ns) * 1e-6;
      const double wallMs =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - d.timerBegun[oldSlot]).count();
      d.lastGpuMs = ms <= wallMs ? ms : -1.0;
    }
    timer = d.timers[d.timerFrame % 3].id();
    d.timerBegun[d.timerFrame % 3] = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, timer);
  }

  // Readbacks earlier frames queued (FrameGraph::readback) whose fences
  // have signalled: delivered now, never waited for.
  res.pool.pollReadbacks();
  // The last frame's kept targets go back to the pool now.
  d.lastFrame.reset();
  d.keptHdr.clear();
  d.keptDepth.clear();
  d.keptSizes.clear();
  if (!d.lensSampling) releaseLensTextures(d);

  // Once per frame, whatever the number of views.
  const RenderWorld world = RenderWorld::build(state);
  std::vector<RenderView> views;
  for (const ViewTarget& t : targets) views.push_back(t.view);
  const RenderView& lodView = options.lodView ? *options.lodView : views.front();
  const VisibleSet visible = buildVisibleSet(world, res.meshes, views, &lodView, settings.meshLodErrorPixels);
  stats.instancesCulled = visible.culled;
  stats.instancesAtCoarserLod = visible.coarser;
  const size_t lightsInView = pointLightsInView(world, views);
  d.uploadFrameData(world, visible, settings, state.time, targets, lightsInView);
  res.materials.build(state, visible, res.meshes, res.materialBlock);

  // Reversed-Z: depth 1 at the near plane, 0 at the far plane.
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);  // scans are open surfaces, seen from both sides
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);

  auto graph = std::make_unique<FrameGraph>(res.pool);
  FrameContext frame{res, world, visible, settings, options, lodView, stats};
  frame.views = &views;  // spot/point shadows: lights that reach no view cast nothing
  frame.lightsInView = lightsInView;
  std::vector<ViewContext> viewContexts;
  for (size_t i = 0; i < targets.size(); ++i)
    viewContexts.push_back({targets[i].view, i, targets[i].fbo, targets[i].name.empty() ? "" : "[" + targets[i].name + "]"});
  // Shadows: once per frame, before the views that read them.
  addShadowPasses(*graph, frame);
  // Eye-independent: once per frame, before the views.
  addEnvironmentPass(*graph, frame);
  // Clustered lights: once per frame, one grid per view.
  addLightCullingPass(*graph, frame, viewContexts);
  // Transparency (render/oit.h): the frame's translucent submeshes; none, no OIT pass or buffer.
  const DrawList translucent = translucentSubmeshes(frame);
  std::vector<std::shared_ptr<OitViewInfo>> oitViews(viewContexts.size());
  for (const ViewContext& v : viewContexts) {
    SceneTargets scene = addOpaquePass(*graph, frame, v);
    if (!world.terrains.empty()) scene = addTerrainPass(*graph, frame, v, scene);
    scene = addSkyPass(*graph, frame, v, scene);
    if (settings.showGrid && options.showGrid) scene = addGridPass(*graph, frame, v, scene);
    if (options.overlay && !options.overlay->empty())
      scene = addOverlayPass(*graph, frame, v, scene, *options.overlay);
    TextureRef hdr = addResolvePass(*graph, frame, v, scene);
    hdr = addAmbientOcclusionPasses(*graph, frame, v, scene, hdr);  // per eye; none with AO off
    // Transparency over the opaque colour, tested against a single-sample depth.
    TextureRef singleDepth;
    if (!translucent.empty() || options.keepDepth) singleDepth = addDepthResolvePass(*graph, frame, v, scene);
    hdr = addTransparencyPasses(*graph, frame, v, translucent, singleDepth, hdr, options.oitCounts, oitViews[v.index]);
    if (options.depthComplexity && !translucent.empty())
      hdr = addDepthComplexityPass(*graph, frame, v, translucent, singleDepth, hdr);
    hdr = addDepthOfFieldPasses(*graph, frame, v, scene, hdr);       // none with DoF off or no blur
    addToneMapPasses(*graph, frame, v, hdr);
    if (options.keepHdr) graph->keep(hdr);
    d.keptHdr.push_back(options.keepHdr ? hdr : TextureRef{});
    TextureRef depth;
    if (options.keepDepth) {
      depth = singleDepth;
      graph->keep(depth);
    }
    d.keptDepth.push_back(depth);
    d.keptSizes.emplace_back(v.view.width, v.view.height);
  }
  graph->execute(options.passTimings);
  for (const PassRecord& r : graph->records())
    if (r.ran) stats.passes.push_back({r.name, r.cpuMs, r.gpuMs, r.gpuBytes});
  stats.oit = oitStats(settings, oitViews);
  d.lastFrame = std::move(graph);
  res.pool.endFrame();

  if (timer) {
    glEndQuery(GL_TIME_ELAPSED);
    ++d.timerFrame;
  }
  // Leave the state a host (Qt) expects.
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindTextureUnit(0, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, targets.back().fbo);

  stats.gpuMs = d.lastGpuMs;
  fillMemoryStats(stats);
  stats.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return stats;
}

void Renderer::clearTarget(unsigned fbo, float r, float g, float b) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glClearColor(r, g, b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

Image Renderer::readDisplay(unsigned targetFbo, int width, int height) const {
  Image img;
  img.width = width;
  img.height = height;
  img.rgba8.resize(size_t(width) * size_t(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, targetFbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba8.data());
  flipRows(img.rgba8.data(), size_t(width) * 4, size_t(height));  // GL rows are bottom-up
  return img;
}

Image Renderer::readHdr(size_t view) const {
  Image img;
  if (!d_->lastFrame || view >= d_->keptHdr.size()) return img;
  const GLuint tex = d_->lastFrame->keptTexture(d_->keptHdr[view]);
  if (!tex) return img;
  img.width = d_->keptSizes[view].x;
  img.height = d_->keptSizes[view].y;
  img.rgbaF.resize(size_t(img.width) * size_t(img.height) * 4);
  glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(img.rgbaF.size() * sizeof(float)), img.rgbaF.data());
  flipRows(img.rgbaF.data(), size_t(img.width) * 4 * sizeof(float), size_t(img.height));  // GL rows are bottom-up
  return img;
}

void Renderer::readHdrInto(void* dst, size_t bytes, size_t view) const {
  if (!d_->lastFrame || view >= d_->keptHdr.size()) return;
  if (const GLuint tex = d_->lastFrame->keptTexture(d_->keptHdr[view]))
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(bytes), dst);
}

void Renderer::readDepth(void* dst, size_t view) {
  if (!d_->lastFrame || view >= d_->keptDepth.size()) return;
  const GLuint tex = d_->lastFrame->keptTexture(d_->keptDepth[view]);
  if (!tex) return;
  const glm::ivec2 size = d_->keptSizes[view];
  glGetTextureImage(tex, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(size_t(size.x) * size_t(size.y) * 4), dst);
}

std::vector<GpuAllocation> Renderer::resourceRegistry() const {
  std::vector<GpuAllocation> out;
  for (const PoolAllocation& a : d_->res.pool.registry())
    if (a.idleFrames == 0) out.push_back({a.name, a.texture ? "texture" : "buffer", a.bytes, !a.persistent, a.users});
  const RenderResources& res = d_->res;
  const size_t frameBuffers = res.frameBlock.capacity + res.viewBlocks.capacity + res.lights.capacity +
                              res.objects.capacity + res.objectIndices.capacity + res.overlayVertices.capacity +
                              res.materialBlock.capacity;
  out.push_back({"frame_data", "buffer", frameBuffers, false});
  out.back().bytes += res.shadows.block.capacity;  // ShadowBlock: one uniform block, with or without shadows
  if (const size_t m = res.meshes.gpuBytes()) out.push_back({"meshes", "meshes", m, false});
  if (const size_t t = res.terrain.gpuBytes()) out.push_back({"terrains", "terrains", t, false});
  if (const size_t t = res.materials.gpuBytes()) out.push_back({"material_textures", "textures", t, false});
  if (const size_t t = res.meshes.tangentBytes()) out.push_back({"mesh_tangents", "buffer", t, false});
  if (const size_t f = res.fogBlock.capacity) out.push_back({"fog_block", "buffer", f, false});
  return out;
}

size_t Renderer::idlePoolBytes() const { return d_->res.pool.idleBytes(); }

void Renderer::fillMemoryStats(FrameStats& stats) const {
  stats.gpuBytes = 0;
  for (const GpuAllocation& a : resourceRegistry()) stats.gpuBytes += a.bytes;
  stats.idleGpuBytes = idlePoolBytes();
  stats.gpuAllocationsMade = d_->res.pool.allocationsMade();
}

scene::EntityId Renderer::pick(const scene::SceneState& state, const RenderView& view, int x, int y) {
  return pickSurface(state, view, x, y).entity;
}

PickHit Renderer::pickSurface(const scene::SceneState& state, const RenderView& view, int x, int y) {
  if (!d_->ready || x < 0 || y < 0 || x >= view.width || y >= view.height) return {};
  Impl& d = *d_;
  RenderResources& res = d.res;
  // Projection narrowed to the one pixel: the 1x1 target sees just it.
  const double cx = 2.0 * (x + 0.5) / view.width - 1.0;
  const double cy = 1.0 - 2.0 * (y + 0.5) / view.height;
  glm::dmat4 n(1.0);
  n[0][0] = view.width;
  n[1][1] = view.height;
  n[3][0] = -cx * view.width;
  n[3][1] = -cy * view.height;

  const RenderWorld world = RenderWorld::build(state);
  const VisibleSet visible = buildVisibleSet(world, res.meshes, {view}, &view, state.settings.meshLodErrorPixels);
  d.uploadFrameData(world, visible, state.settings, state.time, {ViewTarget{view, 0, {}}}, 0);  // picking lights nothing
  ViewBlock vb = viewBlockOf(view, visible.origin);
  vb.projection = glm::mat4(n * view.projection());
  res.viewBlocks.upload(&vb, sizeof vb);
  res.bindView(0);

  const GLuint color = res.pool.acquireTexture(TextureDesc{1, 1, GL_R32UI}, "pick_id");
  const GLuint depth = res.pool.acquireTexture(TextureDesc{1, 1, GL_DEPTH_COMPONENT32F}, "pick_depth");
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glBindFramebuffer(GL_FRAMEBUFFER, res.pool.framebuffer({color}, depth));
  glViewport(0, 0, 1, 1);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);
  const GLuint zero[4] = {0, 0, 0, 0};
  const float clearDepth = 0.0f;
  glClearBufferuiv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_DEPTH, 0, &clearDepth);
  res.program({"mesh.vert", "pick.frag", "", {}}).use();
  for (const DrawItem& it : visible.draws) {
    glBindVertexArray(it.mesh->vao);
    for (const auto& sm : it.mesh->data->submeshes)
      glDrawElementsInstancedBaseInstance(GL_TRIANGLES, GLsizei(sm.indexCount), GL_UNSIGNED_INT,
                                          reinterpret_cast<const void*>(uintptr_t(sm.firstIndex) * sizeof(uint32_t)),
                                          1, it.object);
  }
  // Terrains after the meshes, ids following theirs (holes are not hit).
  const size_t meshIds = visible.objects.size();
  if (!world.terrains.empty()) res.terrain.drawPick(state, world.terrains, view, unsigned(meshIds + 1));
  GLuint id = 0;
  glReadPixels(0, 0, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, &id);
  // The depth the id pass left (the narrowing scales x and y only): the
  // view depth of the surface, for focus picking (depth of field).
  float depthValue = 0.0f;
  glReadPixels(0, 0, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depthValue);
  res.pool.releaseTexture(color);
  res.pool.releaseTexture(depth);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  glUseProgram(0);
  PickHit hit;
  if (id > meshIds && id <= meshIds + world.terrains.size()) hit.entity = world.terrains[id - meshIds - 1];
  else if (id > 0 && id <= meshIds) hit.entity = visible.entities[id - 1];
  if (id > 0 && depthValue > 0.0f) {
    const glm::dmat4 p = view.projection();  // reversed Z: 1/z = (depth + p22) / p32
    hit.viewDepth = p[3][2] / (double(depthValue) + p[2][2]);
  }
  return hit;
}

void Renderer::collectGarbage(const scene::SceneState& state) {
  d_->res.meshes.collect(state);
  d_->res.materials.collect(state);
}

TerrainUpload Renderer::syncTerrain(const scene::TerrainData& data, bool measureGpu) {
  gl::Query query;
  if (measureGpu) {
    query = gl::createQuery(GL_TIME_ELAPSED);
    glBeginQuery(GL_TIME_ELAPSED, query.id());
  }
  const TerrainUploadStats s = d_->res.terrain.sync(data);
  TerrainUpload out{s.bytes, s.regions, s.cpuMs, s.lodMs, s.full};
  if (measureGpu) {
    glEndQuery(GL_TIME_ELAPSED);
    const auto t0 = std::chrono::steady_clock::now();
    glFinish();
    out.finishMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &ns);
    out.gpuMs = double(ns) * 1e-6;
  }
  return out;
}

LodSelection Renderer::terrainLod(const scene::SceneState& state, scene::EntityId entity, const RenderView& view) {
  return d_->res.terrain.select(state, entity, view);
}

std::vector<std::string> Renderer::takeTerrainMaterialProblems() { return d_->res.terrain.takeMaterialProblems(); }

std::vector<std::string> Renderer::takeGlMessages() { return d_->debug.take(); }

std::vector<std::string> Renderer::takeMaterialProblems() { return d_->res.materials.takeProblems(); }

std::vector<std::string> Renderer::takeShadowProblems() {
  std::vector<std::string> out;
  out.swap(d_->res.shadows.newProblems);
  return out;
}

std::vector<BuiltProgram> Renderer::builtPrograms() const {
  std::vector<BuiltProgram> out;
  for (const gl::ProgramDesc& d : d_->res.shaders.builtPrograms()) out.push_back({d.name(), d.defines});
  return out;
}

std::vector<std::string> Renderer::takeDofProblems() {
  std::vector<std::string> out;
  out.swap(d_->res.dofProblems);
  return out;
}

// The reference's sums and pinhole depths go back to the pool (at its next
// frame or the next frame of another mode).
void Renderer::releaseLensTextures(Impl& d) {
  for (GLuint t : d.lensAccum) d.res.pool.releaseTexture(t);
  for (GLuint t : d.lensDepth) d.res.pool.releaseTexture(t);
  d.lensAccum.clear();
  d.lensDepth.clear();
}

// Depth of field, reference (dof_reference.h): the lens samples are whole
// frames through renderViews (with lensSampling set, so each is a pinhole
// frame), their HDR images summed in float, then one small graph tone maps
// the sums into the targets and keeps them for readHdr.
std::optional<FrameStats> Renderer::renderLensReference(const scene::SceneState& state,
                                                         const std::vector<ViewTarget>& targets,
                                                         const RenderOptions& options) {
  Impl& d = *d_;
  RenderResources& res = d.res;
  const RenderWorld world = RenderWorld::build(state);
  std::vector<RenderView> views;
  for (const ViewTarget& t : targets) views.push_back(t.view);
  const RenderView& lodView = options.lodView ? *options.lodView : views.front();
  const VisibleSet visible = buildVisibleSet(world, res.meshes, views, &lodView, state.settings.meshLodErrorPixels);
  std::vector<DofLens> lenses(targets.size());
  bool any = false;
  for (size_t i = 0; i < targets.size(); ++i)
    if (!depthOfFieldNeeded(state.settings, res, world, visible, views[i], &lenses[i])) lenses[i].valid = false;
    else any = true;
  if (!any) return std::nullopt;

  const int n = std::clamp(state.settings.dofReferenceSamples, 64, 1024);
  const std::vector<glm::dvec2> disc = lensDiscSamples(n);
  releaseLensTextures(d);
  for (const RenderView& v : views) d.lensAccum.push_back(acquireLensAccumulation(res, v.width, v.height));
  RenderOptions o = options;
  o.keepHdr = true;
  o.keepDepth = false;
  o.measureGpuTime = false;
  o.passTimings = false;
  o.lodView = &lodView;  // every sample draws the same levels of detail
  FrameStats stats;
  d.lensSampling = true;
  if (options.keepDepth) {
    // The depth a caller reads (the export's comfort check, the focus
    // pick) is the pinhole frame's, as with the other modes: one more
    // frame at the lens centre, its depth kept past the samples.
    RenderOptions pinhole = o;
    pinhole.keepHdr = false;
    pinhole.keepDepth = true;
    renderViews(state, targets, pinhole);
    for (size_t i = 0; i < views.size(); ++i) {
      const GLuint tex = res.pool.acquireTexture(TextureDesc{views[i].width, views[i].height, GL_DEPTH_COMPONENT32F},
                                                 "dof_reference_depth");
      glCopyImageSubData(d.lastFrame->keptTexture(d.keptDepth[i]), GL_TEXTURE_2D, 0, 0, 0, 0, tex, GL_TEXTURE_2D, 0, 0,
                         0, 0, views[i].width, views[i].height, 1);
      d.lensDepth.push_back(tex);
    }
  }
  for (const glm::dvec2& p : disc) {
    std::vector<ViewTarget> sample = targets;
    for (size_t i = 0; i < sample.size(); ++i)
      if (lenses[i].valid) sample[i].view = lensSampleView(views[i], lenses[i], p);
    stats = renderViews(state, sample, o);
    for (size_t i = 0; i < views.size(); ++i)
      accumulateLensSample(res, d.lastFrame->keptTexture(d.keptHdr[i]), d.lensAccum[i], views[i].width,
                           views[i].height, 1.0f / float(n));
  }
  d.lensSampling = false;

  // Tone map the sums into the targets.
  d.lastFrame.reset();
  d.keptHdr.clear();
  d.keptDepth.clear();
  d.keptSizes.clear();
  auto graph = std::make_unique<FrameGraph>(res.pool);
  FrameStats finalStats;
  FrameContext frame{res, world, visible, state.settings, options, lodView, finalStats};
  for (size_t i = 0; i < targets.size(); ++i) {
    const ViewContext v{targets[i].view, i, targets[i].fbo, targets[i].name.empty() ? "" : "[" + targets[i].name + "]"};
    const TextureRef sum = graph->importTexture(v.named("dof_reference"), d.lensAccum[i],
                                                TextureDesc{views[i].width, views[i].height, GL_RGBA32F});
    addToneMapPasses(*graph, frame, v, sum);
    if (options.keepHdr) graph->keep(sum);
    d.keptHdr.push_back(options.keepHdr ? sum : TextureRef{});
    TextureRef depth;
    if (i < d.lensDepth.size()) {
      depth = graph->importTexture(v.named("dof_reference_depth"), d.lensDepth[i],
                                   TextureDesc{views[i].width, views[i].height, GL_DEPTH_COMPONENT32F});
      graph->keep(depth);
    }
    d.keptDepth.push_back(depth);
    d.keptSizes.emplace_back(views[i].width, views[i].height);
  }
  graph->execute(false);
  for (const PassRecord& r : graph->records())
    if (r.ran) stats.passes.push_back({r.name, r.cpuMs, r.gpuMs, r.gpuBytes});
  d.lastFrame = std::move(graph);
  res.pool.endFrame();
  glBindFramebuffer(GL_FRAMEBUFFER, targets.back().fbo);
  fillMemoryStats(stats);
  return stats;
}

std::vector<std::string> Renderer::takeLightProblems() {
  std::vector<std::string> out;
  out.swap(d_->res.lightProblems);
  return out;
}

std::vector<SunCascadeInfo> Renderer::sunCascades() const {
  std::vector<SunCascadeInfo> out;
  for (const ShadowCascade& c : d_->res.shadows.sun.cascades)
    out.push_back({c.splitNear, c.splitFar, c.texelMetres, c.frameToMap, d_->res.shadows.sun.frameOrigin});
  return out;
}

void Renderer::shutdown() {
  if (!d_->ready) return;
  d_->lastFrame.reset();
  d_->res.meshes.clear();
  d_->res.materials.clear();
  d_->res.terrain.release();
  d_->res.pool.clear();
  d_->res.shaders.release();
  d_ = std::make_unique<Impl>();  // every remaining handle deletes its object now
}

}  // namespace hs::render
