#include "scene/particle_world.h"

#include <cmath>

#include "foliage/surface.h"

namespace hs::scene {

std::optional<particles::EmitterDesc> emitterInWorld(const SceneState& state, EntityId id) {
  const Entity* e = state.find(id);
  if (!e || !e->particles) return std::nullopt;
  particles::EmitterDesc d = e->particles->desc;
  d.origin += glm::dvec3(state.worldMatrix(id)[3]);
  d.name = e->name;
  return d;
}

std::vector<PlacedEmitter> visibleEmitters(const SceneState& state) {
  std::vector<PlacedEmitter> out;
  for (EntityId id : state.depthFirstOrder()) {
    const Entity* e = state.find(id);
    if (!e || !e->particles || !state.effectivelyVisible(id)) continue;
    out.push_back({id, *emitterInWorld(state, id)});
  }
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
  terrain_ = std::make_unique<particles::HeightFieldCollider>(
      [hf](double x, double y) {
        const auto p = foliage::terrainSurface(*hf, {x, y});
        return p ? p->position.z : -1e30;
      },
      [hf](double x, double y) {
        const auto p = foliage::terrainSurface(*hf, {x, y});
        return p ? p->normal : glm::dvec3(0.0, 0.0, 1.0);
      },
      std::min(0.25, 0.5 * std::min(hf->spacing().x, hf->spacing().y)));
}

void ParticleWorld::buildMeshes() {
  if (meshesBuilt_) return;
  meshesBuilt_ = true;
  meshGround_ = std::make_unique<FoliageGround>(state_, true);
  for (const foliage::MeshGround* m : meshGround_->ground().meshes)
    meshes_.push_back(std::make_unique<particles::RaycastCollider>(
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
        }));
}

particles::EvaluatorInputs ParticleWorld::inputs(const particles::EmitterDesc& desc, bool colliders) {
  particles::EvaluatorInputs in;
  if (colliders && desc.collision != particles::CollisionMode::None) {
    buildTerrain();
    buildMeshes();
    if (terrain_) in.colliders.push_back(terrain_.get());
    for (const auto& m : meshes_) in.colliders.push_back(m.get());
  }
  if (desc.shape == particles::Shape::Terrain) {
    buildTerrain();
    in.ground = terrain_.get();
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
  return in;
}

std::optional<particles::Evaluator> ParticleWorld::evaluator(const particles::EmitterDesc& desc, std::string& error,
                                                             bool colliders) {
  return particles::Evaluator::create(desc, inputs(desc, colliders), error);
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
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace hs::scene
