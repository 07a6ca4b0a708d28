// Terrain through the real renderer (headless EGL; on this machine Mesa
// llvmpipe), the two render targets side by side with their budgets:
//
//  1. One brush dab of radius 128 samples on a 4097^2 terrain including the
//     GPU upload of its region, against 2 ms: the dab (CPU), the renderer's
//     sync of that region (GL upload calls + CDLOD bounds + LOD errors, CPU),
//     and the GPU side (GL_TIME_ELAPSED around the uploads, and glFinish).
//  2. LOD: an 8193^2 terrain at 1920x1080 with a 1-pixel error bound:
//     triangles drawn (vs the full-resolution mesh), frame time (CPU and
//     wall with glFinish), selection time, and the measured screen-space
//     error against the full-resolution mesh (per pixel, from the depth
//     buffer: the distance on screen between the drawn surface point and
//     the full mesh's point above or below it).
//  3. The scene file: first save of the 8193^2 terrain and the save after one
//     radius-128 stroke (tiles and bytes written, time).
//
//   bench_terrain_render [--quick]   (quick: 2049^2 and 4097^2)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "bench/common/bench_util.h"
#include "core/parallel.h"
#include "render/offscreen_renderer.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/operations.h"
#include "scene/terrain_edits.h"
#include "scene/terrain_file.h"
#include "scene/terrain_ops.h"
#include "scene/terrain_pick.h"
#include "terrain/noise.h"
#include "terrain/stroke.h"
#include "tests/common/look_from.h"
#include "tests/common/terrain_screen_error.h"

using namespace hs;
using bench::median;
using bench::nowSeconds;

namespace {

// A document with a sun, a camera and an n^2 terrain of fractal hills at
// 1 m spacing (heights 180..420 m), painted by the default rules.
struct Bench {
  scene::Document doc;
  scene::EntityId terrain = scene::kNoEntity, camera = scene::kNoEntity;
  explicit Bench(int n) {
    scene::SceneState s;
    s.settings.showGrid = false;
    s.settings.antialiasing = scene::Antialiasing::None;
    doc.reset(std::move(s), {});
    scene::ops::addLight(doc, "Sun", test::lookFrom({0, 0, 0}, {0.4, 0.3, -1.0}), scene::Light{});
    scene::ops::NewTerrain spec;
    spec.samplesX = spec.samplesY = n;
    spec.sizeMetres = glm::dvec2(double(n - 1));
    spec.centre = glm::dvec3(glm::dvec2(double(n - 1) * 0.5), 0.0);  // world x, y = local: 0..n-1
    std::string error;
    terrain = scene::ops::addTerrain(doc, spec, error);
    terrain::Heightfield& hf = data().terrain().height;
    terrain::FractalNoise fn;
    fn.seed = 7;
    fn.scale = 800.0;
    fn.octaves = 9;
    std::vector<float> all(size_t(n) * size_t(n));
    hs::parallelFor(n, 0, 16, [&](int b, int e) {
      for (int y = b; y < e; ++y) {
        fn.row(0.0, 1.0, double(y), n, all.data() + size_t(y) * size_t(n));
        for (int x = 0; x < n; ++x) all[size_t(y) * size_t(n) + size_t(x)] = 300.0f + 120.0f * all[size_t(y) * size_t(n) + size_t(x)];
      }
    });
    hf.write(hf.bounds(), all);
    data().noteChanged(hf.bounds(), scene::kTerrainAll);
    scene::Camera c;
    c.verticalFovDeg = 50.0;
    c.nearClip = 0.5;
    c.farClip = 100000.0;
    camera = scene::ops::addCamera(doc, "Camera", scene::Transform{}, c);
  }
  scene::TerrainData& data() { return *scene::terrainOf(doc.state(), terrain)->data; }
  scene::TerrainId id() const { return doc.state().find(terrain)->terrain->terrain; }
  render::RenderView look(glm::dvec3 eye, glm::dvec3 target, int w, int h) {
    scene::ops::setTransforms(doc, {{camera, test::lookFrom(eye, target)}}, "look");
    return render::viewFromCamera(doc.state(), camera, w, h);
  }
};

using ErrorStats = test::TerrainScreenError;

ErrorStats measureError(render::OffscreenRenderer& r, Bench& b, const render::RenderView& v) {
  std::vector<float> depth(size_t(v.width) * size_t(v.height));
  r.renderer().readDepth(depth.data());
  return test::terrainScreenError(depth, v, b.data().heights(), scene::terrainWorldOrigin(b.doc.state(), b.terrain));
}

double ms(double s0) { return (nowSeconds() - s0) * 1e3; }

void dabBench(render::OffscreenRenderer& r, int n) {
  Bench b(n);
  const render::RenderView v = b.look({double(n) * 0.5, -200.0, 900.0}, {double(n) * 0.5, double(n) * 0.4, 300.0}, 640, 360);
  double t0 = nowSeconds();
  r.renderOnly(b.doc.state(), v);
  std::printf("1. Brush dab of radius 128 samples on %dx%d, including the GPU upload of its region (budget 2 ms)\n", n, n);
  std::printf("   first frame (uploads all %.0f MB, builds CDLOD bounds and LOD errors): %.0f ms\n\n",
              double(n) * n * 4 / 1e6, ms(t0));
  std::printf("%-10s %8s %10s %10s %9s %9s %9s %10s %9s %9s\n", "tool", "dab", "region", "bytes", "GL upload",
              "glFinish", "dab+upl", "vs 2 ms", "LOD bkpg", "all");
  struct T {
    const char* name;
    terrain::BrushTool tool;
    float strength;
  };
  for (const T& tool : {T{"raise", terrain::BrushTool::Raise, 0.5f}, T{"smooth", terrain::BrushTool::Smooth, 0.5f},
                        T{"noise", terrain::BrushTool::Noise, 1.0f}, T{"paint", terrain::BrushTool::Paint, 0.5f}}) {
    std::vector<double> dab, upload, lod, finish, total, all;
    size_t bytes = 0;
    terrain::Region region;
    terrain::BrushSettings s;
    s.tool = tool.tool;
    s.radius = 128.0;
    s.strength = tool.strength;
    s.paintLayer = 3;
    terrain::Stroke st(b.data().terrain(), s);
    for (int i = 0; i < 15; ++i) {
      const glm::dvec2 at(double(n) * 0.5 + 37.0 * i, double(n) * 0.5 + 11.0 * i);
      t0 = nowSeconds();
      const terrain::StrokeUpdate u = st.dabAt(at);
      const double dabMs = ms(t0);
      scene::noteTerrainChange(b.doc, b.id(), b.data(), u.changed, scene::changeKindsOf(tool.tool));
      const render::TerrainUpload up = r.renderer().syncTerrain(b.data(), true);
      if (i < 2) continue;  // the first dabs also copy tiles for undo
      dab.push_back(dabMs);
      upload.push_back(up.cpuMs - up.lodMs);
      lod.push_back(up.lodMs);
      finish.push_back(up.finishMs);
      total.push_back(dabMs + (up.cpuMs - up.lodMs) + std::max(0.0, up.finishMs));
      all.push_back(dabMs + up.cpuMs + std::max(0.0, up.finishMs));
      bytes = up.bytes;
      region = u.changed;
    }
    scene::pushTerrainStep(b.doc, b.id(), st.finish(), "bench");
    std::printf("%-10s %8.3f %4dx%-5d %10zu %9.3f %9.3f %9.3f %9.2fx %9.3f %9.3f\n", tool.name, median(dab),
                region.width(), region.height(), bytes, median(upload), median(finish), median(total),
                median(total) / 2.0, median(lod), median(all));
  }
  std::printf("\n   dab: the brush on the CPU (%d threads). GL upload: the sub-image uploads of the changed region\n"
              "   straight from the tiles (GL_UNPACK_ROW_LENGTH 128; llvmpipe copies into the texture inside these\n"
              "   calls, so this is the GPU-side copy too). glFinish: waiting for the GPU afterwards. vs 2 ms:\n"
              "   (dab + GL upload + glFinish) / 2 ms. LOD bkpg: the renderer's CDLOD min/max and LOD-error\n"
              "   refresh of the region (once per frame for all the frame's dabs). all: everything. Medians of 13.\n\n",
              hs::resolveThreads(0));
}

void lodBench(render::OffscreenRenderer& r, int n) {
  double t0 = nowSeconds();
  Bench b(n);
  const double buildS = (nowSeconds() - t0);
  std::printf("2. LOD: %dx%d terrain (1 m spacing, %.0f x %.0f m, heights 180..420 m) at 1920x1080, error bound 1 px\n", n, n,
              double(n - 1), double(n - 1));
  std::printf("   (terrain generated in %.1f s)\n", buildS);
  struct View {
    const char* name;
    glm::dvec3 eye, target;
  };
  const double c = double(n) * 0.5;
  const View views[] = {
      {"aerial, 45 deg down, 2 km up", {c, -800.0, 2300.0}, {c, c * 0.6, 300.0}},
      {"low, 50 m above ground", {c, c * 0.3, 0.0}, {c + 300.0, c, 0.0}},
      {"grazing, horizon in view", {c * 0.4, 300.0, 0.0}, {c, c * 1.2, 0.0}},
  };
  std::printf("\n%-32s %10s %9s %10s %10s %9s %9s %9s %9s %9s\n", "view", "triangles", "quads", "vs full", "CPU ms",
              "wall ms", "select", "err max", "err 99.9%", "err mean");
  const size_t full = size_t(2) * size_t(n - 1) * size_t(n - 1);
  bool first = true;
  for (const View& v0 : views) {
    glm::dvec3 eye = v0.eye, target = v0.target;
    if (v0.eye.z == 0.0) {  // heights over the ground below
      const double g = *scene::terrainSurfaceAt(b.doc.state(), b.terrain, glm::dvec2(eye));
      eye.z = g + 50.0;
      target.z = g - 20.0;
    }
    const render::RenderView v = b.look(eye, target, 1920, 1080);
    if (first) {
      t0 = nowSeconds();
      r.renderOnly(b.doc.state(), v);
      std::printf("(first frame: uploads %.0f MB and builds the CDLOD bounds and LOD errors: %.0f ms)\n",
                  double(n) * n * 4 / 1e6, ms(t0));
      first = false;
    }
    std::vector<double> cpu, wall;
    render::FrameStats st;
    render::RenderOptions keepDepth;  // the last frame's depth measures the error
    keepDepth.keepDepth = true;
    for (int i = 0; i < 5; ++i) {
      t0 = nowSeconds();
      st = r.renderOnly(b.doc.state(), v, keepDepth);
      wall.push_back(ms(t0));
      cpu.push_back(st.cpuMs);
    }
    t0 = nowSeconds();
    const render::LodSelection sel = r.renderer().terrainLod(b.doc.state(), b.terrain, v);
    const double selectMs = ms(t0);
    const ErrorStats e = measureError(r, b, v);
    std::printf("%-32s %10zu %9zu %9.4f%% %10.1f %9.1f %9.2f %9.3f %9.3f %9.4f\n", v0.name, st.terrainTriangles,
                st.terrainPatches, 100.0 * double(st.terrainTriangles) / double(full), median(cpu), median(wall), selectMs,
                e.maxPx, e.p999, e.mean);
    (void)sel;
  }
  std::printf("\n   full-resolution mesh: %zu triangles. CPU ms: Renderer::render on the calling thread (llvmpipe\n"
              "   rasterises on its own threads); wall ms: the same with glFinish (what a frame costs). err: the\n"
              "   drawn surface against the full-resolution mesh, pixels on screen, over every terrain pixel.\n\n",
              full);

  // 3. The file after one stroke.
  const std::string path = (std::filesystem::temp_directory_path() / "bench_terrain_render.hscene").string();
  std::filesystem::remove(path);
  std::string error;
  scene::SaveReport firstSave;
  t0 = nowSeconds();
  if (!scene::saveScene(scene::snapshotForSave(b.doc.state()), path, error, &firstSave)) {
    std::printf("save failed: %s\n", error.c_str());
    return;
  }
  const double firstMs = ms(t0);
  terrain::BrushSettings s;
  s.radius = 128.0;
  s.strength = 2.0f;
  terrain::Stroke st(b.data().terrain(), s);
  for (int i = 0; i < 8; ++i) st.moveTo(glm::dvec2(c + 20.0 * i, c + 7.0 * i));
  scene::pushTerrainStep(b.doc, b.id(), st.finish(), "stroke");
  scene::SaveReport second;
  t0 = nowSeconds();
  scene::saveScene(scene::snapshotForSave(b.doc.state()), path, error, &second);
  const double secondMs = ms(t0);
  std::printf("3. Saving the %dx%d terrain: first save %zu tiles, %.1f MB in %.0f ms; after one radius-128 stroke:\n"
              "   %zu tiles, %.0f KB in %.0f ms (%zu tiles unchanged, found by their hashes)\n\n",
              n, n, firstSave.tilesWritten, double(firstSave.tileBytesWritten) / 1e6, firstMs, second.tilesWritten,
              double(second.tileBytesWritten) / 1e3, secondMs, second.tilesUnchanged);
  std::filesystem::remove(path);
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "no headless OpenGL: %s\n", error.c_str());
    return 1;
  }
  std::printf("Terrain rendering benchmark on %s, %d hardware threads, load average %.2f\n\n", r.glDescription().c_str(),
              hs::resolveThreads(0), bench::loadAverage());
  dabBench(r, quick ? 2049 : 4097);
  lodBench(r, quick ? 4097 : 8193);
  std::printf("load average at the end: %.2f\n", bench::loadAverage());
  return 0;
}
