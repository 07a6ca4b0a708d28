// bench_shadows: the sun's cascaded shadow maps against a CPU ray cast.
//
// A test scene (a 1 x 1 km hill terrain as a mesh, 193,548 triangles;
// spheres, posts and floating slabs within 120 m of the camera; a sun 15
// degrees up, shadow distance 1 km) at 1920x1080. The reference: each
// pixel's world position from the depth buffer, a ray towards the sun
// through every triangle of the scene (meshproc's BVH occlusion query).
// The renderer's state per pixel: the HDR image with shadows divided by the
// one without (ambient off, so the sun is all the light); lit at 0.5 or
// more. Pixels the sun barely reaches (facing away, grazing) are left out.
//
// For each shadow-map resolution (512..4096) and cascade count (1..4): the
// share of pixels whose state differs from the reference, next to the
// shadow pass's GPU time (timestamps, fenced) and the frame time; then the
// cascade texel size on screen at 10 m, 100 m, 1 km and 10 km for the
// presets over 30 km; then a stereo pair's time over a mono frame's with
// shadows on (bench_frame measured 2.04x without).
//
// Then the same for a spot light (high over the first shapes, a 90-degree
// cone along the view) and a point light (low among them), each alone with
// the sun hidden: the share of pixels differing from a ray cast towards the
// light's position against the light's own map size (a cube: per face),
// next to the `shadow_local` pass's GPU time.
//
//   bench_shadows [--frames N] [--size WxH] [--plot FILE.png] [--quick]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "bench/common/height_grid.h"
#include "bench/common/plot.h"
#include "mesh/primitives.h"
#include "meshproc/closest_point_bvh.h"
#include "render/offscreen_renderer.h"
#include "render/shadow_cascades.h"
#include "tests/common/look_from.h"

using namespace hs;
using bench::median;

namespace {

struct Options {
  int frames = 3, width = 1920, height = 1080;
  std::string plot;
  bool quick = false;
};

struct BenchScene {
  scene::SceneState state;
  mesh::MeshData world;  // every triangle in world coordinates
};

std::shared_ptr<const mesh::MeshData> hills() {
  return bench::heightGridMesh(312, 1000.0f, [](float x, float y) {
    return 9.0f * std::sin(x * 0.021f) * std::cos(y * 0.017f) + 4.0f * std::sin(x * 0.07f + y * 0.05f);
  });
}

double hillHeight(double x, double y) {
  const float fx = float(x), fy = float(y);  // as hills() computes it
  return double(9.0f * std::sin(fx * 0.021f) * std::cos(fy * 0.017f) + 4.0f * std::sin(fx * 0.07f + fy * 0.05f));
}

BenchScene buildScene() {
  BenchScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.shadows = true;
  s.settings.shadowQuality = scene::ShadowQuality::Custom;
  s.settings.shadowDistance = 1000.0;
  auto add = [&](std::shared_ptr<const mesh::MeshData> m, glm::dvec3 at, glm::dvec3 scale) {
    const uint32_t base = uint32_t(out.world.positions.size());
    for (const glm::vec3& p : m->positions) out.world.positions.push_back(glm::vec3(glm::dvec3(p) * scale + at));
    for (uint32_t i : m->indices) out.world.indices.push_back(base + i);
    scene::MeshAsset a;
    a.id = s.maxAssetId() + 1;
    a.name = "shape";
    a.contentHash = mesh::contentHash(*m);
    a.data = std::move(m);
    const scene::AssetId id = a.id;
    s.assets.emplace(id, std::move(a));
    scene::Entity e;
    e.id = s.maxEntityId() + 1;
    e.name = "shape";
    e.mesh = scene::MeshInstance{id};
    e.transform.translation = at;
    e.transform.scale = scale;
    s.roots.push_back(e.id);
    s.entities.emplace(e.id, e);
  };
  add(hills(), {0, 0, 0}, {1, 1, 1});
  auto sphere = std::make_shared<const mesh::MeshData>(mesh::uvSphere(1.0f, 48, 24));
  auto slab = std::make_shared<const mesh::MeshData>(mesh::gridPlane(1.0f, 1));
  // Spheres and posts along the view, floating slabs (detached shadows).
  for (int i = 0; i < 8; ++i) {
    const double y = 10.0 + 14.0 * i, x = (i % 2 ? 6.0 : -7.0) + 2.0 * std::sin(i);
    const double r = 1.0 + 0.4 * (i % 3);
    add(sphere, {x, y, hillHeight(x, y) + r * 0.8}, {r, r, r});
    const double px = -x * 0.6, py = y + 6.0;
    add(sphere, {px, py, hillHeight(px, py) + 2.0}, {0.25, 0.25, 2.5});  // a post
  }
  for (int i = 0; i < 3; ++i) {
    const double x = -4.0 + 5.0 * i, y = 30.0 + 25.0 * i;
    add(slab, {x, y, hillHeight(x, y) + 3.0}, {4, 4, 1});
  }
  out.world.submeshes.push_back({0, uint32_t(out.world.indices.size()), -1});
  scene::Entity sun;
  sun.id = s.maxEntityId() + 1;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.light->castsShadows = true;
  sun.transform.rotation = scene::fromEulerDegrees({75.0, 0, 200});  // 15 degrees up
  s.roots.push_back(sun.id);
  s.entities.emplace(sun.id, sun);
  scene::Entity cam;
  cam.id = s.maxEntityId() + 1;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 50.0;
  cam.transform = test::lookFrom({0, -25, hillHeight(0, -25) + 30.0}, {0, 55, 0});
  s.roots.push_back(cam.id);
  s.entities.emplace(cam.id, cam);
  return out;
}

// Per pixel: -1 (not counted) or the reference state (0 lit, 1 shadowed), top row first.
struct Reference {
  std::vector<float> unshadowed;  // green channel, linear HDR
  std::vector<int8_t> shadowed;
  size_t counted = 0, refShadowed = 0;
};

// The light the reference rays go to: the sun (a direction) or a spot or
// point light (a position; rays end there).
struct RayTarget {
  bool directional = true;
  glm::dvec3 v{0, 0, 1};
};

RayTarget sunTarget(const scene::SceneState& s) {
  for (const auto& [id, e] : s.entities)
    if (e.light && e.light->type == scene::Light::Type::Sun) return {true, glm::dvec3(s.worldMatrix(id) * glm::dvec4(0, 0, 1, 0))};
  return {};
}

Reference reference(render::OffscreenRenderer& r, const BenchScene& sc, const scene::SceneState& state,
                    const RayTarget& light, const render::RenderView& view) {
  scene::SceneState s = state;
  s.settings.shadows = false;
  s.settings.ambientIntensity = 0.0f;
  render::RenderOptions o;
  o.keepDepth = true;
  const hs::Image lit = r.render(s, view, true, nullptr, o);
  std::vector<float> depth(size_t(view.width) * size_t(view.height));
  r.renderer().readDepth(depth.data());
  Reference ref{std::vector<float>(depth.size(), 0.0f), std::vector<int8_t>(depth.size(), int8_t(-1)), 0, 0};
  float maxLit = 0.0f;
  for (size_t i = 0; i < depth.size(); ++i) maxLit = std::max(maxLit, ref.unshadowed[i] = lit.rgbaF[i * 4 + 1]);
  const mesh::ClosestPointBvh bvh(sc.world);
  const glm::dmat4 inv = glm::inverse(view.projection() * glm::dmat4(view.viewRotation()));
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const size_t i = size_t(y) * size_t(view.width) + size_t(x);
      const float d = depth[size_t(view.height - 1 - y) * size_t(view.width) + size_t(x)];
      if (d <= 0.0f || ref.unshadowed[i] < 0.01f * maxLit) continue;
      const glm::dvec4 e = inv * glm::dvec4((x + 0.5) / view.width * 2.0 - 1.0, 1.0 - (y + 0.5) / view.height * 2.0,
                                            double(d), 1.0);
      const glm::dvec3 p = view.eye + glm::dvec3(e) / e.w;
      // Starting 3 cm towards the light: the depth buffer's position error.
      if (light.directional) {
        ref.shadowed[i] = int8_t(bvh.occluded(p, light.v, 0.03, 1e5));
      } else {
        const double dist = glm::length(light.v - p);
        ref.shadowed[i] = int8_t(bvh.occluded(p, (light.v - p) / dist, 0.03, dist - 0.03));
      }
      ++ref.counted;
      ref.refShadowed += size_t(ref.shadowed[i]);
    }
  return ref;
}

struct Row {
  int resolution = 0, cascades = 0;
  double differPercent = 0.0, shadowedPercent = 0.0, passMs = 0.0, frameMs = 0.0;
};

// `s` with shadows at `resolution` (the sun's cascades: settings; a spot or
// point light: its own shadow_resolution), timed on pass `passName`.
Row measure(render::OffscreenRenderer& r, scene::SceneState s, const render::RenderView& view, const Reference& ref,
            int resolution, int cascades, const std::string& passName, const Options& o) {
  s.settings.ambientIntensity = 0.0f;
  s.settings.shadowResolution = resolution;
  s.settings.shadowCascades = cascades;
  for (auto& [id, e] : s.entities)
    if (e.light && e.light->type != scene::Light::Type::Sun) e.light->shadowResolution = resolution;
  Row row;
  row.resolution = resolution;
  row.cascades = cascades;
  const hs::Image img = r.render(s, view, true);
  size_t differ = 0, shadowed = 0;
  for (size_t i = 0; i < ref.shadowed.size(); ++i) {
    if (ref.shadowed[i] < 0) continue;
    const bool sh = img.rgbaF[i * 4 + 1] < 0.5f * ref.unshadowed[i];
    shadowed += sh;
    differ += sh != bool(ref.shadowed[i]);
  }
  row.differPercent = 100.0 * double(differ) / double(ref.counted);
  row.shadowedPercent = 100.0 * double(shadowed) / double(ref.counted);
  std::vector<double> pass, frame;
  render::RenderOptions timed;
  timed.passTimings = true;
  for (int f = 0; f < o.frames; ++f) {
    const render::FrameStats st = r.renderOnly(s, view, timed);
    for (const render::PassStats& p : st.passes)
      if (p.name == passName) pass.push_back(p.gpuMs);
    const double t0 = bench::nowSeconds();
    r.renderOnly(s, view);
    frame.push_back(1000.0 * (bench::nowSeconds() - t0));
  }
  row.passMs = median(pass);
  row.frameMs = median(frame);
  return row;
}

}  // namespace

// No QCoreApplication: the plot (bench/common/plot.h) starts the
// QGuiApplication it needs, which cannot coexist with a core one.
int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each table line as it is measured, also into a file
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) o.frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--size" && i + 1 < argc) std::sscanf(argv[++i], "%dx%d", &o.width, &o.height);
    else if (a == "--plot" && i + 1 < argc) o.plot = argv[++i];
    else if (a == "--quick") o.quick = true;
    else {
      std::fprintf(stderr, "usage: bench_shadows [--frames N] [--size WxH] [--plot FILE.png] [--quick]\n");
      return 2;
    }
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_shadows: %s\n", error.c_str());
    return 1;
  }
  const BenchScene sc = buildScene();
  const render::RenderView view = render::viewFromCamera(sc.state, sc.state.cameras().front(), o.width, o.height);
  std::printf("bench_shadows at %dx%d, %s; %zu scene triangles; %s\n", o.width, o.height, r.glDescription().c_str(),
              sc.world.triangleCount(), bench::loadAverageLine().c_str());
  const double t0 = bench::nowSeconds();
  const Reference ref = reference(r, sc, sc.state, sunTarget(sc.state), view);
  std::printf("CPU ray cast (meshproc BVH, one thread): %zu pixels counted, %.1f%% shadowed, %.1f s\n\n", ref.counted,
              100.0 * double(ref.refShadowed) / double(ref.counted), bench::nowSeconds() - t0);

  std::vector<Row> rows;
  const std::vector<int> resolutions = o.quick ? std::vector<int>{512, 2048} : std::vector<int>{512, 1024, 2048, 4096};
  std::printf("| map size | cascades | pixels differing from the ray cast | shadowed (ray cast %.1f%%) | shadow pass GPU ms | frame ms |\n",
              100.0 * double(ref.refShadowed) / double(ref.counted));
  std::printf("| ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (int res : resolutions)
    for (int c = 1; c <= 4; ++c) {
      const Row row = measure(r, sc.state, view, ref, res, c, "shadow_sun", o);
      rows.push_back(row);
      std::printf("| %d | %d | %.2f%% | %.1f%% | %.1f | %.0f |\n", res, c, row.differPercent, row.shadowedPercent,
                  row.passMs, row.frameMs);
      std::fflush(stdout);
    }

  // Spot and point lights (docs/rendering.md "Shadows", "Spot and point
  // lights"): the sun hidden, one light casting, against its own map size
  // (a cube: per face), the same reference towards the light's position.
  std::vector<Row> spotRows, pointRows;
  for (scene::Light::Type type : {scene::Light::Type::Spot, scene::Light::Type::Point}) {
    const bool spot = type == scene::Light::Type::Spot;
    scene::SceneState s = sc.state;
    for (auto& [id, e] : s.entities)
      if (e.light) e.visible = false;
    scene::Entity l;
    l.id = s.maxEntityId() + 1;
    l.name = spot ? "Spot" : "Point";
    l.light = scene::Light{};
    l.light->type = type;
    l.light->intensity = spot ? 5.0e7f : 2.0e7f;
    l.light->range = spot ? 150.0f : 60.0f;
    l.light->innerConeDeg = 70.0f;
    l.light->outerConeDeg = 90.0f;
    l.light->castsShadows = true;
    // The spot high over the first spheres and posts, looking along the
    // view; the point light low among them.
    const glm::dvec3 at = spot ? glm::dvec3(0, 5, hillHeight(0, 5) + 30.0) : glm::dvec3(0, 38, hillHeight(0, 38) + 5.0);
    if (spot) l.transform = test::lookFrom(at, glm::dvec3(0, 45, hillHeight(0, 45)));
    l.transform.translation = at;
    s.roots.push_back(l.id);
    s.entities.emplace(l.id, l);
    const double tr = bench::nowSeconds();
    const Reference lref = reference(r, sc, s, {false, at}, view);
    std::printf("\n%s light alone: %zu pixels counted, ray cast %.1f%% shadowed (%.1f s)\n\n"
                "| %s | pixels differing from the ray cast | shadowed | shadow pass GPU ms | frame ms |\n"
                "| ---: | ---: | ---: | ---: | ---: |\n",
                spot ? "Spot" : "Point", lref.counted, 100.0 * double(lref.refShadowed) / double(std::max<size_t>(lref.counted, 1)),
                bench::nowSeconds() - tr, spot ? "map size" : "face size");
    const std::vector<int> sizes = o.quick ? std::vector<int>{512, 2048} : std::vector<int>{256, 512, 1024, 2048, 4096};
    for (int res : sizes) {
      const Row row = measure(r, s, view, lref, res, 1, "shadow_local", o);
      (spot ? spotRows : pointRows).push_back(row);
      std::printf("| %d | %.2f%% | %.1f%% | %.1f | %.0f |\n", res, row.differPercent, row.shadowedPercent, row.passMs,
                  row.frameMs);
    }
  }
  std::printf("%s\n\n", bench::loadAverageLine().c_str());

  // Texel size on screen: metres per texel of the cascade that serves each
  // depth, over metres per pixel at that depth, for the presets over 30 km.
  std::printf("\nCascade texel size on screen (pixels per shadow texel side; < 1: finer than the screen), %dx%d, "
              "fov 50 deg, shadow distance 30 km:\n\n| preset | 10 m | 100 m | 1 km | 10 km |\n| --- | ---: | ---: | ---: | ---: |\n",
              o.width, o.height);
  render::RenderView wide = view;
  wide.farClip = 50000.0;
  for (int q = 0; q < 3; ++q) {
    scene::SceneSettings st;
    st.shadows = true;
    st.shadowQuality = scene::ShadowQuality(q);
    st.shadowDistance = 30000.0;
    const render::ShadowConfig cfg = render::resolveShadowConfig(st, 0, nullptr);
    const render::SunCascades cs = render::computeSunCascades(wide, glm::dvec3(0.3, 0.9, -0.3), cfg, wide.eye);
    const char* names[] = {"low (1024, 2)", "medium (2048, 3)", "high (4096, 4)"};
    std::printf("| %s |", names[q]);
    for (double dist : {10.0, 100.0, 1000.0, 10000.0}) {
      double texel = 0.0;
      for (const render::ShadowCascade& c : cs.cascades)
        if (dist <= c.splitFar) {
          texel = c.texelMetres;
          break;
        }
      std::printf(" %.2f (%.3g m) |", texel / wide.pixelSizeAt(dist), texel);
    }
    std::printf("\n");
  }

  // Stereo with shadows on: one shadow pass for both eyes.
  {
    scene::SceneState s = sc.state;
    s.settings.shadowQuality = scene::ShadowQuality::Medium;
    render::RenderView left = view, right = view;
    left.eye -= view.right() * 0.0325;
    right.eye += view.right() * 0.0325;
    render::RenderOptions opt;
    opt.lodView = &view;
    r.renderOnly(s, view, opt);
    std::vector<double> mono, stereo;
    for (int f = 0; f < std::max(o.frames, 3); ++f) {
      double t = bench::nowSeconds();
      r.renderOnly(s, view, opt);
      mono.push_back(bench::nowSeconds() - t);
      t = bench::nowSeconds();
      r.renderViewsOnly(s, {left, right}, opt);
      stereo.push_back(bench::nowSeconds() - t);
    }
    std::printf("\nStereo with shadows on (medium): mono %.0f ms, stereo pair %.0f ms, ratio %.2fx (bench_frame without "
                "shadows: 2.04x)\n",
                1000.0 * median(mono), 1000.0 * median(stereo), median(stereo) / median(mono));
  }
  std::printf("%s\n", bench::loadAverageLine().c_str());

  if (!o.plot.empty()) {
    const bench::PlotColour colours[4] = {{200, 60, 40}, {40, 120, 200}, {40, 160, 80}, {150, 80, 180}};
    const bench::PlotMarker markers[4] = {bench::PlotMarker::Circle, bench::PlotMarker::Square,
                                          bench::PlotMarker::Triangle, bench::PlotMarker::Diamond};
    bench::PlotPanel byRes{"Error against map size", "shadow map size (texels per side)", "pixels differing from the ray cast (%)",
                           true, true, {}};
    bench::PlotPanel byTime{"Error against shadow pass time", "shadow pass GPU time (ms)",
                            "pixels differing from the ray cast (%)", true, true, {}};
    for (int c = 1; c <= 4; ++c) {
      bench::PlotSeries a{std::to_string(c) + (c == 1 ? " cascade" : " cascades"), colours[c - 1], markers[c - 1], false, {}, {}};
      bench::PlotSeries b = a;
      for (const Row& row : rows)
        if (row.cascades == c) {
          a.points.emplace_back(row.resolution, row.differPercent);
          b.points.emplace_back(row.passMs, row.differPercent);
          b.pointLabels.push_back(std::to_string(row.resolution));
        }
      byRes.series.push_back(a);
      byTime.series.push_back(b);
    }
    // Spot and point lights (their own scenes: the sun hidden, one light).
    const bench::PlotColour localColours[2] = {{220, 150, 20}, {90, 90, 90}};
    for (int k = 0; k < 2; ++k) {
      bench::PlotSeries a{k == 0 ? "spot light" : "point light (face size)", localColours[k], bench::PlotMarker::Circle,
                          false, {}, {}};
      bench::PlotSeries b = a;
      for (const Row& row : k == 0 ? spotRows : pointRows) {
        a.points.emplace_back(row.resolution, row.differPercent);
        b.points.emplace_back(row.passMs, row.differPercent);
        b.pointLabels.push_back(std::to_string(row.resolution));
      }
      byRes.series.push_back(a);
      byTime.series.push_back(b);
    }
    const std::string err = bench::savePlotPng({byRes, byTime}, o.plot);
    if (!err.empty()) std::fprintf(stderr, "bench_shadows: plot: %s\n", err.c_str());
    else std::printf("plot: %s\n", o.plot.c_str());
  }
  return 0;
}
