// Cluster hierarchies in the renderer (issue 38 items 3-4; render/
// cluster_source.h), golden-free: every image here is compared with one
// rendered here from the full-resolution mesh.
//   - crack-free: where the full-resolution scan covers a pixel and its
//     neighbours out to the bound, the cut covers it too (a crack between
//     clusters of two levels would show the sky there);
//   - error bound: at the 1-pixel bound the image differs from full
//     resolution about the outline only, while a loose bound differs more;
//   - budget: with a GPU budget of a tenth of the scan's pages a low flight
//     renders, never holds more than the budget, and its frames equal the
//     unlimited budget's;
//   - a frame that may not stream waits for its pages (the same image in
//     any run); the viewport's streaming frames start coarse and converge
//     on it; a damaged page is reported by name and its parent is drawn;
//   - both eyes of a pair draw the cut of the camera's view; the level
//     view colours clusters by level.
#include <QtTest>

#include <cmath>
#include <set>

#include "image_compare.h"
#include "look_from.h"
#include "mesh/mesh_data.h"
#include "render/offscreen_renderer.h"
#include "scene/cluster_asset.h"
#include "scene/import_pipeline.h"
#include "scene/transform.h"

using namespace hs;
using hs::test::lookFrom;

namespace {

const std::string kBunny = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";

// The scan twice: as a cluster hierarchy (asset 1, its coarse cut as its
// mesh) and whole (asset 2, the reference).
struct Scan {
  scene::MeshAsset clustered, whole;
};

Scan makeScan(mesh::MeshData input, bool certify = true) {
  Scan s;
  s.whole.id = 2;
  s.whole.name = "whole";
  s.whole.contentHash = mesh::contentHash(input);
  s.whole.data = std::make_shared<const mesh::MeshData>(input);
  mesh::ClusterOptions o;
  o.certifyErrors = certify;
  scene::ClusterBuild b = scene::buildClusterAsset(input, o, scene::kClusterProxyTriangles);
  s.clustered.id = 1;
  s.clustered.name = "clustered";
  s.clustered.contentHash = mesh::contentHash(b.proxy);
  s.clustered.data = std::make_shared<const mesh::MeshData>(std::move(b.proxy));
  s.clustered.clustersHash = b.clustersHash;
  s.clustered.clusters = std::move(b.clusters);
  return s;
}

const Scan& bunny() {
  static const Scan s = [] {
    mesh::ImportResult r = mesh::importMesh(kBunny);
    if (!r.ok()) qFatal("%s", r.error.c_str());
    return makeScan(std::move(*r.mesh));
  }();
  return s;
}

// A rolling 4 km x 4 km scan tile of 1.28M triangles, the kind a low
// flight crosses (its errors estimated, not certified: the budget is what
// is tested with it, and certifying takes several times as long).
const Scan& valley() {
  static const Scan s = [] {
    mesh::MeshData m;
    const int n = 800;
    const double size = 4000.0;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = size * i / n - 0.5 * size, y = size * j / n - 0.5 * size;
        const double z = 40.0 * std::sin(x / 130.0) * std::cos(y / 170.0) + 8.0 * std::sin(x / 23.0 + y / 31.0);
        m.positions.push_back(glm::vec3(float(x), float(y), float(z)));
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
        m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
      }
    m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
    mesh::computeVertexNormals(m);
    return makeScan(std::move(m), false);
  }();
  return s;
}

// One scan entity (the clustered or the whole asset), a sun, and a camera
// at `eye` looking at `target`; `bound` is the pixel bound.
scene::SceneState sceneOf(const Scan& scan, bool clustered, glm::dvec3 eye, glm::dvec3 target, double scale,
                          double bound = 1.0) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.meshLodErrorPixels = bound;
  s.assets.emplace(1, scan.clustered);
  s.assets.emplace(2, scan.whole);
  auto add = [&](scene::Entity e) {
    e.id = s.maxEntityId() + 1;
    s.roots.push_back(e.id);
    s.entities.emplace(e.id, e);
  };
  scene::Entity e;
  e.name = "Scan";
  e.mesh = scene::MeshInstance{clustered ? scene::AssetId(1) : scene::AssetId(2)};
  e.transform.scale = glm::dvec3(scale);
  add(e);
  scene::Entity sun;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.transform.rotation = scene::fromEulerDegrees({40, 0, -35});
  add(sun);
  scene::Entity cam;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 40.0;
  cam.camera->nearClip = 0.01;
  cam.camera->farClip = 10000.0;
  cam.transform = lookFrom(eye, target);
  add(cam);
  return s;
}

render::RenderView viewOf(const scene::SceneState& s, int w, int h) {
  return render::viewFromCamera(s, s.cameras().front(), w, h);
}

// The pixels something was drawn at (reversed-Z depth above 0), from the
// frame `r` rendered last with keepDepth.
std::vector<uint8_t> coverage(render::OffscreenRenderer& r, int w, int h) {
  std::vector<float> depth(size_t(w) * size_t(h));
  r.renderer().readDepth(depth.data());
  std::vector<uint8_t> m(depth.size());
  for (size_t p = 0; p < m.size(); ++p) m[p] = depth[p] > 0.0f;
  return m;
}

// Pixels the reference covers with every pixel within `margin` covered too
// (inside the silhouette, beyond what a bounded error can move it) that
// `test` does not cover: holes.
size_t holes(const std::vector<uint8_t>& reference, const std::vector<uint8_t>& test, int w, int h, int margin) {
  size_t n = 0;
  for (int y = margin; y < h - margin; ++y)
    for (int x = margin; x < w - margin; ++x) {
      if (test[size_t(y) * size_t(w) + size_t(x)]) continue;
      bool interior = true;
      for (int dy = -margin; dy <= margin && interior; ++dy)
        for (int dx = -margin; dx <= margin && interior; ++dx)
          interior = reference[size_t(y + dy) * size_t(w) + size_t(x + dx)] != 0;
      n += interior;
    }
  return n;
}

size_t outlinePixels(const std::vector<uint8_t>& m, int w, int h) {
  size_t n = 0;
  auto in = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && m[size_t(y) * size_t(w) + size_t(x)]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      n += in(x, y) && (!in(x - 1, y) || !in(x + 1, y) || !in(x, y - 1) || !in(x, y + 1));
  return n;
}

test::Rgba8Image toTest(const hs::Image& img) { return {img.width, img.height, img.rgba8}; }

}  // namespace

class TestClusterRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    const auto& c = *bunny().clustered.clusters;
    qInfo("bunny: %zu triangles, %zu clusters in %zu levels, %zu pages; coarse mesh %zu triangles",
          bunny().whole.data->triangleCount(), c.index.clusters.size(), c.levels(), c.pageBytes.size(),
          bunny().clustered.data->triangleCount());
  }

  // Near one side of the scan the cut mixes levels: fewer triangles than
  // the scan, more than its coarse mesh, one instance drawn from clusters.
  void drawsACutOfMixedLevels() {
    const glm::dvec3 c = glm::dvec3(bunny().whole.data->bounds().center()) * 10.0;
    const auto s = sceneOf(bunny(), true, c + glm::dvec3(0.2, -1.2, 0.4), c, 10.0);
    render::FrameStats stats;
    r_.render(s, viewOf(s, 320, 240), false, &stats);
    const render::ClusterStats& k = stats.clusters;
    qInfo("cut: %zu clusters, %zu triangles (scan %zu), %zu pages resident, %.2f ms", k.clusters, k.triangles,
          bunny().whole.data->triangleCount(), k.pagesResident, k.cutMs);
    QCOMPARE(k.instances, size_t(1));
    QVERIFY(k.complete);
    QCOMPARE(k.pagesWanted, size_t(0));
    QVERIFY(k.triangles < bunny().whole.data->triangleCount());
    QVERIFY(k.triangles > bunny().clustered.data->triangleCount() / 4);
    QCOMPARE(stats.instancesDrawn, size_t(1));
    QVERIFY(stats.trianglesDrawn > 0 && stats.trianglesDrawn <= k.triangles);
    // The level view shows several levels.
    render::RenderOptions o;
    o.clusterLevels = true;
    const hs::Image img = r_.render(s, viewOf(s, 320, 240), false, nullptr, o);
    std::set<uint32_t> hues;
    for (size_t p = 0; p < img.rgba8.size(); p += 4) {
      const int r = img.rgba8[p], g = img.rgba8[p + 1], b = img.rgba8[p + 2];
      if (std::max({r, g, b}) - std::min({r, g, b}) > 60) hues.insert(uint32_t(r / 48) << 8 | uint32_t(g / 48) << 4 | uint32_t(b / 48));
    }
    QVERIFY2(hues.size() >= 3, qPrintable(QString::number(hues.size())));
  }

  // Crack-free and within the bound, against full resolution.
  void crackFreeAndWithinTheBound() {
    const glm::dvec3 c = glm::dvec3(bunny().whole.data->bounds().center()) * 10.0;
    for (const auto& [eye, bound] : std::vector<std::pair<glm::dvec3, double>>{
             {c + glm::dvec3(0.2, -1.2, 0.4), 1.0}, {c + glm::dvec3(-1.0, -2.5, 1.0), 1.0},
             {c + glm::dvec3(0.2, -1.2, 0.4), 4.0}, {c + glm::dvec3(3.0, -6.0, 2.0), 8.0}}) {
      const int w = 480, h = 360;
      const auto cut = sceneOf(bunny(), true, eye, c, 10.0, bound);
      const auto full = sceneOf(bunny(), false, eye, c, 10.0, bound);
      const render::RenderView v = viewOf(cut, w, h);
      render::FrameStats stats;
      render::RenderOptions depth;
      depth.keepDepth = true;
      const hs::Image imgCut = r_.render(cut, v, false, &stats, depth);
      const auto mCut = coverage(r_, w, h);
      const hs::Image imgFull = r_.render(full, v, false, nullptr, depth);
      const auto mFull = coverage(r_, w, h);
      const int margin = int(std::ceil(bound)) + 1;
      const size_t hole = holes(mFull, mCut, w, h, margin);
      size_t differing = 0;
      for (size_t p = 0; p < mFull.size(); ++p) differing += mFull[p] != mCut[p];
      const size_t outline = outlinePixels(mFull, w, h);
      const test::CompareResult cmp = test::compareImages(toTest(imgCut), toTest(imgFull), 16);
      qInfo("bound %.0f px: %zu of %zu triangles; holes %zu; coverage differs at %zu pixels (%.2f per outline pixel); "
            "%s",
            bound, stats.clusters.triangles, bunny().whole.data->triangleCount(), hole, differing,
            double(differing) / double(outline), cmp.summary().c_str());
      QVERIFY(stats.clusters.instances == 1 && stats.clusters.complete);
      QVERIFY(outline > 100);
      QCOMPARE(hole, size_t(0));
      // An error within the bound moves the outline by at most that many
      // pixels either way.
      QVERIFY2(double(differing) <= 2.0 * bound * double(outline), cmp.summary().c_str());
      if (bound == 1.0) QVERIFY2(cmp.differingShare < 0.02, cmp.summary().c_str());
    }
  }

  // A tenth of the pages' memory: a low flight renders within it and each
  // frame equals the unlimited budget's.
  void budgetOfATenth() {
    const scene::ClusterAsset& c = *valley().clustered.clusters;
    // A slot of the GPU pool holds the largest page: 32 bytes a vertex, 4 an index.
    const mesh::PageExtent largest = mesh::largestPage(c.index);
    const double slotBytes = double(largest.vertices * 32 + largest.indices * 4);
    const double budgetMb = slotBytes * double(c.index.pageCount) / 10.0 / 1048576.0;
    {
      std::vector<float> errors(c.levels(), 0.0f);
      for (const auto& e : c.index.clusters) errors[e.level] = std::max(errors[e.level], e.error);
      QString t;
      for (float e : errors) t += QString(" %1").arg(double(e), 0, 'g', 3);
      qInfo("valley: largest error per level (m):%s", qPrintable(t));
    }
    qInfo("valley: %zu triangles, %zu pages; budget %.2f MiB (%zu slots)", valley().whole.data->triangleCount(),
          size_t(c.index.pageCount), budgetMb, size_t(c.index.pageCount) / 10);
    render::OffscreenRenderer unlimited;
    std::string error;
    QVERIFY2(unlimited.initialize(error), error.c_str());
    size_t maxWanted = 0;
    for (int step = 0; step < 6; ++step) {
      // A survey flight 60 m over the ground, looking down ahead.
      const glm::dvec3 eye(-600.0 + 200.0 * step, -300.0, 100.0);
      auto s = sceneOf(valley(), true, eye, eye + glm::dvec3(20.0, 30.0, -90.0), 1.0);
      auto limited = s;
      limited.settings.clusterGpuBudgetMb = budgetMb;
      const render::RenderView v = viewOf(s, 160, 120);
      render::FrameStats a, b;
      const hs::Image imgLimited = r_.render(limited, v, false, &a);
      const hs::Image imgUnlimited = unlimited.render(s, v, false, &b);
      qInfo("step %d: %zu clusters, %zu pages resident (%.2f MiB of %.2f), %s; unlimited: %zu clusters, %zu pages "
            "drawn, %zu resident",
            step, a.clusters.clusters, a.clusters.pagesResident, double(a.clusters.gpuBytes) / 1048576.0, budgetMb,
            a.clusters.complete ? "whole" : "not whole", b.clusters.clusters, b.clusters.pagesDrawn,
            b.clusters.pagesResident);
      QCOMPARE(a.clusters.instances, size_t(1));
      QVERIFY(double(a.clusters.gpuBytes) <= budgetMb * 1048576.0 + 1.0);
      QVERIFY(a.clusters.complete && b.clusters.complete);
      QCOMPARE(a.clusters.clusters, b.clusters.clusters);
      QVERIFY(imgLimited.rgba8 == imgUnlimited.rgba8);
      maxWanted = std::max(maxWanted, a.clusters.pagesResident);
    }
    QVERIFY(maxWanted > 0);
  }

  // A frame that may not stream is the same in any run; the viewport's
  // streaming frames start with what is resident and converge on it.
  void waitingAndStreamingFrames() {
    const glm::dvec3 c = glm::dvec3(bunny().whole.data->bounds().center()) * 10.0;
    const auto s = sceneOf(bunny(), true, c + glm::dvec3(0.2, -1.2, 0.4), c, 10.0);
    const render::RenderView v = viewOf(s, 320, 240);
    render::OffscreenRenderer fresh;
    std::string error;
    QVERIFY2(fresh.initialize(error), error.c_str());
    const hs::Image waited = r_.render(s, v, false);
    render::RenderOptions stream;
    stream.streamClusters = true;
    render::FrameStats first;
    fresh.render(s, v, false, &first, stream);
    QVERIFY(!first.clusters.complete);  // nothing was resident yet
    int frames = 1;
    render::FrameStats last = first;
    hs::Image img;
    for (; frames < 200 && !last.clusters.complete; ++frames) {
      QTest::qWait(5);
      img = fresh.render(s, v, false, &last, stream);
    }
    qInfo("streaming: whole after %d frames", frames);
    QVERIFY(last.clusters.complete);
    QVERIFY(img.rgba8 == waited.rgba8);
    QVERIFY(fresh.render(s, v, false).rgba8 == waited.rgba8);
  }

  // A damaged page: the frame finishes, the page is named once, and the
  // coarser level covers its place (no hole).
  void damagedPageDrawsItsParent() {
    const scene::ClusterAsset& good = *bunny().clustered.clusters;
    std::vector<std::vector<uint8_t>> pages;
    for (uint32_t p = 0; p < good.pages->pageCount(); ++p) {
      std::string e;
      pages.push_back(*good.pages->read(p, e));
    }
    uint32_t victim = 0;  // a page of level-0 clusters
    while (good.index.clusters[good.index.pageFirst[victim]].level != 0) ++victim;
    pages[victim][pages[victim].size() / 2] ^= 0x55;
    scene::ClusterAsset damaged = good;
    damaged.pages = scene::ClusterPageStore::inMemory(std::move(pages), good.pages->pageHashes());
    Scan scan = bunny();
    scan.clustered.clusters = std::make_shared<const scene::ClusterAsset>(std::move(damaged));
    const glm::dvec3 c = glm::dvec3(bunny().whole.data->bounds().center()) * 10.0;
    const glm::dvec3 eye = c + glm::dvec3(0.0, -3.0, 0.5);
    const auto s = sceneOf(scan, true, eye, c, 10.0, 0.0);  // bound 0: every level-0 page wanted
    const auto full = sceneOf(scan, false, eye, c, 10.0, 0.0);
    const render::RenderView v = viewOf(s, 320, 240);
    (void)r_.renderer().takeClusterProblems();
    render::FrameStats stats;
    render::RenderOptions depth;
    depth.keepDepth = true;
    r_.render(s, v, false, &stats, depth);
    const auto mCut = coverage(r_, 320, 240);
    const std::vector<std::string> problems = r_.renderer().takeClusterProblems();
    QCOMPARE(problems.size(), size_t(1));
    QVERIFY2(problems[0].find("cluster page " + std::to_string(victim)) != std::string::npos &&
                 problems[0].find("checksum") != std::string::npos && problems[0].find("'clustered'") != std::string::npos,
             problems[0].c_str());
    QVERIFY(!stats.clusters.complete);
    QCOMPARE(stats.clusters.instances, size_t(1));
    r_.render(full, v, false, nullptr, depth);
    QCOMPARE(holes(coverage(r_, 320, 240), mCut, 320, 240, 3), size_t(0));
    r_.render(s, v, false);
    QVERIFY(r_.renderer().takeClusterProblems().empty());  // once
  }

  // The right eye with the camera's view as its LOD view draws the left
  // eye's cut.
  void bothEyesShareTheCut() {
    const glm::dvec3 c = glm::dvec3(bunny().whole.data->bounds().center()) * 10.0;
    const auto s = sceneOf(bunny(), true, c + glm::dvec3(0.2, -1.2, 0.4), c, 10.0);
    const render::RenderView mono = viewOf(s, 320, 240);
    render::RenderView right = mono;
    right.eye += 0.3 * mono.right();
    const render::FrameStats left = r_.renderOnly(s, mono);
    const render::FrameStats alone = r_.renderOnly(s, right);
    render::RenderOptions shared;
    shared.lodView = &mono;
    const render::FrameStats rightShared = r_.renderOnly(s, right, shared);
    qInfo("cut triangles: left %zu, right alone %zu, right with the camera's view %zu", left.clusters.triangles,
          alone.clusters.triangles, rightShared.clusters.triangles);
    QVERIFY(alone.clusters.triangles != left.clusters.triangles);
    QCOMPARE(rightShared.clusters.triangles, left.clusters.triangles);
    QCOMPARE(rightShared.clusters.clusters, left.clusters.clusters);
  }
};

QTEST_GUILESS_MAIN(TestClusterRender)
#include "test_cluster_render.moc"
