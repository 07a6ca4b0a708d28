#include "render/particle_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "particles/rng.h"

namespace hs::render {
namespace {

// The most types and cells an instance can name (GpuInstance::typeAndCell).
constexpr size_t kMaxEmitters = 65536;

}  // namespace

glm::dvec3 meshParticleAxis(uint32_t variant) {
  // Two more numbers from the particle's 32 random bits (the constants only
  // tell the two hashes apart), then the area-preserving map of the unit
  // square onto the sphere: z uniform in [-1, 1), the azimuth in [0, 2 pi).
  const double u = particles::unitFromHash(particles::hashU32(variant ^ 0x6A09E667u));
  const double v = particles::unitFromHash(particles::hashU32(variant ^ 0xBB67AE85u));
  const double z = 1.0 - 2.0 * u;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * 3.14159265358979323846 * v;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

double meshLargestExtent(const mesh::Bounds& b) {
  if (b.empty) return 0.0;
  const glm::dvec3 e = glm::dvec3(b.max) - glm::dvec3(b.min);
  return std::max({e.x, e.y, e.z});
}

MeshParticlePose meshParticlePose(const mesh::Bounds& level0, const glm::dvec3& position, double size,
                                  double rotationDeg, uint32_t variant) {
  MeshParticlePose pose;
  pose.rotation = glm::angleAxis(glm::radians(rotationDeg), meshParticleAxis(variant));
  const double extent = meshLargestExtent(level0);
  pose.scale = extent > 0.0 && std::isfinite(extent) ? size / extent : 0.0;
  // The bounds' centre onto the particle: v = centre lands on `position`.
  pose.offset = position - pose.rotation * (pose.scale * glm::dvec3(level0.center()));
  return pose;
}

MeshParticleSource::MeshParticleSource() : inner_("particle_meshes", InstancedSource::Culling::Cpu) {}
MeshParticleSource::~MeshParticleSource() = default;

void MeshParticleSource::clear() {
  next_ = InstanceSet{};
  firstIds_.clear();
}

const mesh::Bounds& MeshParticleSource::boundsOf(const scene::MeshAsset& asset) {
  auto& [data, bounds] = bounds_[asset.id];
  if (data != asset.data) {
    data = asset.data;
    bounds = data->bounds();
  }
  return bounds;
}

size_t MeshParticleSource::add(scene::EntityId entity, const particles::EmitterDesc& desc,
                               const scene::MeshAsset& asset, const particles::Frame& frame, std::string& error) {
  if (next_.types.size() >= kMaxEmitters) {
    error = "emitter '" + desc.name + "', field 'draw_mesh': more than " + std::to_string(kMaxEmitters) +
            " emitters draw meshes in this frame; this one is left out";
    return 0;
  }
  const mesh::Bounds& bounds = boundsOf(asset);
  const uint16_t index = uint16_t(next_.types.size());
  // A particle is no foliage: drawn at any distance, never swaying, casting shadows.
  next_.types.push_back({.mesh = asset.id, .cullDistance = 0.0f, .fadeLength = 0.0f, .windResponse = 0.0f,
                         .castShadows = true});
  next_.cells.push_back(desc.origin);
  firstIds_.push_back({uint32_t(next_.instances.size()), entity});
  // Positions relative to the emitter's origin (the cell) and each one's
  // random bits, as the sprites' records have them.
  const std::vector<particles::PackedParticle> packed = particles::packFrame(frame, desc.origin, desc.origin, desc.seed);
  size_t added = 0;
  for (size_t i = 0; i < frame.particles.size(); ++i) {
    const particles::Particle& p = frame.particles[i];
    if (!(p.size > 0.0)) continue;
    const MeshParticlePose pose = meshParticlePose(bounds, p.position, p.size, p.rotationDeg, packed[i].variant);
    if (!(pose.scale > 0.0) || !std::isfinite(pose.scale)) continue;
    next_.instances.push_back(packInstance(glm::vec3(pose.offset), glm::quat(pose.rotation), float(pose.scale), index,
                                           index, uint32_t(next_.instances.size())));
    ++added;
  }
  return added;
}

size_t MeshParticleSource::commit() {
  const size_t n = next_.instances.size();
  pickRanges_ = firstIds_;
  next_.entity = scene::kNoEntity;  // picked() names each particle's emitter
  inner_.setInstances(std::move(next_));
  clear();
  return n;
}

PickedItem MeshParticleSource::picked(uint32_t k) const {
  // The last emitter whose first id is at or before k.
  auto it = std::upper_bound(pickRanges_.begin(), pickRanges_.end(), k,
                             [](uint32_t id, const std::pair<uint32_t, scene::EntityId>& r) { return id < r.first; });
  if (it == pickRanges_.begin()) return {};
  return {std::prev(it)->second, UINT32_MAX};
}

}  // namespace hs::render
