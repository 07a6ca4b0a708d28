#pragma once
// Ambient occlusion against an independent reference (test_ao_render,
// bench_ao): a small scene (a floor, a sphere resting on it, a smaller one
// beside it, a wall behind) lit by the ambient term only, so the HDR image
// with AO divided by the one without is the AO visibility the renderer
// applied; and the same visibility ray cast on the CPU through every
// triangle of the scene (meshproc's BVH): from each pixel's position (the
// renderer's own depth buffer), cosine-weighted rays in the hemisphere of
// the true surface normal (the nearest triangle's), a ray occluded when a
// triangle lies within the AO radius. Header-only; needs hs_render,
// hs_meshproc and hs_core.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/parallel.h"
#include "look_from.h"
#include "mesh/primitives.h"
#include "meshproc/closest_point_bvh.h"
#include "render/offscreen_renderer.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"

namespace hs::test {

struct AoScene {
  scene::SceneState state;
  render::RenderView view;
  mesh::MeshData world;  // every triangle, world coordinates
};

inline AoScene aoScene(int width, int height) {
  AoScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.sky = scene::SkyModel::Gradient;
  s.settings.ambientIntensity = 1.0f;
  s.settings.aoStrength = 1.0f;
  s.settings.aoResolution = scene::AoResolution::Full;
  scene::Material grey;
  grey.baseColor = glm::vec3(0.6f);
  grey.model = scene::LightingModel::Lambert;
  grey.twoSided = true;
  grey.id = 1;
  grey.name = "grey";
  s.materials.emplace(grey.id, grey);
  auto add = [&](mesh::MeshData m, glm::dvec3 at, glm::dvec3 euler, double scale) {
    scene::MeshAsset a;
    a.id = s.maxAssetId() + 1;
    a.name = "shape";
    a.contentHash = mesh::contentHash(m);
    a.data = std::make_shared<const mesh::MeshData>(std::move(m));
    a.materialSlots.assign(scene::materialSlotCount(*a.data), grey.id);
    scene::Entity e;
    e.id = s.maxEntityId() + 1;
    e.name = "shape";
    e.mesh = scene::MeshInstance{a.id};
    e.transform.translation = at;
    e.transform.rotation = scene::fromEulerDegrees(euler);
    e.transform.scale = glm::dvec3(scale);
    s.roots.push_back(e.id);
    s.entities.emplace(e.id, e);
    const glm::dmat4 w = s.worldMatrix(e.id);
    const uint32_t base = uint32_t(out.world.positions.size());
    for (const glm::vec3& p : a.data->positions) out.world.positions.push_back(glm::vec3(w * glm::dvec4(glm::dvec3(p), 1.0)));
    for (uint32_t i : a.data->indices) out.world.indices.push_back(base + i);
    s.assets.emplace(a.id, std::move(a));
  };
  add(mesh::gridPlane(20.0f, 8), {0, 0, 0}, {0, 0, 0}, 1.0);
  add(mesh::uvSphere(1.0f, 64, 32), {0, 0, 1.0}, {0, 0, 0}, 1.0);
  add(mesh::uvSphere(1.0f, 48, 24), {1.9, 0.9, 0.6}, {0, 0, 0}, 0.6);
  add(mesh::gridPlane(8.0f, 4), {0, 2.8, 4.0}, {90, 0, 0}, 1.0);  // a wall standing on the floor
  out.world.submeshes.push_back({0, uint32_t(out.world.indices.size()), -1});
  out.view.width = width;
  out.view.height = height;
  out.view.fovY = glm::radians(50.0);
  out.view.eye = {1.2, -4.5, 2.6};
  out.view.orientation = lookFrom(out.view.eye, {0.2, 1.0, 0.5}).rotation;
  return out;
}

// The renderer's AO visibility per pixel (top row first; -1 where nothing
// or too little ambient light was drawn) and its depth (bottom row first).
struct RenderedAo {
  std::vector<float> visibility;
  std::vector<float> depth;
  render::FrameStats stats;  // the AO frame's (passTimings: the ao pass's GPU time)
};

inline RenderedAo renderAo(render::OffscreenRenderer& r, const AoScene& sc, scene::AmbientOcclusion ao, float radius,
                           scene::AoResolution resolution = scene::AoResolution::Full) {
  RenderedAo out;
  scene::SceneState s = sc.state;
  s.settings.ao = scene::AmbientOcclusion::Off;
  render::RenderOptions o;
  o.keepDepth = true;
  const hs::Image open = r.render(s, sc.view, true, nullptr, o);
  out.depth.resize(size_t(sc.view.width) * size_t(sc.view.height));
  r.renderer().readDepth(out.depth.data());
  s.settings.ao = ao;
  s.settings.aoRadius = radius;
  s.settings.aoResolution = resolution;
  render::RenderOptions timed;
  timed.passTimings = true;
  const hs::Image occluded = r.render(s, sc.view, true, &out.stats, timed);
  out.visibility.assign(out.depth.size(), -1.0f);
  for (size_t i = 0; i < out.visibility.size() && open.isFloat() && occluded.isFloat(); ++i) {
    const float a = open.rgbaF[i * 4 + 1], b = occluded.rgbaF[i * 4 + 1];
    if (a > 1e-3f) out.visibility[i] = b / a;
  }
  return out;
}

// The ray-cast visibility per pixel (top row first, -1 for the sky), with
// `rays` cosine-weighted rays (a stratified grid, rounded to a square).
inline std::vector<float> rayCastAo(const AoScene& sc, const std::vector<float>& depth, double radius, int rays) {
  const render::RenderView& view = sc.view;
  const mesh::ClosestPointBvh bvh(sc.world);
  const glm::dmat4 inv = glm::inverse(view.projection() * glm::dmat4(view.viewRotation()));
  const int side = std::max(1, int(std::lround(std::sqrt(double(rays)))));
  std::vector<float> out(depth.size(), -1.0f);
  parallelFor(view.height, 0, 1, [&](int64_t y0, int64_t y1) {
    uint32_t hint = UINT32_MAX;
    for (int64_t y = y0; y < y1; ++y)
      for (int x = 0; x < view.width; ++x) {
        const float d = depth[size_t(view.height - 1 - y) * size_t(view.width) + size_t(x)];
        if (d <= 0.0f) continue;
        const glm::dvec4 e = inv * glm::dvec4((x + 0.5) / view.width * 2.0 - 1.0, 1.0 - (y + 0.5) / view.height * 2.0,
                                              double(d), 1.0);
        const glm::dvec3 p = view.eye + glm::dvec3(e) / e.w;
        const mesh::ClosestPointBvh::Hit hit = bvh.closest(p, hint);
        if (!hit.found()) continue;
        hint = hit.face;
        const glm::dvec3 a(sc.world.positions[sc.world.indices[hit.face * 3]]);
        const glm::dvec3 b(sc.world.positions[sc.world.indices[hit.face * 3 + 1]]);
        const glm::dvec3 c(sc.world.positions[sc.world.indices[hit.face * 3 + 2]]);
        glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        if (glm::dot(n, view.eye - hit.point) < 0.0) n = -n;  // two-sided: the side the eye sees
        const glm::dvec3 helper = std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
        const glm::dvec3 t = glm::normalize(glm::cross(helper, n)), bt = glm::cross(n, t);
        const glm::dvec3 origin = hit.point + n * 1e-4;
        int blocked = 0;
        for (int i = 0; i < side; ++i)
          for (int j = 0; j < side; ++j) {
            // Malley: uniform on the disc, lifted to the hemisphere.
            const double u = (i + 0.5) / side, v = (j + 0.5) / side;
            const double rr = std::sqrt(u), phi = 6.283185307179586 * v;
            const glm::dvec3 dir = t * (rr * std::cos(phi)) + bt * (rr * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1.0 - u));
            if (bvh.occluded(origin, dir, 1e-4, radius)) ++blocked;
          }
        out[size_t(y) * size_t(view.width) + size_t(x)] = 1.0f - float(blocked) / float(side * side);
      }
  });
  return out;
}

struct AoError {
  size_t pixels = 0;
  double mean = 0.0, p95 = 0.0;  // |renderer - reference|
  double bias = 0.0;             // mean of renderer - reference
  double occludedShare = 0.0;    // share of pixels the reference has below 0.9
};

inline AoError compareAo(const std::vector<float>& measured, const std::vector<float>& reference) {
  AoError e;
  std::vector<double> errs;
  size_t occluded = 0;
  for (size_t i = 0; i < measured.size(); ++i) {
    if (measured[i] < 0.0f || reference[i] < 0.0f) continue;
    const double d = double(measured[i]) - double(reference[i]);
    errs.push_back(std::abs(d));
    e.bias += d;
    if (reference[i] < 0.9f) ++occluded;
  }
  e.pixels = errs.size();
  if (errs.empty()) return e;
  for (double x : errs) e.mean += x;
  e.mean /= double(errs.size());
  e.bias /= double(errs.size());
  std::sort(errs.begin(), errs.end());
  e.p95 = errs[std::min(errs.size() - 1, size_t(0.95 * double(errs.size())))];
  e.occludedShare = double(occluded) / double(errs.size());
  return e;
}

}  // namespace hs::test
