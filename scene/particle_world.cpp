#include "scene/particle_world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "foliage/surface.h"
#include "sequencer/camera_path.h"
#include "sequencer/track.h"

#include <glm/gtc/matrix_transform.hpp>

namespace hs::scene {

std::optional<particles::EmitterDesc> emitterInWorld(const SceneState& state, EntityId id) {
  const Entity* e = state.find(id);
  if (!e || !e->particles) return std::nullopt;
  particles::EmitterDesc d = e->particles->desc;
  d.origin += glm::dvec3(state.worldMatrix(id)[3]);
  d.name = e->name;
  return d;
}

namespace {

bool movesTransform(const sequencer::Binding& b) {
  if (b.path) return true;
  for (const sequencer::Track& t : b.tracks) {
    const std::string& p = sequencer::trackProperty(t);
    if ((p == "transform.translation" || p == "transform.rotation" || p == "transform.scale") &&
        sequencer::trackKeyCount(t) > 0)
      return true;
  }
  return false;
}

}  // namespace

std::shared_ptr<const EmitterMotion> EmitterMotion::of(const SceneState& state, EntityId id) {
  const Entity* e = state.find(id);
  if (!e || !e->particles || e->particles->desc.space != particles::Space::World) return nullptr;
  auto m = std::make_shared<EmitterMotion>();
  bool moves = false, path = false;
  for (EntityId at = id; at != kNoEntity;) {
    const Entity* x = state.find(at);
    if (!x) break;
    Level level{at, x->transform, std::nullopt};
    if (const sequencer::Binding* b = state.sequence.findBinding(at); b && movesTransform(*b)) {
      level.binding = *b;
      moves = true;
      path = path || b->path.has_value();
    }
    m->levels_.push_back(std::move(level));
    at = x->parent;
  }
  if (!moves) return nullptr;
  m->offset_ = e->particles->desc.origin;
  if (path) m->compiled_ = std::make_shared<const sequencer::CompiledSequence>(state.sequence);
  return m;
}

glm::dvec3 EmitterMotion::originAt(double t) const {
  std::optional<sequencer::SequenceState> values;
  if (compiled_) values = sequencer::evaluate(*compiled_, t);
  glm::dmat4 m(1.0);
  for (const Level& level : levels_) {
    Transform local = level.transform;
    if (level.binding && values) {
      if (auto p = values->vector(level.id, "transform.translation")) local.translation = *p;
      if (auto q = values->rotation(level.id, "transform.rotation")) local.rotation = *q;
      if (auto s = values->vector(level.id, "transform.scale")) local.scale = *s;
      if (level.binding->path) {
        // A path gives the world position and orientation (animation.cpp).
        Transform world = local;
        world.scale = glm::dvec3(1.0);
        m = world.matrix() * glm::scale(glm::dmat4(1.0), local.scale) * m;
        return glm::dvec3(m[3]) + offset_;
      }
    } else if (level.binding) {
      for (const sequencer::Track& track : level.binding->tracks) {
        if (const auto* v = std::get_if<sequencer::VectorTrack>(&track)) {
          const auto value = sequencer::evaluate(*v, t);
          if (!value) continue;
          if (v->property == "transform.translation") local.translation = *value;
          else if (v->property == "transform.scale") local.scale = *value;
        } else if (const auto* r = std::get_if<sequencer::RotationTrack>(&track)) {
          const auto value = sequencer::evaluate(*r, t);
          if (value && r->property == "transform.rotation" && glm::length(*value) > 1e-12)
            local.rotation = glm::normalize(*value);
        }
      }
    }
    m = local.matrix() * m;
  }
  return glm::dvec3(m[3]) + offset_;
}

std::optional<particles::OriginBox> EmitterMotion::originRange(double t0, double t1) const {
  if (t1 < t0) std::swap(t0, t1);
  // The box (centre c, half extents h) of the chain's translation so far,
  // from the entity up: a parent maps x to T + R S x.
  glm::dvec3 c(0.0), h(0.0);
  for (size_t i = 0; i < levels_.size(); ++i) {
    const Level& level = levels_[i];
    glm::dvec3 tLo = level.transform.translation, tHi = tLo;
    glm::dvec3 sLo = level.transform.scale, sHi = sLo;
    glm::dquat rotation = level.transform.rotation;
    bool turns = false;
    if (level.binding) {
      // A scale track: the range the path's level below may need too.
      for (const sequencer::Track& track : level.binding->tracks)
        if (const auto* v = std::get_if<sequencer::VectorTrack>(&track); v && v->property == "transform.scale")
          if (const auto r = sequencer::valueRange(*v, t0, t1)) std::tie(sLo, sHi) = *r;
    }
    if (level.binding && level.binding->path) {
      // A path places this level anywhere on its curve (the whole curve's
      // box: its progress keys are not followed here) and turns it any way
      // (its aim): what lies below is a ball about the curve (originAt).
      const auto [lo, hi] = sequencer::PathSampler(level.binding->path->path.points).box();
      const glm::dvec3 sMax = glm::max(glm::abs(sLo), glm::abs(sHi));
      const double r = i == 0 ? 0.0 : std::max({sMax.x, sMax.y, sMax.z}) * (glm::length(c) + glm::length(h));
      const glm::dvec3 pad(r + 1e-12 * (glm::length(lo) + glm::length(hi) + r));
      return particles::OriginBox{lo - pad + offset_, hi + pad + offset_};
    }
    if (level.binding) {
      for (const sequencer::Track& track : level.binding->tracks) {
        if (const auto* v = std::get_if<sequencer::VectorTrack>(&track)) {
          const auto r = sequencer::valueRange(*v, t0, t1);
          if (!r) continue;
          if (v->property == "transform.translation") std::tie(tLo, tHi) = *r;
          else if (v->property == "transform.scale") std::tie(sLo, sHi) = *r;
        } else if (const auto* q = std::get_if<sequencer::RotationTrack>(&track)) {
          if (q->property != "transform.rotation" || q->keys.empty()) continue;
          turns = sequencer::turnsDuring(*q, t0, t1);
          // originAt's rule for the orientation a still track holds.
          const glm::dquat value = *sequencer::evaluate(*q, t0);
          if (glm::length(value) > 1e-12) rotation = glm::normalize(value);
        }
      }
    }
    const glm::dvec3 tc = 0.5 * (tLo + tHi), th = 0.5 * (tHi - tLo);
    if (i == 0) {  // the entity's own rotation and scale do not move its origin
      c = tc;
      h = th;
      continue;
    }
    if (!turns && sLo == sHi) {
      const glm::dmat3 a = glm::mat3_cast(rotation) * glm::dmat3(glm::scale(glm::dmat4(1.0), sLo));
      glm::dvec3 reach = th;
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) reach[r] += std::abs(a[k][r]) * h[k];  // glm: a[column][row]
      c = tc + a * c;
      h = reach;
    } else {
      // Turning or scaling: |R S x| <= s_max |x|, a ball about the translation.
      const glm::dvec3 sMax = glm::max(glm::abs(sLo), glm::abs(sHi));
      const double s = std::max({sMax.x, sMax.y, sMax.z});
      const double r = s * (glm::length(c) + glm::length(h));
      c = tc;
      h = th + glm::dvec3(r);
    }
  }
  // Rounding of the evaluation the box encloses (a few ulps of its size).
  h += glm::dvec3(1e-12 * (glm::length(c) + glm::length(h)));
  return particles::OriginBox{c - h + offset_, c + h + offset_};
}

bool EmitterMotion::operator==(const EmitterMotion& o) const {
  if (levels_.size() != o.levels_.size() || offset_ != o.offset_ || bool(compiled_) != bool(o.compiled_)) return false;
  for (size_t i = 0; i < levels_.size(); ++i) {
    const Level &a = levels_[i], &b = o.levels_[i];
    if (a.id != b.id || a.transform != b.transform || bool(a.binding) != bool(b.binding)) return false;
    if (a.binding && !(*a.binding == *b.binding)) return false;
  }
  // A path's aims read the rest of the sequence.
  return !compiled_ || compiled_->sequence() == o.compiled_->sequence();
}

const MeshAsset* drawMeshAsset(const SceneState& state, const std::string& name) {
  if (name.empty()) return nullptr;
  for (const auto& [id, e] : state.entities) {  // ordered by id
    if (!e.mesh || e.name != name) continue;
    const MeshAsset* a = state.findAsset(e.mesh->mesh);
    if (a && a->data && !a->data->positions.empty() && !a->data->indices.empty()) return a;
  }
  return nullptr;
}

std::string drawMeshProblem(const particles::EmitterDesc& desc) {
  return "emitter '" + desc.name + "', field 'draw_mesh': no entity '" + desc.drawMesh + "' with a mesh";
}

std::optional<PlacedBound> placedBound(const PlacedEmitter& placed, double t, ParticleWorld* world,
                                       const particles::SurfaceSampler* surface) {
  // The particles alive at t were born in [t - lifetime_max, t].
  const double t0 = t - std::max(0.0, placed.desc.lifetimeMax);
  PlacedBound out;
  out.desc = placed.desc;
  if (placed.spawn) {
    const auto [lo, hi] = placed.spawn->range(particles::spawnValues(placed.desc), t0, t);
    out.desc = particles::widenedForSpawn(placed.desc, lo, hi);
  }
  particles::BoundInputs in;
  in.moves = bool(placed.motion);
  if (placed.motion) in.birthOrigins = placed.motion->originRange(t0, t);
  if (placed.desc.shape == particles::Shape::Terrain && world) in.groundRange = world->groundRange();
  in.surface = surface;
  const std::optional<particles::ParticleBound> b = particles::particleBound(out.desc, in);
  if (!b) return std::nullopt;
  out.bound = *b;
  return out;
}

std::optional<PlacedEmitter> placedEmitter(const SceneState& state, EntityId id) {
  std::optional<particles::EmitterDesc> desc = emitterInWorld(state, id);
  if (!desc) return std::nullopt;
  return PlacedEmitter{id, std::move(*desc), EmitterMotion::of(state, id), EmitterSpawnTracks::of(state, id)};
}

std::vector<PlacedEmitter> visibleEmitters(const SceneState& state) {
  std::vector<PlacedEmitter> out;
  for (EntityId id : state.depthFirstOrder())
    if (state.effectivelyVisible(id))
      if (std::optional<PlacedEmitter> placed = placedEmitter(state, id)) out.push_back(std::move(*placed));
  return out;
}

void ParticleWorld::buildTerrain() {
  if (terrainBuilt_) return;
  terrainBuilt_ = true;
  terrainGround_ = std::make_unique<FoliageGround>(state_, false);
  const terrain::Terrain* t = terrainGround_->ground().terrain;
  if (!t) return;
  const terrain::Heightfield* hf = &t->height;
  // Off the grid or over a hole there is nothing to meet: far below.
  Boxed<particles::HeightFieldCollider> b;
  b.collider = std::make_unique<particles::HeightFieldCollider>(
      [hf](double x, double y) {
        const auto p = foliage::terrainSurface(*hf, {x, y});
        return p ? p->position.z : -1e30;
      },
      [hf](double x, double y) {
        const auto p = foliage::terrainSurface(*hf, {x, y});
        return p ? p->normal : glm::dvec3(0.0, 0.0, 1.0);
      },
      std::min(0.25, 0.5 * std::min(hf->spacing().x, hf->spacing().y)));
  // Met over its footprint from its highest sample down: a particle below
  // the surface is met where it is (HeightFieldCollider).
  const terrain::HeightRange r = hf->range();
  b.lo = {hf->origin().x, hf->origin().y, -std::numeric_limits<double>::infinity()};
  b.hi = {hf->origin().x + hf->sizeMetres().x, hf->origin().y + hf->sizeMetres().y, hf->origin().z + double(r.max)};
  terrain_ = std::move(b);
}

const particles::HeightFieldCollider* ParticleWorld::terrainCollider() {
  buildTerrain();
  return terrain_ ? terrain_->collider.get() : nullptr;
}

const terrain::Heightfield* ParticleWorld::terrainHeights() {
  buildTerrain();
  const terrain::Terrain* t = terrainGround_ ? terrainGround_->ground().terrain : nullptr;
  return t ? &t->height : nullptr;
}

std::optional<std::pair<double, double>> ParticleWorld::groundRange() {
  buildTerrain();
  const terrain::Terrain* t = terrainGround_ ? terrainGround_->ground().terrain : nullptr;
  if (!t) return std::nullopt;
  const terrain::HeightRange r = t->height.range();
  const double z = t->height.origin().z;
  return std::make_pair(z + double(r.min), z + double(r.max));
}

void ParticleWorld::buildMeshes() {
  if (meshesBuilt_) return;
  meshesBuilt_ = true;
  meshGround_ = std::make_unique<FoliageGround>(state_, true);
  for (const foliage::MeshGround* m : meshGround_->ground().meshes) {
    Boxed<particles::RaycastCollider> b;
    b.lo = glm::dvec3(std::numeric_limits<double>::infinity());
    b.hi = -b.lo;
    const mesh::MeshData& md = m->mesh();
    for (const glm::vec3& p : md.positions) {
      b.lo = glm::min(b.lo, md.origin + glm::dvec3(p));
      b.hi = glm::max(b.hi, md.origin + glm::dvec3(p));
    }
    b.collider = std::make_unique<particles::RaycastCollider>(
        [m](const glm::dvec3& from, const glm::dvec3& to) -> std::optional<particles::Hit> {
          const glm::dvec3 d = to - from;
          const double len = glm::length(d);
          if (!(len > 0.0)) return std::nullopt;
          const auto p = m->raycast(from, d / len, len);
          if (!p) return std::nullopt;
          particles::Hit h;
          h.point = p->position;
          h.fraction = std::clamp(glm::length(p->position - from) / len, 0.0, 1.0);
          h.normal = glm::dot(p->normal, from - p->position) < 0.0 ? -p->normal : p->normal;
          return h;
        });
    meshes_.push_back(std::move(b));
  }
}

bool PlacedEmitter::sameAs(const PlacedEmitter& o) const {
  auto same = [](const auto& a, const auto& b) { return a == b || (a && b && *a == *b); };
  return entity == o.entity && desc == o.desc && same(motion, o.motion) && same(spawn, o.spawn);
}

void addTimeInputs(const PlacedEmitter& placed, particles::EvaluatorInputs& in) {
  if (placed.motion) in.originAt = [m = placed.motion](double t) { return m->originAt(t); };
  if (placed.spawn) in.spawnAt = [s = placed.spawn](double birth, particles::SpawnValues& v) { s->apply(birth, v); };
}

particles::EvaluatorInputs ParticleWorld::inputs(const particles::EmitterDesc& desc, bool colliders, bool fixed) {
  particles::EvaluatorInputs in;
  if (desc.shape == particles::Shape::Terrain) {
    buildTerrain();
    in.ground = terrain_ ? terrain_->collider.get() : nullptr;
  }
  if (desc.shape == particles::Shape::Mesh) {
    for (EntityId id : state_.depthFirstOrder()) {
      const Entity* e = state_.find(id);
      if (!e || e->name != desc.mesh || !e->mesh || !state_.effectivelyVisible(id)) continue;
      const MeshAsset* a = state_.findAsset(e->mesh->mesh);
      if (!a || !a->data || a->data->triangleCount() == 0) continue;
      const mesh::MeshData w = worldMesh(*a->data, state_.worldMatrix(id));
      const glm::dvec3 base = w.origin - desc.origin;  // emitter-relative, formed in double
      std::vector<glm::dvec3> corners;
      corners.reserve(w.indices.size());
      for (uint32_t i : w.indices) corners.push_back(base + glm::dvec3(w.positions[i]));
      surfaces_.push_back(std::make_unique<particles::TriangleSurface>(std::move(corners)));
      if (!surfaces_.back()->empty()) in.surface = surfaces_.back().get();
      break;
    }
  }
  if (colliders && desc.collision != particles::CollisionMode::None) {
    buildTerrain();
    buildMeshes();
    // Where its particles can be (world), widened by 1 m; none: everywhere.
    std::optional<particles::ParticleBound> reach;
    if (fixed) {
      particles::BoundInputs b;
      b.surface = in.surface;
      if (desc.shape == particles::Shape::Terrain) b.groundRange = groundRange();
      reach = particles::particleBound(desc, b);
    }
    auto mayMeet = [&](const glm::dvec3& lo, const glm::dvec3& hi) {
      if (!reach) return true;
      const glm::dvec3 c = desc.origin + reach->centre;
      const glm::dvec3 nearest = glm::clamp(c, lo, hi);
      return glm::length(nearest - c) <= reach->radius + 1.0;
    };
    if (terrain_ && mayMeet(terrain_->lo, terrain_->hi)) in.colliders.push_back(terrain_->collider.get());
    for (const auto& m : meshes_)
      if (mayMeet(m.lo, m.hi)) in.colliders.push_back(m.collider.get());
  }
  return in;
}

std::optional<particles::Evaluator> ParticleWorld::evaluator(const particles::EmitterDesc& desc, std::string& error,
                                                             bool colliders) {
  return particles::Evaluator::create(desc, inputs(desc, colliders), error);
}

std::optional<particles::Evaluator> ParticleWorld::evaluator(const PlacedEmitter& placed, std::string& error,
                                                             bool colliders) {
  particles::EvaluatorInputs in = inputs(placed.desc, colliders, !placed.motion && !placed.spawn);
  addTimeInputs(placed, in);
  return particles::Evaluator::create(placed.desc, std::move(in), error);
}

std::vector<EmitterCount> liveParticleCounts(const SceneState& state, double t) {
  std::vector<EmitterCount> out;
  const std::vector<PlacedEmitter> emitters = visibleEmitters(state);
  if (emitters.empty()) return out;
  ParticleWorld world(state);
  for (const PlacedEmitter& p : emitters) {
    EmitterCount c;
    c.entity = p.entity;
    c.name = p.desc.name;
    if (auto ev = world.evaluator(p.desc, c.error, false)) c.live = ev->liveCount(t, &c.estimated);
    if (c.error.empty() && !p.desc.drawMesh.empty() && !drawMeshAsset(state, p.desc.drawMesh))
      c.error = drawMeshProblem(p.desc);  // counted, but drawn as nothing
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace hs::scene
