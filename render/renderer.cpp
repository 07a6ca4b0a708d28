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
#include "render/mesh_source.h"
#include "render/terrain_source.h"
#include "render/oit.h"
#include "render/passes/ao_passes.h"
#include "render/passes/background_passes.h"
#include "render/passes/dof_passes.h"
#include "render/dof_reference.h"
#include "render/passes/environment_pass.h"
#include "render/passes/group_combine.h"
#include "render/passes/light_culling.h"
#include "render/passes/output_passes.h"
#include "render/passes/scene_passes.h"
#include "render/passes/shadow_passes.h"
#include "render/cluster_source.h"
#include "render/foliage_sources.h"
#include "render/particle_source.h"
#include "render/render_resources.h"
#include "scene/camera_post.h"
#include "scene/impostor_key.h"
#include "scene/light_units.h"

namespace hs::render {
namespace {

// Every program the renderer uses, built (and so checked) at initialisation.
const std::vector<gl::ProgramDesc>& allPrograms() {
  static const std::vector<gl::ProgramDesc> programs = {
      {"mesh.vert", "mesh.frag", "", {}},         {"mesh.vert", "pick.frag", "", {}},
      {"mesh.vert", "cluster_level.frag", "", {}},  // the cluster level view (cluster_source.h)
      {"fullscreen.vert", "sky.frag", "", {}},    {"grid.vert", "grid.frag", "", {}},
      {"overlay.vert", "overlay.frag", "", {}},   {"fullscreen.vert", "tonemap.frag", "", {"HS_TONEMAP_ACES"}},
      {"fullscreen.vert", "fxaa.frag", "", {}},
      // The post chain: every per-pixel effect at once (each is checked), bloom's levels
      {"fullscreen.vert", "tonemap.frag", "", {"HS_TONEMAP_AGX", "HS_BLOOM", "HS_CA", "HS_GRADE", "HS_VIGNETTE", "HS_GRAIN"}},
      {"fullscreen.vert", "tonemap.frag", "", {"HS_TONEMAP_NEUTRAL"}},
      {"fullscreen.vert", "bloom_down.frag", "", {"HS_BLOOM_PREFILTER"}},
      {"fullscreen.vert", "bloom_down.frag", "", {}},     {"fullscreen.vert", "bloom_up.frag", "", {}},
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
      // Instanced draw sources (instanced_source.h)
      {"mesh.vert", "mesh.frag", "", {"INSTANCED"}}, {"", "", "instance_cull.comp", {}},
      {"", "", "instance_commands.comp", {}},
      // Particles (particle_source.h)
      {"particle.vert", "particle.frag", "", {"HS_PARTICLE"}}, {"", "", "particle_eval.comp", {}},
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
  // The last frame's graphs (one per view group, and the one combining
  // them), holding what they keep (HDR colour, depth) until the next frame,
  // and what each view of the frame kept, in order over the groups.
  struct Kept {
    const FrameGraph* hdrGraph = nullptr;
    const FrameGraph* depthGraph = nullptr;
    TextureRef hdr, depth;
    glm::ivec2 size{0};
  };
  std::vector<std::unique_ptr<FrameGraph>> frames;
  std::vector<Kept> kept;
  // While renderGroups runs: the graphs and views of its earlier groups,
  // which a later group's frame does not drop.
  bool inGroups = false;
  size_t groupFrames = 0, groupKept = 0;
  // Depth of field's reference (dof_reference.h): while the lens samples
  // render (each a plain pinhole frame adding its HDR images, times
  // lensWeight, to the persistent sums; the first clears them), and while
  // its pinhole frame at the lens centre renders (the depth it keeps).
  bool lensSampling = false, lensPinhole = false;
  int lensSample = 0;
  float lensWeight = 0.0f;
  std::vector<std::shared_ptr<DrawSource>> extraSources;  // setDrawSources
  FoliageSources foliage;  // the document's foliage (foliage_sources.h)
  ParticleSources particles;  // the document's emitters (particle_source.h)
  ClusterSources clusters;    // meshes with a cluster hierarchy (cluster_source.h)
  // The mesh source, then the clustered meshes when the frame has any, then the terrains.
  void addMeshSources(FrameContext& frame, VisibleSet& visible, const std::vector<RenderView>& views,
                      MeshSource& meshes, TerrainSource& terrains) {
    frame.sources = {&meshes};
    if (DrawSource* c = clusters.update(frame, visible, views)) frame.sources.push_back(c);
    frame.sources.push_back(&terrains);
  }
  // The sources every frame draws after the meshes and terrains: the
  // document's foliage, its particles (the sprites when any is live in
  // view, the mesh particles when an emitter with a draw_mesh has live
  // particles), then the extra ones.
  void addSources(const scene::SceneState& state, FrameContext& frame) {
    for (const auto& s : foliage.update(state)) frame.sources.push_back(s.get());
    if (DrawSource* p = particles.update(state, frame)) frame.sources.push_back(p);
    if (DrawSource* m = particles.meshes()) frame.sources.push_back(m);
    for (const auto& s : extraSources) frame.sources.push_back(s.get());
  }

  // The suffix of a view's passes and resources: its name, and from the
  // second group of renderGroups on the group's ("[g1/left]").
  size_t groupIndex = 0;
  std::string suffix(const std::string& name) const {
    std::string tag = groupIndex ? "g" + std::to_string(groupIndex) : "";
    if (!tag.empty() && !name.empty()) tag += "/";
    tag += name;
    return tag.empty() ? "" : "[" + tag + "]";
  }

  void resetKept() {
    frames.resize(groupFrames);
    kept.resize(groupKept);
  }

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

  // The object data and materials of every mesh draw, the shadow-only
  // casters' too: after the shadow views chose them (planShadows).
  // The other sources' materials follow the meshes' (DrawSource::addMaterials).
  void uploadDraws(FrameContext& frame, const VisibleSet& visible) {
    res.objects.reserve(std::max<size_t>(visible.objects.size(), 1) * sizeof(GpuObject));
    res.objects.upload(visible.objects.data(), visible.objects.size() * sizeof(GpuObject));
    res.ensureObjectIndices(visible.objects.size());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBufferBinding, res.objects.buffer.id());
    std::vector<DrawItem> draws = visible.draws;
    for (DrawSource* s : frame.sources) s->addMaterials(frame, draws);
    res.materials.build(*frame.world.state, draws, {visible.inView, visible.draws.size()}, res.meshes, res.materialBlock);
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
  if (state.settings.depthOfField == scene::DepthOfField::Reference && !d_->lensSampling && !d_->lensPinhole)
    if (std::optional<FrameStats> s = renderLensReference(state, targets, options)) return *s;
  const auto t0 = std::chrono::steady_clock::now();
  Impl& d = *d_;
  RenderResources& res = d.res;
  // A camera's own post settings apply to the views through it (both eyes
  // of a pair are the same camera's).
  const scene::SceneSettings settings = scene::settingsFor(state, targets.front().view.camera);

  GLuint timer = 0;
  if (options.measureGpuTime && !d.inGroups) {
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
  // The last frame's kept targets go back to the pool now (but for the
  // earlier groups' of this frame).
  d.resetKept();

  // Once per frame, whatever the number of views.
  const RenderWorld world = RenderWorld::build(state);
  std::vector<RenderView> views;
  for (const ViewTarget& t : targets) views.push_back(t.view);
  const RenderView& lodView = options.lodView ? *options.lodView : views.front();
  VisibleSet visible = buildVisibleSet(world, res.meshes, views, &lodView, settings.meshLodErrorPixels);
  stats.instancesCulled = visible.culled;
  stats.instancesAtCoarserLod = visible.coarser;
  const size_t lightsInView = pointLightsInView(world, views);
  d.uploadFrameData(world, visible, settings, state.time, targets, lightsInView);

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
    viewContexts.push_back({targets[i].view, i, targets[i].fbo, d.suffix(targets[i].name)});
  // What the frame draws (draw_source.h), in drawing order.
  MeshSource meshSource(visible, world, res.meshes, res.materials);
  TerrainSource terrainSource(world);
  d.addMeshSources(frame, visible, views, meshSource, terrainSource);
  d.addSources(state, frame);
  // Shadow views first: each source culls its casters once.
  const ShadowPlan shadows = planShadows(frame);
  d.uploadDraws(frame, visible);
  for (DrawSource* s : frame.sources) s->addPreparePasses(*graph, frame);
  // Shadows: once per frame, before the views that read them.
  addShadowPasses(*graph, frame, shadows);
  // Eye-independent: once per frame, before the views.
  addEnvironmentPass(*graph, frame);
  // Clustered lights: once per frame, one grid per view.
  addLightCullingPass(*graph, frame, viewContexts);
  // Transparency (render/oit.h): the sources' translucent surfaces; none, no OIT pass or buffer.
  const bool translucent = anySource(frame, DrawVariant::Surface, SurfaceSet::Translucent);
  std::vector<std::shared_ptr<OitViewInfo>> oitViews(viewContexts.size());
  for (const ViewContext& v : viewContexts) {
    SceneTargets scene = addOpaquePass(*graph, frame, v);
    scene = addSourcePasses(*graph, frame, v, scene);
    scene = addSkyPass(*graph, frame, v, scene);
    if (settings.showGrid && options.showGrid) scene = addGridPass(*graph, frame, v, scene);
    if (options.overlay && !options.overlay->empty())
      scene = addOverlayPass(*graph, frame, v, scene, *options.overlay);
    TextureRef hdr = addResolvePass(*graph, frame, v, scene);
    hdr = addAmbientOcclusionPasses(*graph, frame, v, scene, hdr);  // per eye; none with AO off
    // Transparency over the opaque colour, tested against a single-sample depth.
    TextureRef singleDepth;
    if (translucent || options.keepDepth) singleDepth = addDepthResolvePass(*graph, frame, v, scene);
    // Stippling and error diffusion in stereo take the first eye's pattern by depth.
    TextureRef pairDepth;
    if ((settings.post.stipple || settings.post.dither == scene::DitherMode::ErrorDiffusion) &&
        viewContexts.size() == 2)
      pairDepth = singleDepth.valid() ? singleDepth : addDepthResolvePass(*graph, frame, v, scene);
    // The layered depth of field captures the translucent surfaces itself
    // and composites them over the colour before them: no transparency
    // pass for the view then (each surface counted once).
    if (!layeredDepthOfField(frame, v.view))
      hdr = addTransparencyPasses(*graph, frame, v, SurfaceSet::Translucent, singleDepth, hdr, options.oitCounts,
                                  oitViews[v.index]);
    if (options.depthComplexity && translucent)
      hdr = addDepthComplexityPass(*graph, frame, v, SurfaceSet::Translucent, singleDepth, hdr);
    hdr = addDepthOfFieldPasses(*graph, frame, v, scene, hdr);       // none with DoF off or no blur
    // A lens sample of the depth of field's reference adds its image to
    // the sums instead of showing it.
    if (d.lensSampling) addLensSamplePass(*graph, frame, v, hdr, d.lensSample == 0, d.lensWeight);
    else addToneMapPasses(*graph, frame, v, hdr, pairDepth);
    Impl::Kept k;
    k.hdrGraph = k.depthGraph = graph.get();
    k.size = {v.view.width, v.view.height};
    if (options.keepHdr) graph->keep(k.hdr = hdr);
    if (options.keepDepth) graph->keep(k.depth = singleDepth);
    d.kept.push_back(k);
  }
  graph->execute(options.passTimings);
  for (const PassRecord& r : graph->records())
    if (r.ran) stats.passes.push_back({r.name, r.cpuMs, r.gpuMs, r.gpuBytes});
  stats.oit = oitStats(settings, oitViews);
  d.frames.push_back(std::move(graph));
  if (!d.inGroups) res.pool.endFrame();  // renderGroups ends its frame once

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
  if (view >= d_->kept.size() || !d_->kept[view].hdrGraph) return img;
  const Impl::Kept& k = d_->kept[view];
  const GLuint tex = k.hdrGraph->keptTexture(k.hdr);
  if (!tex) return img;
  img.width = k.size.x;
  img.height = k.size.y;
  img.rgbaF.resize(size_t(img.width) * size_t(img.height) * 4);
  glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(img.rgbaF.size() * sizeof(float)), img.rgbaF.data());
  flipRows(img.rgbaF.data(), size_t(img.width) * 4 * sizeof(float), size_t(img.height));  // GL rows are bottom-up
  return img;
}

void Renderer::readHdrInto(void* dst, size_t bytes, size_t view) const {
  if (view >= d_->kept.size() || !d_->kept[view].hdrGraph) return;
  if (const GLuint tex = d_->kept[view].hdrGraph->keptTexture(d_->kept[view].hdr))
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(bytes), dst);
}

void Renderer::readDepth(void* dst, size_t view) {
  if (view >= d_->kept.size() || !d_->kept[view].depthGraph) return;
  const GLuint tex = d_->kept[view].depthGraph->keptTexture(d_->kept[view].depth);
  if (!tex) return;
  const glm::ivec2 size = d_->kept[view].size;
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
  if (const size_t t = res.impostors.gpuBytes()) out.push_back({"impostor_atlases", "textures", t, false});
  if (const size_t f = res.fogBlock.capacity) out.push_back({"fog_block", "buffer", f, false});
  if (const size_t l = res.luts.gpuBytes()) out.push_back({"lut_tables", "textures", l, false});
  if (const size_t l = res.viewTransforms.gpuBytes()) out.push_back({"view_transform_tables", "textures", l, false});
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
  VisibleSet visible = buildVisibleSet(world, res.meshes, {view}, &view, state.settings.meshLodErrorPixels);
  d.uploadFrameData(world, visible, state.settings, state.time, {ViewTarget{view, 0, {}}}, 0);  // picking lights nothing
  ViewBlock vb = viewBlockOf(view, visible.origin);
  vb.projection = glm::mat4(n * view.projection());
  res.viewBlocks.upload(&vb, sizeof vb);

  // A frame of one pass (the id pass) over the frame's sources; each
  // source's ids follow the one before's (meshes, then terrains).
  FrameStats stats;
  RenderOptions options;
  options.streamClusters = true;  // a click picks what the viewport shows, without waiting for pages
  const std::vector<RenderView> views{view};
  FrameContext frame{res, world, visible, state.settings, options, view, stats};
  frame.views = &views;
  MeshSource meshSource(visible, world, res.meshes, res.materials);
  TerrainSource terrainSource(world);
  d.addMeshSources(frame, visible, views, meshSource, terrainSource);
  d.addSources(state, frame);
  d.uploadDraws(frame, visible);
  FrameGraph graph(res.pool);
  for (DrawSource* s : frame.sources) s->addPreparePasses(graph, frame);
  struct Pick {
    TextureRef id, depth;
    GLuint picked = 0;
    float depthValue = 0.0f;
  };
  std::vector<uint32_t> bases;
  uint32_t next = 1;  // 0: nothing
  for (DrawSource* s : frame.sources) {
    bases.push_back(next);
    next += s->pickIds();
  }
  const Pick& pick = graph.addPass<Pick>(
      "pick",
      [&](PassBuilder& b, Pick& p) {
        p.id = b.create("pick_id", TextureDesc{1, 1, GL_R32UI});
        p.depth = b.create("pick_depth", TextureDesc{1, 1, GL_DEPTH_COMPONENT32F});
        declareSources(b, frame, DrawVariant::Pick);
        b.sideEffect();
      },
      [&](const Pick& p, const PassResources& r) {
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({p.id}, p.depth));
        glViewport(0, 0, 1, 1);
        glDisable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_GREATER);
        const GLuint zero[4] = {0, 0, 0, 0};
        const float clearDepth = 0.0f;
        glClearBufferuiv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_DEPTH, 0, &clearDepth);
        res.bindView(0);
        for (size_t i = 0; i < frame.sources.size(); ++i) {
          if (!frame.sources[i]->has(DrawVariant::Pick)) continue;
          DrawCall call;
          call.variant = DrawVariant::Pick;
          call.pickBase = bases[i];
          call.pickPixel = {x, int(view.height) - 1 - y};
          frame.sources[i]->draw(frame, call, r);
        }
        auto& out = const_cast<Pick&>(p);
        glReadPixels(0, 0, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, &out.picked);
        // The depth the id pass left (the narrowing scales x and y only): the
        // view depth of the surface, for focus picking (depth of field).
        glReadPixels(0, 0, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &out.depthValue);
      });
  graph.execute();
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  glUseProgram(0);
  PickHit hit;
  const uint32_t id = pick.picked;
  for (size_t i = 0; i < frame.sources.size() && id; ++i)
    if (id >= bases[i] && id < bases[i] + frame.sources[i]->pickIds()) {
      const PickedItem item = frame.sources[i]->picked(id - bases[i]);
      hit.entity = item.entity;
      hit.instance = item.instance;
    }
  if (id > 0 && pick.depthValue > 0.0f) {
    const glm::dmat4 p = view.projection();  // reversed Z: 1/z = (depth + p22) / p32
    hit.viewDepth = p[3][2] / (double(pick.depthValue) + p[2][2]);
  }
  return hit;
}

std::vector<std::string> Renderer::particleErrors() const { return d_->particles.errors(); }

void Renderer::setDrawSources(std::vector<std::shared_ptr<DrawSource>> sources) {
  d_->extraSources = std::move(sources);
}

void Renderer::collectGarbage(const scene::SceneState& state) {
  d_->res.meshes.collect(state);
  d_->res.impostors.collect(state);
  d_->res.materials.collect(state);
}

std::optional<foliage::ImpostorImages> Renderer::bakeImpostor(const scene::SceneState& state, scene::AssetId id,
                                                              std::string& error) {
  const scene::MeshAsset* asset = state.findAsset(id);
  if (!asset) {
    error = "mesh asset " + std::to_string(id) + " is not in the scene";
    return std::nullopt;
  }
  RenderResources& res = d_->res;
  const GpuMesh* mesh = res.meshes.get(*asset, 0);
  if (!mesh || mesh->bounds.empty || !(mesh->bounds.radius() > 0.0f)) {
    error = "mesh asset '" + asset->name + "' has no triangles to bake";
    return std::nullopt;
  }
  // The frame's material table and block serve the bake (the next frame
  // builds its own): one draw, the asset's level 0.
  const std::vector<DrawItem> draws = {{0, mesh, asset}};
  res.materials.build(state, draws, {draws.size(), draws.size()}, res.meshes, res.materialBlock);
  std::vector<DrawMaterial> materials;
  for (size_t s = 0; s < mesh->data->submeshes.size(); ++s) materials.push_back(res.materials.forDraw(0, s));
  auto images = res.impostors.bakeAndRead(res, id, scene::impostorSourceKey(state, *asset), *mesh, materials);
  if (!images) error = "mesh asset '" + asset->name + "' has no bounds to bake";
  return images;
}

size_t Renderer::impostorsBaked() const { return d_->res.impostors.bakes(); }
size_t Renderer::impostorsUploaded() const { return d_->res.impostors.uploads(); }

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

std::vector<std::string> Renderer::takeLutProblems() {
  std::vector<std::string> out;
  out.swap(d_->res.lutProblems);
  return out;
}

std::vector<std::string> Renderer::takeClusterProblems() { return d_->clusters.takeProblems(); }

std::vector<std::string> Renderer::takeDofProblems() {
  std::vector<std::string> out;
  out.swap(d_->res.dofProblems);
  return out;
}

// Depth of field, reference (dof_reference.h): the lens samples are whole
// frames through renderViews (with lensSampling set: each is a pinhole
// frame whose last pass adds its HDR images to persistent sums in the
// frame graph), then, when the caller keeps depth, one pinhole frame at the
// lens centre for it, then one small graph tone maps the sums into the
// targets and keeps them for readHdr.
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
    // The sources are not made yet: the meshes' nearest depth decides (a
    // particle or a tree nearer than every mesh with the rest in focus and
    // no terrain or sky to blur: no reference).
    if (!depthOfFieldNeeded(state.settings, res, views[i], nearestDrawnDepth(world, visible, views[i]), &lenses[i]))
      lenses[i].valid = false;
    else any = true;
  if (!any) return std::nullopt;

  const int n = std::clamp(state.settings.dofReferenceSamples, 64, 1024);
  const std::vector<glm::dvec2> disc = lensDiscSamples(n);
  RenderOptions o = options;
  o.keepHdr = false;
  o.keepDepth = false;
  o.measureGpuTime = false;
  o.passTimings = false;
  o.lodView = &lodView;  // every sample draws the same levels of detail
  FrameStats stats;
  d.lensSampling = true;
  d.lensWeight = 1.0f / float(n);
  for (int k = 0; k < n; ++k) {
    d.lensSample = k;
    std::vector<ViewTarget> sample = targets;
    for (size_t i = 0; i < sample.size(); ++i)
      if (lenses[i].valid) sample[i].view = lensSampleView(views[i], lenses[i], disc[size_t(k)]);
    stats = renderViews(state, sample, o);
  }
  d.lensSampling = false;
  if (options.keepDepth) {
    // The depth a caller reads (the export's comfort check, the focus
    // pick) is the pinhole frame's, as with the other modes: one more
    // frame at the lens centre, its graph kept with the sums'.
    RenderOptions pinhole = o;
    pinhole.keepDepth = true;
    d.lensPinhole = true;
    renderViews(state, targets, pinhole);
    d.lensPinhole = false;
  } else {
    d.resetKept();
  }

  // Tone map the sums into the targets.
  auto graph = std::make_unique<FrameGraph>(res.pool);
  FrameStats finalStats;
  const scene::SceneSettings settings = scene::settingsFor(state, targets.front().view.camera);
  FrameContext frame{res, world, visible, settings, options, lodView, finalStats};
  for (size_t i = 0; i < targets.size(); ++i) {
    const ViewContext v{targets[i].view, i, targets[i].fbo, d.suffix(targets[i].name)};
    const TextureRef sum = lensSumTexture(*graph, v);
    addToneMapPasses(*graph, frame, v, sum);
    if (d.kept.size() <= d.groupKept + i) d.kept.emplace_back();
    Impl::Kept& k = d.kept[d.groupKept + i];
    k.size = {views[i].width, views[i].height};
    k.hdrGraph = graph.get();
    k.hdr = {};
    if (options.keepHdr) graph->keep(k.hdr = sum);
  }
  graph->execute(false);
  for (const PassRecord& r : graph->records())
    if (r.ran) stats.passes.push_back({r.name, r.cpuMs, r.gpuMs, r.gpuBytes});
  d.frames.push_back(std::move(graph));
  if (!d.inGroups) res.pool.endFrame();
  glBindFramebuffer(GL_FRAMEBUFFER, targets.back().fbo);
  fillMemoryStats(stats);
  return stats;
}

std::vector<FrameStats> Renderer::renderGroups(const scene::SceneState& state, const std::vector<ViewGroup>& groups,
                                               const RenderOptions& options, const GroupCombine* combine) {
  std::vector<FrameStats> out;
  Impl& d = *d_;
  if (!d.ready || groups.empty()) return out;
  d.groupFrames = d.groupKept = 0;
  d.resetKept();  // the last frame's
  d.inGroups = true;
  for (const ViewGroup& g : groups) {
    d.groupIndex = size_t(&g - groups.data());
    RenderOptions o = options;
    o.lodView = g.lodView;
    if (combine) o.keepHdr = true;
    out.push_back(renderViews(state, g.targets, o));
    // What this group keeps stays through the next groups.
    d.groupFrames = d.frames.size();
    d.groupKept = d.kept.size();
  }
  if (combine && !combine->targets.empty()) {
    // The last graph. With one post chain for every group (no camera of
    // them overrides a post setting differently): view i of every group,
    // weighted and summed in linear light, run through that chain into
    // combine->targets[i]. With differing chains, each group's finished
    // picture (its own chain, already in its targets) is combined instead,
    // as an editor cuts between graded shots; the HDR mix is still what
    // keepHdr keeps.
    std::vector<scene::SceneSettings> groupSettings;
    for (const ViewGroup& g : groups) {
      const scene::EntityId camera = g.targets.empty() ? scene::kNoEntity : g.targets.front().view.camera;
      groupSettings.push_back(scene::settingsFor(state, camera));
    }
    bool oneChain = true;
    for (const scene::SceneSettings& gs : groupSettings)
      oneChain = oneChain && scene::samePostChain(gs, groupSettings[0]);
    auto graph = std::make_unique<FrameGraph>(d.res.pool);
    // Its passes (the combine, the tone map) read the settings alone: no
    // world or visible set is built for them.
    const RenderWorld world;
    const VisibleSet visible;
    FrameStats stats;
    FrameContext frame{d.res, world, visible, groupSettings[0], options, combine->targets.front().view, stats};
    const CombinePattern pattern{combine->transition, combine->progress, combine->frame};
    for (size_t i = 0; i < combine->targets.size(); ++i) {
      const ViewTarget& t = combine->targets[i];
      const ViewContext v{t.view, i, t.fbo, t.name.empty() ? "" : "[" + t.name + "]"};
      std::vector<std::pair<TextureRef, float>> images, pictures;
      for (size_t g = 0, first = 0; g < groups.size(); first += groups[g].targets.size(), ++g) {
        if (i >= groups[g].targets.size() || g >= combine->weights.size()) continue;
        const Impl::Kept& k = d.kept[first + i];
        const GLuint tex = k.hdrGraph ? k.hdrGraph->keptTexture(k.hdr) : 0;
        if (!tex) continue;
        images.emplace_back(graph->importTexture(v.named("group" + std::to_string(g)), tex,
                                                 TextureDesc{k.size.x, k.size.y, GL_RGBA16F}),
                            combine->weights[g]);
        if (!oneChain)
          pictures.emplace_back(addTargetCopyPass(*graph, frame, v, groups[g].targets[i].fbo,
                                                  "group" + std::to_string(g) + "_picture"),
                                combine->weights[g]);
      }
      Impl::Kept k;
      k.size = {t.view.width, t.view.height};
      if (oneChain) {
        const TextureRef mixed = addGroupCombinePass(*graph, frame, v, images, pattern);
        addToneMapPasses(*graph, frame, v, mixed);
        if (options.keepHdr) graph->keep(k.hdr = mixed);
      } else {
        addGroupCombinePass(*graph, frame, v, pictures, pattern, true);
        if (options.keepHdr) graph->keep(k.hdr = addGroupCombinePass(*graph, frame, v, images, pattern));
      }
      if (options.keepHdr) k.hdrGraph = graph.get();
      d.kept.push_back(k);
    }
    graph->execute(options.passTimings);
    FrameStats& last = out.back();
    for (const PassRecord& r : graph->records())
      if (r.ran) last.passes.push_back({r.name, r.cpuMs, r.gpuMs, r.gpuBytes});
    d.frames.push_back(std::move(graph));
  }
  d.inGroups = false;
  d.groupIndex = 0;
  d.groupFrames = d.groupKept = 0;
  d.res.pool.endFrame();
  for (FrameStats& s : out) fillMemoryStats(s);
  return out;
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
  d_->frames.clear();
  d_->kept.clear();
  d_->res.meshes.clear();
  d_->clusters.clear();
  d_->res.impostors.clear();
  d_->res.materials.clear();
  d_->res.terrain.release();
  d_->res.luts.release();
  d_->res.viewTransforms.release();
  d_->res.pool.clear();
  d_->res.shaders.release();
  d_ = std::make_unique<Impl>();  // every remaining handle deletes its object now
}

}  // namespace hs::render
