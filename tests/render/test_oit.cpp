// Transparency (render/oit.h, render/abuffer.h) on a headless EGL context
// (llvmpipe: no fragment shader interlock, no 64-bit atomics): the A-buffer
// against depth peeling (the exact reference, computed by the renderer),
// the K-buffer against the A-buffer bit for bit when K covers the depth
// complexity, every mode's determinism over 20 renders of one frame, 1000
// layers per pixel under a small memory cap (overflow reported, memory
// within the cap, the tail's image against the closed form), the
// depth-complexity count against the scene's construction, and that a
// frame without translucent surfaces has no OIT pass or buffer.
#include <QtTest>

#include <cmath>

#include "oit_scenes.h"
#include "render/offscreen_renderer.h"
#include "scene/fields.h"
#include "scene/scene_json.h"

using namespace hs;
using scene::Transparency;

namespace {

const char* modeName(Transparency t) {
  static const char* const names[] = {"abuffer", "abuffer_fixed", "kbuffer", "weighted", "reference"};
  return names[int(t)];
}

int maxChannelDifference(const Image& a, const Image& b) {
  int worst = 0;
  for (size_t i = 0; i < a.rgba8.size(); ++i) worst = std::max(worst, std::abs(int(a.rgba8[i]) - int(b.rgba8[i])));
  return worst;
}

size_t oitAllocations(const render::Renderer& r, size_t* bytes = nullptr) {
  size_t n = 0;
  if (bytes) *bytes = 0;
  for (const render::GpuAllocation& a : r.resourceRegistry())
    if (a.name.rfind("oit_", 0) == 0) {
      ++n;
      if (bytes) *bytes += a.bytes;
    }
  return n;
}

bool passRan(const render::FrameStats& s, const std::string& prefix) {
  for (const render::PassStats& p : s.passes)
    if (p.name.rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace

class TestOit : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // The A-buffer (sorted ranges), and the fixed array that is one,
  // composite what depth peeling composites,
  // lit and unlit, within 1/255 per channel of the 8-bit output; and
  // translucency shows (the image differs from the same scene opaque).
  void abufferMatchesReference() {
    for (bool lit : {false, true}) {
      test::OitScene sc = test::stackScene(6, lit);
      sc.state.settings.transparency = Transparency::Reference;
      render::FrameStats refStats;
      const Image ref = r_.render(sc.state, sc.view, false, &refStats);
      QCOMPARE(refStats.oit.peels, 6);  // the deepest pixel has 6 layers: 6 peels find fragments
      sc.state.settings.transparency = Transparency::ABuffer;
      render::FrameStats stats;
      const Image img = r_.render(sc.state, sc.view, false, &stats);
      const int diff = maxChannelDifference(img, ref);
      qInfo("lit %d: abuffer vs reference max difference %d/255, %llu fragments, max %u per pixel", int(lit), diff,
            (unsigned long long)stats.oit.fragments, stats.oit.maxPerPixel);
      QVERIFY(diff <= 1);
      QCOMPARE(stats.oit.maxPerPixel, 6u);
      QCOMPARE(stats.oit.overflow, uint64_t(0));
      sc.state.settings.transparency = Transparency::ABufferFixed;
      const Image fixedImg = r_.render(sc.state, sc.view, false, &stats);
      const int fixedDiff = maxChannelDifference(fixedImg, ref);
      qInfo("lit %d: abuffer_fixed vs reference max difference %d/255", int(lit), fixedDiff);
      QVERIFY(fixedDiff <= 1);
      QCOMPARE(stats.oit.layers, 16);
      QCOMPARE(stats.oit.overflow, uint64_t(0));
      test::OitScene opaque = sc;
      for (auto& [id, m] : opaque.state.materials) m.opacity = 1.0f;
      const Image opaqueImg = r_.render(opaque.state, opaque.view);
      QVERIFY(maxChannelDifference(opaqueImg, img) > 40);
    }
  }

  // Small triangles (a lit two-sided sphere of 18k triangles in front of
  // the stack): every sorting mode stays within 1/255 of depth peeling.
  // (Linked lists built with atomics in the lit shader were 38/255 off
  // here on llvmpipe: render/abuffer.h.)
  void sortingModesMatchReferenceOnSmallTriangles() {
    test::OitScene sc = test::stackScene(4, true, 96);
    scene::MeshAsset a;
    a.id = 100;
    a.name = "Sphere";
    mesh::MeshData sphere = mesh::uvSphere(1.2f, 96, 48);
    a.contentHash = mesh::contentHash(sphere);
    a.data = std::make_shared<const mesh::MeshData>(std::move(sphere));
    scene::Material m;
    m.id = 100;
    m.asset = a.id;
    m.name = "Sphere / glass";
    m.baseColor = {0.6f, 0.8f, 0.9f};
    m.opacity = 0.3f;
    a.materialSlots.assign(scene::materialSlotCount(*a.data), m.id);
    sc.state.materials.emplace(m.id, m);
    sc.state.assets.emplace(a.id, a);
    test::addInstance(sc.state, 100, 100, {0.2, -0.1, 2.5});
    sc.state.settings.transparency = Transparency::Reference;
    const Image ref = r_.render(sc.state, sc.view);
    sc.state.settings.transparency = Transparency::ABuffer;
    render::FrameStats stats;
    const Image img = r_.render(sc.state, sc.view, false, &stats);
    const int diff = maxChannelDifference(img, ref);
    QVERIFY(stats.oit.maxPerPixel >= 6);
    QVERIFY(diff <= 1);
    sc.state.settings.transparency = Transparency::ABufferFixed;
    const Image fixedImg = r_.render(sc.state, sc.view);
    const int fixedDiff = maxChannelDifference(fixedImg, ref);
    QVERIFY(fixedDiff <= 1);
    sc.state.settings.transparency = Transparency::KBuffer;
    sc.state.settings.kbufferK = 16;
    const Image k = r_.render(sc.state, sc.view);
    const int kdiff = maxChannelDifference(k, ref);
    qInfo("vs reference: abuffer %d/255, abuffer_fixed %d/255, kbuffer K=16 %d/255", diff, fixedDiff, kdiff);
    QVERIFY(kdiff <= 1);
  }

  // Two layers 0.1 mm apart 8 m away: their depths agree in the top 24
  // bits, where the 32-bit key orders by a hash of object and primitive,
  // not by depth. The A-buffer sorts by the full depth and still matches
  // depth peeling; the K-buffer (key order) shows what ordering by the key
  // alone would do here.
  void nearlyCoplanarLayersInDepthOrder() {
    test::OitScene sc = test::deepScene(0, {0.5f, 0.5f, 0.5f}, 0.5f, 64);
    test::addQuadAsset(sc.state, 10, 20.0f, {0.95f, 0.1f, 0.1f}, 0.6f, true);
    test::addQuadAsset(sc.state, 11, 20.0f, {0.1f, 0.2f, 0.95f}, 0.6f, true);
    test::addInstance(sc.state, 10, 10, {0, 0, 0.0});
    test::addInstance(sc.state, 11, 11, {0, 0, 0.0001});
    sc.state.settings.transparency = Transparency::Reference;
    const Image ref = r_.render(sc.state, sc.view);
    sc.state.settings.transparency = Transparency::ABuffer;
    render::FrameStats stats;
    const Image img = r_.render(sc.state, sc.view, false, &stats);
    QCOMPARE(stats.oit.maxPerPixel, 2u);
    sc.state.settings.transparency = Transparency::KBuffer;
    const Image k = r_.render(sc.state, sc.view);
    const int diff = maxChannelDifference(img, ref), kdiff = maxChannelDifference(k, ref);
    qInfo("0.1 mm apart: abuffer %d/255 from depth peeling, kbuffer (key order) %d/255", diff, kdiff);
    QVERIFY(kdiff > 1);  // the key alone does misorder them here, so the case is tested
    QVERIFY(diff <= 1);
  }

  // With K at least the depth complexity the K-buffer stores every
  // fragment in the A-buffer's order: the same bits. With K below it the
  // rest goes to the tail (reported) and the image differs, but not much.
  void kbufferEqualsABuffer() {
    test::OitScene sc = test::stackScene(6, true);
    const Image a = r_.render(sc.state, sc.view);
    sc.state.settings.transparency = Transparency::KBuffer;
    for (int k : {6, 8, 32}) {
      sc.state.settings.kbufferK = k;
      render::FrameStats stats;
      const Image img = r_.render(sc.state, sc.view, false, &stats);
      QCOMPARE(maxChannelDifference(img, a), 0);
      QCOMPARE(stats.oit.overflow, uint64_t(0));
      QCOMPARE(stats.oit.layers, k);
    }
    sc.state.settings.kbufferK = 2;
    render::FrameStats stats;
    const Image img = r_.render(sc.state, sc.view, false, &stats);
    const int diff = maxChannelDifference(img, a);
    qInfo("K=2: %llu fragments to the tail, tail share %.3f, max difference %d/255",
          (unsigned long long)stats.oit.overflow, stats.oit.tailShare, diff);
    QVERIFY(stats.oit.overflow > 0);
    QVERIFY(stats.oit.tailShare > 0.0 && stats.oit.tailShare < 1.0);
    QVERIFY(diff > 0);
  }

  // A translucent quad that cuts through the opaque backdrop, with MSAA:
  // fragments right at the opaque depth (a resolved multisample depth
  // there) are drawn by the key pass and the lit pass alike, so none finds
  // no key and lands in the tail (before the lit pass tested depth early
  // too, the demo's bunny on its ground lost 82 fragments so), and the
  // A-buffer still equals the K-buffer.
  void crossingTheOpaqueSurfaceWithMsaa() {
    test::OitScene sc = test::stackScene(2, true, 96);
    sc.state.settings.antialiasing = scene::Antialiasing::Msaa4;
    test::addQuadAsset(sc.state, 50, 6.0f, {0.9f, 0.6f, 0.2f}, 0.5f, false);
    test::addInstance(sc.state, 50, 50, {0, 0, -1});
    sc.state.entities.at(50).transform.rotation = scene::fromEulerDegrees({35, 10, 0});
    Image first;
    for (Transparency mode : {Transparency::ABuffer, Transparency::ABufferFixed, Transparency::KBuffer}) {
      sc.state.settings.transparency = mode;
      render::FrameStats stats;
      const Image img = r_.render(sc.state, sc.view, false, &stats);
      qInfo("%s: %llu fragments, overflow %llu", modeName(mode), (unsigned long long)stats.oit.fragments,
            (unsigned long long)stats.oit.overflow);
      QVERIFY(stats.oit.fragments > 0);
      QCOMPARE(stats.oit.overflow, uint64_t(0));
      if (first.rgba8.empty()) first = img;
      else QCOMPARE(maxChannelDifference(img, first), 0);
    }
  }

  // The thesis's K-buffer raced; nothing here may: each mode renders the
  // same frame 20 times with the same bits.
  void deterministic() {
    test::OitScene sc = test::stackScene(9, true, 80);
    sc.state.settings.kbufferK = 4;  // below the depth complexity: the tail is exercised too
    for (Transparency t : {Transparency::ABuffer, Transparency::ABufferFixed, Transparency::KBuffer,
                           Transparency::Weighted, Transparency::Reference}) {
      sc.state.settings.transparency = t;
      const Image first = r_.render(sc.state, sc.view);
      for (int i = 1; i < 20; ++i) {
        const Image again = r_.render(sc.state, sc.view);
        if (again.rgba8 != first.rgba8) QFAIL(qPrintable(QString("%1 differs on render %2").arg(modeName(t)).arg(i)));
      }
    }
  }

  // Under a memory cap the A-buffer keeps each pixel's nearest fragments
  // (as many as the cap allows every pixel) and the fixed array its
  // nearest 16 or fewer; the rest go to the tail. So each equals the
  // K-buffer with K their layers, bit for bit, whatever the arrival order.
  void cappedKeepsTheNearest() {
    test::OitScene sc = test::stackScene(24, false, 100);
    sc.state.settings.oitMemoryMb = 1.0;
    for (Transparency mode : {Transparency::ABuffer, Transparency::ABufferFixed}) {
      sc.state.settings.transparency = mode;
      render::FrameStats stats;
      const Image img = r_.render(sc.state, sc.view, false, &stats);
      const int layers = stats.oit.layers;
      qInfo("%s under 1 MiB: %d per pixel of up to %u, overflow %llu, %zu bytes", modeName(mode), layers,
            stats.oit.maxPerPixel, (unsigned long long)stats.oit.overflow, stats.oit.bytes);
      QVERIFY(layers >= 1 && uint32_t(layers) < stats.oit.maxPerPixel);
      QVERIFY(stats.oit.overflow > 0);
      QVERIFY(stats.oit.bytes <= size_t(1) << 20);
      test::OitScene k = sc;
      k.state.settings.transparency = Transparency::KBuffer;
      k.state.settings.kbufferK = layers;
      k.state.settings.oitMemoryMb = 256.0;
      render::FrameStats kStats;
      const Image kImg = r_.render(k.state, k.view, false, &kStats);
      QCOMPARE(kStats.oit.layers, layers);
      QCOMPARE(kStats.oit.overflow, stats.oit.overflow);
      QCOMPARE(maxChannelDifference(img, kImg), 0);
    }
  }

  // 1000 layers per pixel under a 1 MiB cap: overflow reported, the OIT
  // buffers within the cap (the registry's bytes), and the image close to
  // the closed form c (1 - (1 - a)^n) + b (1 - a)^n, thanks to the tail.
  void thousandLayers() {
    const int n = 1000;
    const glm::vec3 c(0.9f, 0.5f, 0.1f), back(0.1f, 0.1f, 0.6f);
    const float a = 0.002f;
    test::OitScene sc = test::deepScene(n, c, a);
    sc.state.settings.oitMemoryMb = 1.0;
    const double t = std::pow(1.0 - double(a), n);
    for (Transparency mode : {Transparency::ABuffer, Transparency::ABufferFixed, Transparency::KBuffer}) {
      sc.state.settings.transparency = mode;
      render::FrameStats stats;
      const Image hdr = r_.render(sc.state, sc.view, true, &stats);
      size_t bytes = 0;
      oitAllocations(r_.renderer(), &bytes);
      qInfo("%s: %llu fragments, max %u per pixel, overflow %llu, tail share %.3f, %zu bytes (registry %zu)",
            modeName(mode), (unsigned long long)stats.oit.fragments, stats.oit.maxPerPixel,
            (unsigned long long)stats.oit.overflow, stats.oit.tailShare, stats.oit.bytes, bytes);
      QCOMPARE(stats.oit.maxPerPixel, uint32_t(n));
      QVERIFY(stats.oit.overflow > 0);
      QVERIFY(bytes <= size_t(1) << 20);
      QVERIFY(stats.oit.bytes <= size_t(1) << 20);
      for (int ch = 0; ch < 3; ++ch) {
        const double expected = double(c[ch]) * (1.0 - t) + double(back[ch]) * t;
        const float got = hdr.rgbaF[(size_t(24) * 48 + 24) * 4 + size_t(ch)];
        if (std::abs(double(got) - expected) > 0.03)
          QFAIL(qPrintable(QString("%1 channel %2: %3, expected %4").arg(modeName(mode)).arg(ch).arg(got).arg(expected)));
      }
    }
  }

  // The depth-complexity count is the scene's: a pixel under all of the
  // deep scene's layers has them all, and the mean over covered pixels is
  // that too.
  void fragmentCounts() {
    test::OitScene sc = test::deepScene(7, {0.5f, 0.5f, 0.5f}, 0.3f, 32);
    for (Transparency mode : {Transparency::ABuffer, Transparency::ABufferFixed, Transparency::KBuffer,
                              Transparency::Weighted, Transparency::Reference}) {
      sc.state.settings.transparency = mode;
      render::FrameStats stats;
      render::RenderOptions o;
      o.oitCounts = true;
      r_.render(sc.state, sc.view, false, &stats, o);
      QVERIFY(stats.oit.active);
      QVERIFY(stats.oit.counted);
      QCOMPARE(stats.oit.maxPerPixel, 7u);
      QCOMPARE(stats.oit.coveredPixels, uint64_t(32 * 32));
      QCOMPARE(stats.oit.meanPerPixel, 7.0);
      QCOMPARE(stats.oit.mode, std::string(modeName(mode)));
    }
  }

  // No translucent surface in view: no OIT pass ran and no OIT buffer is
  // in the registry; one in view: they are there.
  void costsNothing() {
    test::OitScene sc = test::stackScene(3, false, 64);
    render::FrameStats stats;
    r_.render(sc.state, sc.view, false, &stats);
    QVERIFY(passRan(stats, "oit_"));
    QVERIFY(oitAllocations(r_.renderer()) > 0);
    QVERIFY(stats.oit.active && stats.oit.bytes > 0);
    for (auto& [id, m] : sc.state.materials) m.opacity = 1.0f;
    r_.render(sc.state, sc.view, false, &stats);
    QVERIFY(!passRan(stats, "oit_"));
    QCOMPARE(oitAllocations(r_.renderer()), size_t(0));
    QVERIFY(!stats.oit.active);
    QCOMPARE(stats.oit.bytes, size_t(0));
    // Translucent but out of view: nothing either.
    test::OitScene away = test::stackScene(3, false, 64);
    away.view.orientation = test::lookFrom(away.view.eye, {0, 0, 20}).rotation;
    r_.render(away.state, away.view, false, &stats);
    QVERIFY(!passRan(stats, "oit_"));
    QCOMPARE(oitAllocations(r_.renderer()), size_t(0));
  }

  // Bad values of the settings and of opacity: refused by the fields (the
  // CLI's `set` and the editor ask fieldValueProblem), clamped by the
  // setters (a loaded file), and a frame set to extremes in code renders.
  void badInput() {
    for (auto [key, text] : {std::pair{"kbuffer_k", "0"}, {"kbuffer_k", "1000"}, {"oit_memory_mb", "0"},
                             {"oit_memory_mb", "nan"}, {"transparency", "sorted"}}) {
      const scene::SettingsField* f = scene::findSettingsField(key);
      QVERIFY(f);
      std::string error;
      const auto v = scene::parseFieldValue(*f, text, error);
      if (v) error = scene::fieldValueProblem(*f, *v, static_cast<const scene::SceneSettings*>(nullptr));
      qInfo("%s %s: %s", key, text, error.c_str());
      QVERIFY(!error.empty());
      // Range problems name the field (the CLI and the loader add its key to every message).
      if (std::string(text) != "nan" && std::string(text) != "sorted") QVERIFY(error.find(f->label) != std::string::npos);
    }
    const scene::MaterialField* opacity = scene::findMaterialField("opacity");
    for (const char* text : {"nan", "-0.5", "1.5"}) {
      std::string error;
      const auto v = scene::parseFieldValue(*opacity, text, error);
      if (v) error = scene::fieldValueProblem(*opacity, *v, static_cast<const scene::Material*>(nullptr));
      QVERIFY2(!error.empty(), text);
    }
    scene::SceneSettings s;
    scene::findSettingsField("kbuffer_k")->set(s, scene::FieldValue(1000.0));
    QCOMPARE(s.kbufferK, 32);
    scene::findSettingsField("kbuffer_k")->set(s, scene::FieldValue(0.0));
    QCOMPARE(s.kbufferK, 1);
    scene::findSettingsField("oit_memory_mb")->set(s, scene::FieldValue(0.0));
    QCOMPARE(s.oitMemoryMb, 1.0);
    // A loaded file: without the fields (written before them), the defaults;
    // with bad values, each clamped and named in a warning.
    {
      Json j = scene::sceneToJson(test::stackScene(2, false, 32).state);
      for (const char* key : {"transparency", "kbuffer_k", "oit_memory_mb"}) j["settings"].erase(key);
      std::string error;
      bool notJson = false;
      const auto old = scene::sceneFromJsonText(j.dump(), error, notJson);
      QVERIFY2(old, error.c_str());
      QCOMPARE(old->settings.transparency, Transparency::ABuffer);
      QCOMPARE(old->settings.kbufferK, 8);
      QCOMPARE(old->settings.oitMemoryMb, 256.0);
      j["settings"]["kbuffer_k"] = 1000;
      j["settings"]["oit_memory_mb"] = 0;
      std::vector<std::string> warnings;
      const auto bad = scene::sceneFromJsonText(j.dump(), error, notJson, &warnings);
      QVERIFY2(bad, error.c_str());
      QCOMPARE(bad->settings.kbufferK, 32);
      QCOMPARE(bad->settings.oitMemoryMb, 1.0);
      std::string all;
      for (const std::string& w : warnings) all += w + "\n";
      qInfo("%s", all.c_str());
      QVERIFY(all.find("kbuffer_k") != std::string::npos && all.find("oit_memory_mb") != std::string::npos);
    }
    // Values only code can set still render: the renderer clamps again.
    test::OitScene sc = test::stackScene(3, false, 32);
    sc.state.settings.transparency = Transparency::KBuffer;
    sc.state.settings.kbufferK = 1000;
    sc.state.settings.oitMemoryMb = 0.0;
    render::FrameStats stats;
    const Image img = r_.render(sc.state, sc.view, false, &stats);
    QCOMPARE(img.width, 32);
    QVERIFY(stats.oit.layers >= 1 && stats.oit.layers <= 32);
  }
};

QTEST_GUILESS_MAIN(TestOit)
#include "test_oit.moc"
