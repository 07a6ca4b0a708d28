// Mesh LODs in the renderer: per instance the coarsest level whose projected
// error is within the scene's pixel bound (render/mesh_lod.h, mesh::selectLod),
// nothing for what is outside the view, FrameStats counting what was drawn,
// and an image at the 1-pixel bound that differs from full resolution only
// by a small tolerance (no golden needed: both are rendered here).
#include <QtTest>

#include <cmath>

#include "image_compare.h"
#include "look_from.h"
#include "mesh/mesh_import.h"
#include "meshproc/mesh_process.h"
#include "render/mesh_lod.h"
#include "render/offscreen_renderer.h"
#include "scene/transform.h"

using namespace hs;
using hs::test::lookFrom;

namespace {

test::Rgba8Image toTest(const hs::Image& img) { return {img.width, img.height, img.rgba8}; }

// The bunny with three coarser levels (17k, 4.3k, 1.1k triangles), as the
// import with --lods 3 makes them.
const scene::MeshAsset& bunnyAsset() {
  static const scene::MeshAsset asset = [] {
    mesh::ImportResult r = mesh::importMesh(HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj");
    if (!r.ok()) qFatal("cannot load the bunny: %s", r.error.c_str());
    mesh::ProcessOptions o;
    o.clean = false;
    o.lodLevels = 3;
    o.error.samplesPerFace = 4;
    mesh::ProcessResult p = mesh::processMesh(*r.mesh, o);
    if (!p.ok()) qFatal("LOD chain: %s", p.error.c_str());
    scene::MeshAsset a;
    a.id = 1;
    a.name = "bunny";
    a.contentHash = mesh::contentHash(*r.mesh);
    a.data = std::make_shared<const mesh::MeshData>(std::move(*r.mesh));
    for (size_t k = 0; k < p.lods.size(); ++k) {
      scene::MeshLod l;
      l.contentHash = mesh::contentHash(p.lods[k]);
      l.hausdorff = p.report.lods[k + 1].hausdorff;
      l.data = std::make_shared<const mesh::MeshData>(std::move(p.lods[k]));
      a.lods.push_back(l);
    }
    return a;
  }();
  return asset;
}

size_t trianglesOf(const scene::MeshAsset& a, int level) {
  return level == 0 ? a.data->triangleCount() : a.lods[size_t(level) - 1].data->triangleCount();
}

// One bunny (scaled `scale` times) at the origin, a sun, and a camera
// `distance` metres away looking at it; `threshold` is the LOD pixel bound.
scene::SceneState bunnyScene(double distance, double scale = 1.0, double threshold = 1.0) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.meshLodErrorPixels = threshold;
  const scene::MeshAsset& a = bunnyAsset();
  s.assets.emplace(a.id, a);
  const mesh::Bounds b = a.data->bounds();
  const glm::dvec3 centre = glm::dvec3(b.center()) * scale;
  auto add = [&](scene::Entity e) {
    e.id = s.maxEntityId() + 1;
    s.roots.push_back(e.id);
    s.entities.emplace(e.id, e);
  };
  scene::Entity bunny;
  bunny.name = "Bunny";
  bunny.mesh = scene::MeshInstance{a.id};
  bunny.transform.scale = glm::dvec3(scale);
  add(bunny);
  scene::Entity sun;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.transform.rotation = scene::fromEulerDegrees({40, 0, -35});
  add(sun);
  scene::Entity cam;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 30.0;
  cam.camera->nearClip = 0.01;
  cam.transform = lookFrom(centre + glm::normalize(glm::dvec3(0.1, -1.0, 0.25)) * distance, centre);
  add(cam);
  return s;
}

// Pixels where `object` (an image with the object) differs from
// `background` (the same view without it) by more than 16 in a channel are
// the object's; those with a 4-neighbour (or the image's edge) outside it
// are its outline. `differing`: pixels where `other` differs from `object`.
struct OutlineCount {
  size_t outline = 0, differing = 0;
};
OutlineCount outlineAndDiffering(const hs::Image& object, const hs::Image& background, const hs::Image& other) {
  const int w = object.width, h = object.height;
  auto differs = [&](const hs::Image& a, const hs::Image& b, int x, int y) {
    const size_t i = (size_t(y) * size_t(w) + size_t(x)) * 4;
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(a.rgba8[i + size_t(c)]) - int(b.rgba8[i + size_t(c)])) > 16) return true;
    return false;
  };
  auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && differs(object, background, x, y); };
  OutlineCount r;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (inside(x, y) && (!inside(x - 1, y) || !inside(x + 1, y) || !inside(x, y - 1) || !inside(x, y + 1))) ++r.outline;
      if (differs(other, object, x, y)) ++r.differing;
    }
  return r;
}

render::RenderView cameraView(const scene::SceneState& s, int w, int h) {
  return render::viewFromCamera(s, s.cameras().front(), w, h);
}

// What the renderer chooses for the bunny in `s` seen through `v`.
render::MeshLodChoice choice(const scene::SceneState& s, const render::RenderView& v) {
  const scene::MeshAsset& a = bunnyAsset();
  const scene::Entity& e = s.entities.at(s.findByName("Bunny"));
  const mesh::Bounds b = a.data->bounds();
  const glm::dmat4 w = s.worldMatrix(e.id);
  const glm::dvec3 centre = glm::dvec3(w * glm::dvec4(glm::dvec3(b.center()), 1.0));
  return render::chooseMeshLod(a.lodErrors(), centre - v.eye, double(b.radius()), e.transform.scale.x, v,
                               s.settings.meshLodErrorPixels);
}

}  // namespace

class TestMeshLod : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    const scene::MeshAsset& a = bunnyAsset();
    QCOMPARE(a.lods.size(), size_t(3));
    qInfo("bunny LODs: %zu, %zu (%.3g m), %zu (%.3g m), %zu (%.3g m)", trianglesOf(a, 0), trianglesOf(a, 1),
          a.lods[0].hausdorff, trianglesOf(a, 2), a.lods[1].hausdorff, trianglesOf(a, 3), a.lods[2].hausdorff);
  }

  // The rule, without GL: the coarsest level within the bound.
  void selectionRule() {
    const std::vector<double> errors{0.0, 0.001, 0.004, 0.016};
    render::RenderView v;
    v.fovY = glm::radians(40.0);
    v.height = 1000;
    const auto at = [&](double d, double scale = 1.0, double threshold = 1.0) {
      return render::chooseMeshLod(errors, glm::dvec3(0, d + 0.5 * scale, 0), 0.5, scale, v, threshold);
    };
    QCOMPARE(at(0.5).level, 0);        // close: full resolution
    QCOMPARE(at(100000).level, 3);     // far: the coarsest
    for (double d : {1.0, 3.0, 10.0, 30.0, 100.0}) {
      const render::MeshLodChoice c = at(d);
      QVERIFY(c.projectedErrorPixels <= 1.0);
      if (c.level < 3)  // the next level would be over the bound
        QVERIFY(mesh::projectedErrorPixels(errors[size_t(c.level) + 1], c.distance, v.fovY, v.height) > 1.0);
      QCOMPARE(c.distance, d);  // to the sphere, not its centre
    }
    // A larger instance needs a finer level at the same distance; a looser bound a coarser one.
    QVERIFY(at(10.0, 10.0).level < at(10.0 + 4.5, 1.0).level);
    QVERIFY(at(10.0, 1.0, 4.0).level > at(10.0).level);
    // A bound of 0 is full resolution; an eye inside the sphere too.
    QCOMPARE(at(10000.0, 1.0, 0.0).level, 0);
    QCOMPARE(render::chooseMeshLod(errors, glm::dvec3(0.1, 0, 0), 0.5, 1.0, v, 1.0).level, 0);
  }

  // The bunny is 0.15 m tall: scaled 10 times (a 1.5 m rock) it spans the
  // chain's levels over a few metres at 320 x 240. (With refined levels,
  // whose errors are 25-30% lower, level 1 is drawn from about 2 m.)
  void nearInstanceDrawsFullResolution() {
    const auto s = bunnyScene(1.5, 10.0);
    render::FrameStats stats;
    r_.render(s, cameraView(s, 320, 240), false, &stats);
    QCOMPARE(stats.instancesDrawn, size_t(1));
    QCOMPARE(stats.instancesAtCoarserLod, size_t(0));
    QCOMPARE(stats.trianglesDrawn, trianglesOf(bunnyAsset(), 0));
  }

  // The test the issue asks for: far away, a coarser level is drawn, and its
  // projected error is within the 1-pixel bound.
  void farInstanceDrawsACoarserLodWithinTheBound() {
    size_t previous = trianglesOf(bunnyAsset(), 0) + 1;
    int coarser = 0, lastLevel = -1;
    for (double distance : {2.0, 3.0, 5.0, 12.0, 40.0}) {
      const auto s = bunnyScene(distance, 10.0);
      const render::RenderView v = cameraView(s, 320, 240);
      const render::MeshLodChoice c = choice(s, v);
      render::FrameStats stats;
      r_.render(s, v, false, &stats);
      qInfo("at %.0f m: level %d, %.3f px, %zu triangles", distance, c.level, c.projectedErrorPixels, stats.trianglesDrawn);
      QCOMPARE(stats.instancesDrawn, size_t(1));
      QCOMPARE(stats.trianglesDrawn, trianglesOf(bunnyAsset(), c.level));
      QCOMPARE(stats.instancesAtCoarserLod, size_t(c.level > 0 ? 1 : 0));
      QVERIFY2(c.projectedErrorPixels <= 1.0, qPrintable(QString::number(c.projectedErrorPixels)));
      QVERIFY(stats.trianglesDrawn <= previous);  // farther never draws more
      QVERIFY(c.level >= lastLevel);
      previous = stats.trianglesDrawn;
      lastLevel = c.level;
      coarser = std::max(coarser, c.level);
    }
    QCOMPARE(coarser, 3);  // every level of the chain was used on the way
    // Ten times larger again at 12 m, the same asset needs a finer level.
    const auto big = bunnyScene(12.0, 100.0);
    QCOMPARE(choice(big, cameraView(big, 320, 240)).level, 0);
  }

  void boundOfZeroDrawsFullResolution() {
    const auto s = bunnyScene(40.0, 10.0, 0.0);
    render::FrameStats stats;
    r_.render(s, cameraView(s, 320, 240), false, &stats);
    QCOMPARE(stats.trianglesDrawn, trianglesOf(bunnyAsset(), 0));
    QCOMPARE(stats.instancesAtCoarserLod, size_t(0));
  }

  void outsideTheViewDrawsNothing() {
    const auto s = bunnyScene(30.0);
    render::RenderView v = cameraView(s, 320, 240);
    v.orientation = v.orientation * glm::angleAxis(glm::pi<double>(), glm::dvec3(0, 1, 0));  // turn around
    render::FrameStats stats;
    r_.render(s, v, false, &stats);
    QCOMPARE(stats.instancesDrawn, size_t(0));
    QCOMPARE(stats.instancesCulled, size_t(1));
    QCOMPARE(stats.trianglesDrawn, size_t(0));
  }

  // A stereo pair draws the same level in both eyes when it passes its
  // camera's view as RenderOptions::lodView (the export and the stereo
  // preview do); left to itself each eye would choose on its own and, near
  // a switch distance, differently.
  void stereoEyesShareMeshLevels() {
    // Eyes 1.5 m apart, the left one at the camera (a rig pivoting on the
    // left eye), so the right eye is farther from the bunny than the left.
    double found = -1.0;
    for (double d = 2.0; d < 40.0 && found < 0; d += 0.05) {
      const auto s = bunnyScene(d, 10.0, 1.0);
      const render::RenderView mono = cameraView(s, 320, 240);
      render::RenderView right = mono;
      right.eye += 1.5 * mono.right();
      if (choice(s, mono).level != choice(s, right).level) found = d;
    }
    QVERIFY2(found > 0, "no distance where the eyes would choose different levels");
    const auto s = bunnyScene(found, 10.0, 1.0);
    const render::RenderView mono = cameraView(s, 320, 240);
    render::RenderView right = mono;
    right.eye += 1.5 * mono.right();
    const int monoLevel = choice(s, mono).level;
    const size_t left = r_.renderOnly(s, mono).trianglesDrawn;
    const size_t rightAlone = r_.renderOnly(s, right).trianglesDrawn;
    QCOMPARE(left, trianglesOf(bunnyAsset(), monoLevel));
    QVERIFY(rightAlone != left);  // on its own the right eye picks another level
    render::RenderOptions shared;
    shared.lodView = &mono;
    const render::FrameStats rightShared = r_.renderOnly(s, right, shared);
    qInfo("at %.2f m: left eye level %d (%zu triangles), right eye alone %zu, with the camera's levels %zu", found,
          monoLevel, left, rightAlone, rightShared.trianglesDrawn);
    QCOMPARE(rightShared.trianglesDrawn, left);
    QCOMPARE(rightShared.instancesDrawn, size_t(1));
  }

  // Golden-free: at the 1-pixel bound the image is the full-resolution
  // image up to a few edge pixels, while the coarsest level at the same
  // spot differs visibly more (so the comparison can tell).
  // Level 1 is looked at where the rule last chooses it before level 2
  // (found from the levels' errors; it was a fixed 4.5 m, right at that
  // switch, so a decimation change that lowered level 2's error from
  // 0.000487 to 0.00048 m switched the level drawn there), level 2 in the
  // middle of its range. The pixels that differ are counted against the
  // bunny's outline in the full image: geometry within a pixel moves the
  // outline by at most a pixel either way, up to two pixels per outline
  // pixel, and the coarser normals' shading adds some (the rule bounds the
  // geometry, not the shading). Measured: 0.82 per outline pixel for level
  // 1 at 3.65 m, 1.26 for level 2 at 8 m; the coarsest level there 4.9 and
  // 2.6. A share of the whole image, as this test once counted, grew with
  // every decimation change that lowered a level's error: the level is
  // then drawn nearer, where the bunny covers more of the image (level 1
  // last drawn at 4.53 m: 0.82% of the image; at 3.65 m: 1.25%).
  void onePixelBoundMatchesFullResolution() {
    double lastLevel1 = 0.0;
    for (double d = 2.0; d < 20.0; d += 0.01) {
      const auto s = bunnyScene(d, 10.0, 1.0);
      const int level = choice(s, cameraView(s, 480, 360)).level;
      if (level == 1) lastLevel1 = d;
      if (level > 1) break;
    }
    QVERIFY(lastLevel1 > 0.0);
    for (double distance : {lastLevel1, 8.0}) {
      const auto lod = bunnyScene(distance, 10.0, 1.0);
      const auto full = bunnyScene(distance, 10.0, 0.0);
      const auto coarsest = bunnyScene(distance, 10.0, 64.0);
      const render::RenderView v = cameraView(lod, 480, 360);
      const int level = choice(lod, v).level;
      QVERIFY(level > 0 && level < 3);  // the comparison is about a coarser, not the coarsest, level
      render::FrameStats a, b, c;
      const hs::Image imgLod = r_.render(lod, v, false, &a);
      const hs::Image imgFull = r_.render(full, v, false, &b);
      const hs::Image imgCoarsest = r_.render(coarsest, v, false, &c);
      QVERIFY(a.trianglesDrawn < b.trianglesDrawn && c.trianglesDrawn < a.trianglesDrawn);
      const test::CompareResult cmp = test::compareImages(toTest(imgLod), toTest(imgFull), 16);
      const test::CompareResult worst = test::compareImages(toTest(imgCoarsest), toTest(imgFull), 16);
      // The bunny's outline: its pixels (the full image against the scene
      // without it) with a neighbour outside it.
      auto empty = full;
      for (auto it = empty.entities.begin(); it != empty.entities.end(); ++it)
        if (it->second.name == "Bunny") {
          empty.roots.erase(std::find(empty.roots.begin(), empty.roots.end(), it->first));
          empty.entities.erase(it);
          break;
        }
      const hs::Image imgEmpty = r_.render(empty, v, false);
      const auto outline = outlineAndDiffering(imgFull, imgEmpty, imgLod);
      const auto outlineCoarsest = outlineAndDiffering(imgFull, imgEmpty, imgCoarsest);
      qInfo("at %.2f m, level %d: %zu vs %zu triangles: %s (%.2f per outline pixel); coarsest (%zu): %s (%.2f)",
            distance, level, a.trianglesDrawn, b.trianglesDrawn, cmp.summary().c_str(),
            double(outline.differing) / double(outline.outline), c.trianglesDrawn, worst.summary().c_str(),
            double(outlineCoarsest.differing) / double(outline.outline));
      QVERIFY(cmp.sizeMatches);
      // Geometry moves by at most a pixel, so only edge pixels change
      // noticeably (and shading a little where normals were averaged).
      QVERIFY(outline.outline > 100);
      QVERIFY2(outline.differing <= 2 * outline.outline, cmp.summary().c_str());
      QVERIFY2(worst.differingShare > 1.5 * cmp.differingShare, worst.summary().c_str());
    }
  }
};

QTEST_GUILESS_MAIN(TestMeshLod)
#include "test_mesh_lod.moc"
