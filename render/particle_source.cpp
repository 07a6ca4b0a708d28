#include "render/particle_source.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <epoxy/gl.h>

#include "particles/bounds.h"
#include "render/frame_context.h"
#include "render/render_view.h"
#include "scene/world_bounds.h"

namespace hs::render {
namespace {

// Storage buffer binding of the particles (shaders/particle.vert) and the
// texture units (a material's units: particles have no material).
constexpr unsigned kParticleBinding = 27;
constexpr unsigned kSpriteUnit = 0, kSceneDepthUnit = 1;
// A velocity-facing quad reaches this far along the motion: a frame's
// travel at 30 fps, the streak a spark leaves on film.
constexpr float kStretchSeconds = 1.0f / 30.0f;
// Transparency keys of particles: above any mesh object index, one per emitter.
constexpr uint32_t kObjectBase = 0x40000000u;

bool needsWorld(const particles::EmitterDesc& d) {
  return d.collision != particles::CollisionMode::None || d.shape == particles::Shape::Mesh ||
         d.shape == particles::Shape::Terrain;
}

// What the collision world is made from: the visible mesh and terrain
// entities where they are. A change rebuilds the world and the evaluators
// that use it (their replay caches too: collisions change the paths).
uint64_t worldKeyOf(const scene::SceneState& state) {
  uint64_t h = 0x9E3779B97F4A7C15ull;
  auto mix = [&](uint64_t v) { h = (h ^ v) * 0x100000001B3ull + (h >> 29); };
  for (const auto& [id, e] : state.entities) {
    if (!e.mesh && !e.terrain) continue;
    mix(id);
    mix(state.effectivelyVisible(id) ? 1 : 2);
    mix(e.mesh ? e.mesh->mesh : 0);
    mix(e.terrain ? e.terrain->terrain : 0);
    const glm::dmat4 m = state.worldMatrix(id);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) mix(std::hash<double>{}(m[c][r]));
  }
  mix(state.assets.size());
  mix(state.terrains.size());
  return h | 1;  // never 0 (0: "no world needed")
}

// The views' frusta with each eye relative to the frame origin.
struct ViewVolume {
  Frustum frustum;
  glm::dvec3 eye;
};

// The sphere (world centre, radius) that holds every particle the emitter
// can have alive at t: its bound (particles/bounds.h: proven), widened by
// scene::placedBound for its spawn tracks and its motion over the births
// of the particles alive at t, grown by the largest particle's reach (a
// sprite: the quad's half-diagonal at the largest size, plus half the
// velocity stretch at the largest speed; a mesh: half the diagonal of the
// cube its longest side is scaled to). None (a mesh shape without its
// surface): unbounded.
std::optional<glm::dvec4> boundSphere(const scene::PlacedEmitter& pe, double t, const particles::Evaluator& ev,
                                      scene::ParticleWorld* world) {
  const std::optional<scene::PlacedBound> b = scene::placedBound(pe, t, world, ev.inputs().surface);
  if (!b) return std::nullopt;
  const particles::EmitterDesc& d = b->desc;  // widened by its spawn tracks
  double sizeScale = d.sizeOverLife.keys.empty() ? 1.0 : 0.0;
  for (const particles::CurveKey& k : d.sizeOverLife.keys) sizeScale = std::max(sizeScale, k.value);
  double reach = 0.5 * std::sqrt(d.drawMesh.empty() ? 2.0 : 3.0) * d.sizeMax * sizeScale;
  if (d.drawMesh.empty() && d.facing == particles::Facing::Velocity)
    reach += 0.5 * double(kStretchSeconds) * particles::speedBound(d, d.lifetimeMax);
  return glm::dvec4(d.origin + b->bound.centre, b->bound.radius + reach);
}

// Whether any view may see a particle inside `sphere` (none: always).
bool mayBeSeen(const std::optional<glm::dvec4>& sphere, const std::vector<ViewVolume>& volumes,
               const glm::dvec3& frameOrigin) {
  if (!sphere) return true;
  const glm::dvec3 c = glm::dvec3(*sphere) - frameOrigin;  // double, then relative
  for (const ViewVolume& v : volumes)
    if (v.frustum.intersectsSphere(c - v.eye, sphere->w)) return true;
  return false;
}

// A billboard's reach about its centre: the quad's half-diagonal, and half
// its streak when it faces along its velocity (particle.vert).
double quadReach(const particles::PackedParticle& q, bool alongVelocity) {
  double radius = 0.5 * std::sqrt(2.0) * double(q.size);
  if (alongVelocity)
    radius += 0.5 * double(kStretchSeconds) * glm::length(glm::dvec3(q.velocity[0], q.velocity[1], q.velocity[2]));
  return radius;
}

// Whether a sphere of radius r swept from `a` to `b` (relative to the
// view's eye) may meet the frustum: no plane leaves both ends outside by
// more than r (conservative: a few corner cases are kept).
bool sweptMayMeet(const Frustum& f, const glm::dvec3& a, const glm::dvec3& b, double r) {
  for (const glm::dvec4& p : f.planes) {
    const glm::dvec3 n(p);
    if (glm::dot(n, a) + p.w < -r && glm::dot(n, b) + p.w < -r) return false;
  }
  return true;
}

// The lowest point a shadow in view can fall on: the meshes the views draw
// (their boxes' corners) and the terrains (their whole boxes).
double lowestReceiverZ(const FrameContext& frame) {
  double z = INFINITY;
  forEachInViewCorner(frame.visible, [&](const glm::dvec3& p) { z = std::min(z, p.z); });
  for (scene::EntityId t : frame.world.terrains) {
    const scene::WorldBox box = scene::worldBounds(*frame.world.state, {t});
    if (!box.empty) z = std::min(z, box.min.z);
  }
  return z;
}

// Mesh particles cast shadows, so one no view sees may still darken a view:
// kept when `sphere` meets a view, or its shadow does (the sphere swept
// along the sun's light up to the shadow distance, and no lower than the
// scene's lowest point, `floorZ`: nothing below it receives a shadow), or a
// shadow-casting point or spot light reaches it. Only what can matter is
// evaluated.
bool meshesMayMatter(const std::optional<glm::dvec4>& sphere, const std::vector<ViewVolume>& volumes,
                     const FrameContext& frame, double floorZ) {
  const glm::dvec3 origin = frame.visible.origin;
  if (mayBeSeen(sphere, volumes, origin)) return true;
  if (!frame.settings.shadows) return false;
  const glm::dvec3 c = glm::dvec3(*sphere) - origin;
  if (const auto& sun = frame.world.sun; sun && sun->castsShadows) {
    double length = frame.settings.shadowDistance;
    if (!std::isfinite(floorZ)) return false;  // nothing in view to fall on
    if (sun->direction.z < -1e-9)
      length = std::min(length, std::max(0.0, (sphere->z + sphere->w - floorZ) / -sun->direction.z));
    for (const ViewVolume& v : volumes)
      if (sweptMayMeet(v.frustum, c - v.eye, c - v.eye + sun->direction * length, sphere->w)) return true;
  }
  for (const WorldLight& l : frame.world.lights)
    if (l.castsShadows && l.type != scene::Light::Type::Sun &&
        glm::length(glm::dvec3(*sphere) - l.position) < double(l.range) + sphere->w)
      return true;
  return false;
}

}  // namespace

ParticleSource::ParticleSource(ParticleSprites& sprites, std::vector<particles::PackedParticle> particles,
                               std::vector<ParticleGpuJob> gpuJobs, std::vector<ParticleDraw> draws, size_t views,
                               const glm::dvec3& origin, std::vector<glm::dvec4> gpuBounds)
    : sprites_(sprites),
      particles_(std::move(particles)),
      gpuJobs_(std::move(gpuJobs)),
      draws_(std::move(draws)),
      views_(views),
      origin_(origin),
      gpuBounds_(std::move(gpuBounds)) {
  records_ = particles_.size();
  for (const ParticleGpuJob& j : gpuJobs_) records_ += j.data.candidates;
}

bool ParticleSource::has(DrawVariant variant, SurfaceSet surfaces) const {
  // Translucent surfaces: the transparency passes and the layered depth of
  // field's capture of every surface (All), which blurs each particle by
  // its own depth. No shadows (Depth), no picking, not in the opaque pass.
  return variant == DrawVariant::Surface && surfaces != SurfaceSet::Opaque && records_ > 0;
}

void ParticleSource::addPreparePasses(FrameGraph& graph, FrameContext& frame) {
  struct Upload {
    BufferRef particles;
  };
  const size_t bytes = records_ * sizeof(particles::PackedParticle);
  const Upload& up = graph.addPass<Upload>(
      "particles_upload",
      [&](PassBuilder& b, Upload& d) {
        d.particles = b.create("particles", BufferDesc{bytes}, Usage::Transfer);
      },
      [this](const Upload& d, const PassResources& r) {
        if (!particles_.empty())
          glNamedBufferSubData(r.buffer(d.particles), 0, GLsizeiptr(particles_.size() * sizeof(particles::PackedParticle)),
                               particles_.data());
      });
  buffer_ = up.particles;
  if (gpuJobs_.empty()) return;
  // The emitters gpuEvaluable takes: evaluated into the rest of the buffer.
  struct Evaluate {
    BufferRef particles;
  };
  const Evaluate& ev = graph.addPass<Evaluate>(
      "particles_evaluate", [&](PassBuilder& b, Evaluate& d) { d.particles = b.write(b.read(buffer_)); },
      [this, &frame](const Evaluate& d, const PassResources& r) {
        GlProgram& p = frame.res.program({"", "", "particle_eval.comp", {}});
        for (const ParticleGpuJob& j : gpuJobs_) dispatchGpuEvaluation(p, j.data, r.buffer(d.particles), j.first);
      });
  buffer_ = ev.particles;
}

void ParticleSource::declare(PassBuilder& builder, DrawVariant variant) const {
  if (variant == DrawVariant::Surface && buffer_.valid()) builder.read(buffer_);
}

double ParticleSource::nearestDepth(const RenderView& view) const {
  const glm::dvec3 fwd = view.forward(), eye = view.eye - origin_;
  double nearest = INFINITY;
  bool stretched = false;  // any emitter's quads stretch along their velocity
  for (const ParticleDraw& d : draws_) stretched = stretched || d.alongVelocity;
  for (const particles::PackedParticle& q : particles_) {
    const glm::dvec3 c(q.position[0], q.position[1], q.position[2]);
    nearest = std::min(nearest, glm::dot(c - eye, fwd) - quadReach(q, stretched));
  }
  for (const glm::dvec4& b : gpuBounds_)
    nearest = std::min(nearest, b.w < 0.0 ? view.nearClip : glm::dot(glm::dvec3(b) - view.eye, fwd) - b.w);
  return nearest;
}

size_t ParticleSource::triangles(SurfaceSet surfaces) const {
  return surfaces != SurfaceSet::Opaque ? records_ * 2 * views_ : 0;
}

void ParticleSource::draw(FrameContext& frame, const DrawCall& call, const PassResources& r) {
  if (!has(call.variant, call.surfaces) || !buffer_.valid()) return;
  std::vector<std::string> defines = call.defines;
  defines.push_back("HS_PARTICLE");  // the passes' own fragment shaders drop what particle.frag drops
  const bool own = call.fragment.empty();
  GlProgram& p = frame.res.program({"particle.vert", own ? "particle.frag" : call.fragment, "", defines});
  p.use();
  glBindVertexArray(frame.res.emptyVao.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kParticleBinding, r.buffer(buffer_));
  glBindTextureUnit(kSpriteUnit, sprites_.texture());
  glBindSampler(kSpriteUnit, 0);
  bool peel = false;
  for (const std::string& d : call.defines) peel = peel || d == "HS_OIT_PEEL";
  if (own && !peel) {
    // Soft particles read the opaque depth the pass tests against: the
    // bound framebuffer's depth attachment (never written while
    // translucent surfaces draw; the depth peel reads its own copy).
    GLint fbo = 0, type = 0, name = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    if (fbo) {
      glGetNamedFramebufferAttachmentParameteriv(GLuint(fbo), GL_DEPTH_ATTACHMENT,
                                                 GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
      if (type == GL_TEXTURE)
        glGetNamedFramebufferAttachmentParameteriv(GLuint(fbo), GL_DEPTH_ATTACHMENT,
                                                   GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    }
    glBindTextureUnit(kSceneDepthUnit, GLuint(name));
    glBindSampler(kSceneDepthUnit, 0);
  }
  p.set("uStretchSeconds", kStretchSeconds);
  p.set("uSpriteTexels", float(ParticleSprites::kSize));
  for (const ParticleDraw& d : draws_) {
    p.set("uFirst", d.first);
    p.set("uObject", d.object);
    p.set("uFacing", d.alongVelocity ? 1 : 0);
    p.set("uLayerBase", d.layerBase);
    p.set("uLayerCount", d.layerCount);
    p.set("uLit", d.lit);
    p.set("uAdditive", d.additive);
    // Without the opaque depth (a pass's own shader) nothing fades.
    p.set("uSoftDistance", d.softDistance);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 6, GLsizei(d.count));
    ++frame.stats.drawCalls;
  }
  glBindTextureUnit(kSceneDepthUnit, 0);
}

ParticleSources::ParticleSources() = default;
ParticleSources::~ParticleSources() = default;

ParticleSources::Entry& ParticleSources::entryFor(const scene::SceneState& state, const scene::PlacedEmitter& placed) {
  Entry& e = entries_[placed.entity];
  const bool world = needsWorld(placed.desc);
  if (world && (!world_ || worldState_ != &state || worldKeyOf(state) != worldKey_)) {
    world_ = std::make_unique<scene::ParticleWorld>(state);
    worldState_ = &state;
    worldKey_ = worldKeyOf(state);
  }
  const uint64_t key = world ? worldKey_ : 0;
  const bool same = e.placed.sameAs(placed) && e.worldKey == key;
  if (e.evaluator && same) return e;
  if (!e.evaluator && !e.error.empty() && same) return e;
  // New or changed: a new evaluator, an empty cache (its entries are keyed
  // by the emitter's content, but its paths depend on the colliders, the
  // emitter's motion and its keyed spawn values too).
  e = Entry{};
  e.placed = placed;
  e.worldKey = key;
  if (world) {
    e.evaluator = world_->evaluator(placed, e.error);
  } else {
    particles::EvaluatorInputs in;
    scene::addTimeInputs(placed, in);
    e.evaluator = particles::Evaluator::create(placed.desc, std::move(in), e.error);
  }
  return e;
}

unsigned ParticleSources::terrainHeightsFor(const terrain::Heightfield& hf) {
  if (!terrainHeights_ || terrainHeightsKey_ != worldKey_) {
    const std::vector<float> heights = gpuTerrainHeights(hf);
    terrainHeights_ = gl::createBuffer();
    glNamedBufferStorage(terrainHeights_.id(), GLsizeiptr(heights.size() * sizeof(float)), heights.data(), 0);
    terrainHeightsKey_ = worldKey_;
  }
  return terrainHeights_.id();
}

const particles::Frame& ParticleSources::frameAt(Entry& e, double t) {
  if (!e.evaluated || e.time != t) {
    e.frame = e.evaluator->frame(t, &e.cache);
    e.time = t;
    e.evaluated = true;
  }
  return e.frame;
}

DrawSource* ParticleSources::update(const scene::SceneState& state, FrameContext& frame) {
  source_.reset();
  errors_.clear();
  meshesActive_ = false;
  if (meshes_) meshes_->clear();
  const std::vector<scene::PlacedEmitter> placed = scene::visibleEmitters(state);
  // Entities gone (or hidden) drop their caches.
  for (auto it = entries_.begin(); it != entries_.end();) {
    bool kept = false;
    for (const scene::PlacedEmitter& p : placed) kept = kept || p.entity == it->first;
    it = kept ? std::next(it) : entries_.erase(it);
  }
  if (placed.empty()) {
    world_.reset();
    worldState_ = nullptr;
    meshes_.reset();
    terrainHeights_ = gl::Buffer();
    return nullptr;
  }
  // Every view of the frame (both eyes): a particle any of them sees is kept.
  std::vector<ViewVolume> volumes;
  const glm::dvec3 origin = frame.visible.origin;
  if (frame.views)
    for (const RenderView& v : *frame.views) volumes.push_back({frustumOf(v), v.eye - origin});
  else
    volumes.push_back({frustumOf(frame.lodView), frame.lodView.eye - origin});

  const double t = state.time.seconds;
  std::vector<particles::PackedParticle> all;
  std::vector<ParticleDraw> draws, gpuDraws;
  std::vector<ParticleGpuJob> jobs;
  std::vector<glm::dvec4> gpuBounds;
  std::optional<double> floorZ;  // the scene's lowest point, found when a mesh emitter needs it
  uint32_t gpuRecords = 0;
  uint32_t index = 0;
  bool terrainUsed = false;  // a GPU job collides with the terrain
  for (const scene::PlacedEmitter& pe : placed) {
    const uint32_t object = kObjectBase + index++;
    Entry& e = entryFor(state, pe);
    if (!e.evaluator) {
      errors_.push_back(e.error);
      continue;
    }
    if (!pe.desc.drawMesh.empty()) {
      // Mesh particles (particle_mesh.h): instances of the named entity's
      // mesh, evaluated on the CPU whatever the GPU setting (the instances
      // are made from the particles), culled per view by the instanced
      // source (a particle out of every camera view may cast a shadow into
      // one: meshesMayMatter).
      const scene::MeshAsset* asset = scene::drawMeshAsset(state, pe.desc.drawMesh);
      if (!asset) {
        errors_.push_back(scene::drawMeshProblem(pe.desc));
        continue;
      }
      if (e.evaluator->candidates(t) == 0) continue;
      // Out of every view, its shadows too: nothing evaluated.
      if (!floorZ) floorZ = lowestReceiverZ(frame);
      if (!meshesMayMatter(boundSphere(pe, t, *e.evaluator, world_ && needsWorld(pe.desc) ? world_.get() : nullptr),
                           volumes, frame, *floorZ)) {
        ++frame.stats.emittersOutOfView;
        continue;
      }
      const particles::Frame& f = frameAt(e, t);
      if (f.particles.empty()) continue;
      if (!meshes_) meshes_ = std::make_unique<MeshParticleSource>();
      std::string error;
      meshes_->add(pe.entity, pe.desc, *asset, f, error);
      if (!error.empty()) errors_.push_back(error);
      continue;
    }
    // Nothing born in the live window: the emitter costs nothing at t.
    if (e.evaluator->candidates(t) == 0) continue;
    // Out of every view: it costs nothing either (no evaluation, no upload).
    const std::optional<glm::dvec4> bound =
        boundSphere(pe, t, *e.evaluator, world_ && needsWorld(pe.desc) ? world_.get() : nullptr);
    const glm::dvec4 sphere = bound.value_or(glm::dvec4(0.0, 0.0, 0.0, -1.0));  // radius < 0: none known
    if (!mayBeSeen(bound, volumes, origin)) {
      ++frame.stats.emittersOutOfView;
      continue;
    }
    ParticleDraw d;
    d.layerBase = ParticleSprites::layerBase(pe.desc.sprite);
    d.layerCount = ParticleSprites::layerCount(pe.desc.sprite);
    d.additive = pe.desc.blend == particles::Blend::Additive;
    d.lit = pe.desc.lit;
    d.alongVelocity = pe.desc.facing == particles::Facing::Velocity;
    d.softDistance = float(pe.desc.softDistance);
    d.object = object;
    GpuTerrainCollider terrain;
    if (world_ && needsWorld(pe.desc)) {
      terrain.collider = world_->terrainCollider();
      terrain.heightfield = world_->terrainHeights();
    }
    if ((frame.options.gpuParticles || frame.settings.particlesOnGpu) &&
        gpuEvaluable(*e.evaluator, t, nullptr, &terrain)) {
      // The compute pass evaluates every candidate (the dead ones draw
      // nothing); no per-particle culling on the CPU.
      if (collidesWithTerrain(*e.evaluator, &terrain)) {
        terrain.heights = terrainHeightsFor(*terrain.heightfield);
        terrainUsed = true;
      }
      ParticleGpuJob job{gpuEmitterData(*e.evaluator, t, origin, pe.desc.seed, &terrain), gpuRecords};
      d.first = gpuRecords;  // after the CPU's records: moved below
      d.count = job.data.candidates;
      gpuRecords += d.count;
      jobs.push_back(std::move(job));
      gpuDraws.push_back(d);
      gpuBounds.push_back(sphere);
      continue;
    }
    const particles::Frame& f = frameAt(e, t);
    if (f.particles.empty()) continue;
    std::vector<particles::PackedParticle> packed = particles::packFrame(f, pe.desc.origin, origin, pe.desc.seed);
    const bool along = d.alongVelocity;
    d.first = uint32_t(all.size());
    for (const particles::PackedParticle& q : packed) {
      if (!(q.colour[3] > 0.0f) || !(q.size > 0.0f)) continue;
      const glm::dvec3 c(q.position[0], q.position[1], q.position[2]);
      const double radius = quadReach(q, along);
      bool seen = false;
      for (const ViewVolume& v : volumes) seen = seen || v.frustum.intersectsSphere(c - v.eye, radius);
      if (seen) all.push_back(q);
    }
    d.count = uint32_t(all.size()) - d.first;
    if (d.count == 0) continue;
    draws.push_back(d);
  }
  if (!terrainUsed) terrainHeights_ = gl::Buffer();
  if (meshes_) {
    const size_t instances = meshes_->commit();
    meshesActive_ = instances > 0;
    frame.stats.particlesDrawn += instances;
  }
  if (all.empty() && jobs.empty()) return nullptr;
  // The compute pass's records follow the CPU's.
  const uint32_t cpuRecords = uint32_t(all.size());
  for (ParticleGpuJob& j : jobs) j.first += cpuRecords;
  for (ParticleDraw& d : gpuDraws) {
    d.first += cpuRecords;
    draws.push_back(d);
  }
  frame.stats.particlesDrawn += all.size() + gpuRecords;
  const size_t views = frame.views ? frame.views->size() : 1;
  source_ = std::make_unique<ParticleSource>(sprites_, std::move(all), std::move(jobs), std::move(draws), views, origin,
                                             std::move(gpuBounds));
  return source_.get();
}

}  // namespace hs::render
