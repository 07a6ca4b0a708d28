// Import at scale and georeferencing, through to processing: bad files each
// with a clear message, UV-less scans, textures that fail to decode,
// offset sidecars (Pix4D, OpenDroneMap, plain, by hand), multi-tile scans
// welded into one asset at UTM coordinates.
#include <QTemporaryDir>
#include <QtTest>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <thread>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "mesh/mesh_import.h"
#include "mesh/tile_merge.h"
#include "meshproc/mesh_process.h"
#include "mesh_builders.h"

using namespace hs::mesh;
namespace fs = std::filesystem;

namespace {

std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

bool anyWarning(const ImportReport& r, const std::string& a, const std::string& b = "") {
  for (const auto& w : r.warnings)
    if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
  return false;
}

ImportOptions zUp() {
  ImportOptions o;
  o.up = UpAxis::Z;
  return o;
}

}  // namespace

class TestMeshprocImport : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  std::string path(const char* name) { return tmp_.filePath(name).toStdString(); }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  void truncatedObjNamesTheLine() {
    hs::test::writeObj(path("whole.obj"), hs::test::curvedGrid(10, 1.0, 0.1, false));
    std::string text = readFile(path("whole.obj"));
    const size_t cut = text.find("\nf ", text.size() / 2) + 6;  // in the middle of a face line
    const size_t line = size_t(std::count(text.begin(), text.begin() + long(cut), '\n')) + 1;
    hs::test::writeText(path("cut.obj"), text.substr(0, cut));
    const ImportResult r = importMesh(path("cut.obj"), zUp());
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("cut.obj:" + std::to_string(line) + ":") != std::string::npos, r.error.c_str());
    QVERIFY2(r.error.find("truncated") != std::string::npos, r.error.c_str());
  }

  void truncatedFbxIsRefusedWithAMessage() {
    const std::string fbx = readFile(HS_TEST_DATA_DIR "/mesh/textured_quad.fbx");
    QVERIFY(fbx.size() > 1000);
    hs::test::writeText(path("cut.fbx"), fbx.substr(0, fbx.size() / 2));
    const ImportResult r = importMesh(path("cut.fbx"));
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("cut.fbx") != std::string::npos, r.error.c_str());
  }

  // A file of several chunks (the reader cuts at 4 MB and parses chunks on
  // all cores): absolute and relative indices, comments and materials
  // switching every 500 faces cross chunk borders, and the mesh must come
  // back exactly as written.
  void largeObjReadInChunksComesBackExactly() {
    const MeshData src = hs::test::curvedGrid(260, 100.0, 2.0, false);  // 135k triangles, ~9 MB
    std::string text = "mtllib none.mtl\n";
    char buf[160];
    const size_t half = src.vertexCount() / 2;
    for (size_t v = 0; v < src.vertexCount(); ++v) {
      std::snprintf(buf, sizeof buf, "v %.9f %.9f %.9f\nvt %.9f %.9f\n", double(src.positions[v].x),
                    double(src.positions[v].y), double(src.positions[v].z), double(src.uvs[v].x),
                    1.0 - double(src.uvs[v].y));
      text += buf;
      if (v == half) text += "# second half of the vertices\n";
    }
    size_t defined = src.vertexCount();
    for (size_t f = 0; f < src.triangleCount(); ++f) {
      if (f % 500 == 0) text += "usemtl m" + std::to_string((f / 500) % 3) + "\n";
      const uint32_t* t = &src.indices[f * 3];
      if (f % 2)  // relative indices: -1 is the last vertex defined
        std::snprintf(buf, sizeof buf, "f %lld/%lld %lld/%lld %lld/%lld\n", (long long)t[0] - (long long)defined,
                      (long long)t[0] - (long long)defined, (long long)t[1] - (long long)defined,
                      (long long)t[1] - (long long)defined, (long long)t[2] - (long long)defined,
                      (long long)t[2] - (long long)defined);
      else
        std::snprintf(buf, sizeof buf, "f %u/%u %u/%u %u/%u\n", t[0] + 1, t[0] + 1, t[1] + 1, t[1] + 1, t[2] + 1, t[2] + 1);
      text += buf;
    }
    QVERIFY(text.size() > 8u << 20);
    hs::test::writeText(path("chunks.obj"), text);
    ImportOptions o = zUp();
    o.recenter = false;
    const ImportResult r = importMesh(path("chunks.obj"), o);
    QVERIFY2(r.ok(), r.error.c_str());
    const MeshData& m = *r.mesh;
    QCOMPARE(m.triangleCount(), src.triangleCount());
    QCOMPARE(m.vertexCount(), src.vertexCount());
    QCOMPARE(m.materials.size(), size_t(3));
    QCOMPARE(m.submeshes.size(), (src.triangleCount() + 499) / 500);
    // Faces in file order, corners as written (vertex ids follow first use).
    for (size_t c = 0; c < m.indices.size(); ++c) {
      const glm::dvec3 got = m.origin + glm::dvec3(m.positions[m.indices[c]]);
      const glm::dvec3 want(src.positions[src.indices[c]]);
      QVERIFY2(glm::length(got - want) < 1e-6, qPrintable(QString("corner %1").arg(c)));
      QVERIFY(glm::length(m.uvs[m.indices[c]] - src.uvs[src.indices[c]]) < 1e-6f);
    }
    for (size_t s = 0; s < m.submeshes.size(); ++s) QCOMPARE(m.submeshes[s].material, int(s % 3));
    QVERIFY2(anyWarning(r.report, "none.mtl"), "the missing material library is reported");
  }

  void zeroByteFile() {
    hs::test::writeText(path("empty.obj"), "");
    const ImportResult r = importMesh(path("empty.obj"));
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("empty.obj") != std::string::npos && r.error.find("0 bytes") != std::string::npos,
             r.error.c_str());
  }

  void meshWithNoFaces() {
    hs::test::writeText(path("points.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const ImportResult r = importMesh(path("points.obj"));
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("no faces") != std::string::npos, r.error.c_str());
  }

  void uvLessScanProcesses() {
    hs::test::writeObj(path("nouv.obj"), hs::test::curvedGrid(30, 5.0, 0.5, false), glm::dvec3(0.0), 9, false);
    ImportResult r = importMesh(path("nouv.obj"), zUp());
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.mesh->uvs.empty());
    ProcessOptions o;
    o.decimate = true;
    o.decimation.targetRatio = 0.1;
    const ProcessResult p = processMesh(std::move(*r.mesh), o);
    QVERIFY2(p.ok(), p.error.c_str());
    QVERIFY(p.mesh.uvs.empty());
    QVERIFY(p.report.errorMeasured);
    QVERIFY(!p.report.error.uvMeasured);  // nothing to displace
    QVERIFY(p.report.error.hausdorff > 0);
  }

  void textureThatFailsToDecode() {
    hs::test::writeText(path("broken.png"), "this is not a PNG");
    hs::test::writeText(path("tex.mtl"), "newmtl stone\nKd 1 1 1\nmap_Kd broken.png\n");
    hs::test::writeText(path("tex.obj"), "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl stone\nf 1/1 2/2 3/3\n");
    const ImportResult r = importMesh(path("tex.obj"), zUp());
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY2(anyWarning(r.report, "broken.png"), r.report.warnings.empty() ? "" : r.report.warnings[0].c_str());
    QVERIFY(r.mesh->textures.empty());
    // The processing pipeline takes the untextured result and skips texels.
    ProcessOptions o;
    o.decimate = true;
    o.decimation.targetRatio = 1.0;
    const ProcessResult p = processMesh(*r.mesh, o);
    QVERIFY(p.ok());
    QVERIFY(!p.report.error.uvMeasured);
    ImportOptions strict = zUp();
    strict.strictTextures = true;
    const ImportResult s = importMesh(path("tex.obj"), strict);
    QVERIFY(!s.ok());
    QVERIFY2(s.error.find("broken.png") != std::string::npos, s.error.c_str());
  }

  void offsetSidecars_data() {
    QTest::addColumn<QString>("sidecarName");
    QTest::addColumn<QString>("content");
    QTest::addColumn<double>("x");
    QTest::addColumn<double>("y");
    QTest::addColumn<double>("z");
    QTest::addColumn<QString>("crs");
    QTest::newRow("pix4d") << "scan_offset.xyz" << "656059.000 5514553.000 1713.000\n" << 656059.0 << 5514553.0 << 1713.0 << "";
    QTest::newRow("odm") << "odm_georeferencing_model_geo.txt" << "WGS84 UTM 32N\n322263 5157982\n" << 322263.0
                         << 5157982.0 << 0.0 << "WGS84 UTM 32N";
    QTest::newRow("plain") << "scan.offset" << "# site origin\n500000.5, 4400000.25, 12\n" << 500000.5 << 4400000.25
                           << 12.0 << "";
  }
  void offsetSidecars() {
    QFETCH(QString, sidecarName);
    QFETCH(QString, content);
    QFETCH(double, x);
    QFETCH(double, y);
    QFETCH(double, z);
    QFETCH(QString, crs);
    const fs::path dir = fs::path(path(qPrintable(QString("geo_") + QTest::currentDataTag())));
    fs::create_directories(dir);
    hs::test::writeObj((dir / "scan.obj").string(), hs::test::curvedGrid(4, 2.0, 0.0, false));
    hs::test::writeText((dir / sidecarName.toStdString()).string(), content.toStdString());
    ImportOptions o = zUp();
    o.geoOffsetMode = ImportOptions::GeoOffsetMode::Auto;
    const ImportResult r = importMesh((dir / "scan.obj").string(), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.report.geoOffset, glm::dvec3(x, y, z));
    QCOMPARE(QString::fromStdString(r.report.geoOffsetCrs), crs);
    // The grid's corner (0,0,0) in the file lands exactly on the offset.
    double best = 1e9;
    for (const auto& w : hs::test::world(*r.mesh)) best = std::min(best, glm::length(w - glm::dvec3(x, y, z)));
    QVERIFY(best < 1e-9);
    // Without Auto the file's coordinates are taken as they are.
    const ImportResult plain = importMesh((dir / "scan.obj").string(), zUp());
    QVERIFY(glm::length(plain.mesh->origin) < 10.0);
  }

  void offsetByHandAndBadOffsetFile() {
    hs::test::writeObj(path("hand.obj"), hs::test::curvedGrid(4, 2.0, 0.0, false));
    ImportOptions o = zUp();
    o.geoOffsetMode = ImportOptions::GeoOffsetMode::Manual;
    o.geoOffset = glm::dvec3(1000.25, 2000.5, 3.0);
    const ImportResult r = importMesh(path("hand.obj"), o);
    QVERIFY(r.ok());
    QCOMPARE(r.report.geoOffsetSource, std::string("set by hand"));
    QVERIFY(glm::length(r.mesh->origin - glm::dvec3(1001.25, 2001.5, 3.0)) < 1e-9);

    GeoOffset g;
    bool isAuto = false, isNone = false;
    std::string err;
    QVERIFY(parseGeoOffset("656059,5514553,1713", g, isAuto, isNone, err));
    QCOMPARE(g.offset, glm::dvec3(656059, 5514553, 1713));
    QVERIFY(parseGeoOffset("auto", g, isAuto, isNone, err) && isAuto);
    QVERIFY(!parseGeoOffset("north-east", g, isAuto, isNone, err));

    hs::test::writeText(path("bad_offset.txt"), "x y z\n");
    o.geoOffsetMode = ImportOptions::GeoOffsetMode::File;
    o.geoOffsetFile = path("bad_offset.txt");
    const ImportResult bad = importMesh(path("hand.obj"), o);
    QVERIFY(!bad.ok());
    QVERIFY2(bad.error.find("bad_offset.txt:1:") != std::string::npos, bad.error.c_str());
  }

  // Two tiles of one UTM scan, each written relative to its own Pix4D
  // offset: imported together they form one asset, each point where it
  // belongs, with the shared border welded.
  void multiTileScanImportsAsOneWeldedAsset() {
    const glm::dvec3 site(656000.0, 5514500.0, 1700.0);
    const MeshData grid = hs::test::curvedGrid(20, 20.0, 0.5, false);
    MeshData left = grid, right = grid;
    left.indices.clear(), right.indices.clear();
    for (size_t f = 0; f < grid.triangleCount(); ++f) {
      const glm::vec3 c = (grid.positions[grid.indices[f * 3]] + grid.positions[grid.indices[f * 3 + 1]] +
                           grid.positions[grid.indices[f * 3 + 2]]) / 3.0f;
      auto& dst = c.x < 10.0f ? left : right;
      dst.indices.insert(dst.indices.end(), {grid.indices[f * 3], grid.indices[f * 3 + 1], grid.indices[f * 3 + 2]});
    }
    left.submeshes = {{0, uint32_t(left.indices.size()), -1}};
    right.submeshes = {{0, uint32_t(right.indices.size()), -1}};
    fs::create_directories(path("tiles/a"));
    fs::create_directories(path("tiles/b"));
    // Different offsets per tile, as tools write them.
    const glm::dvec3 offA = site, offB = site + glm::dvec3(10.0, 0.0, 0.0);
    hs::test::writeObj(path("tiles/a/tile.obj"), left, -glm::dvec3(0.0), 9);
    hs::test::writeObj(path("tiles/b/tile.obj"), right, -glm::dvec3(10.0, 0.0, 0.0), 9);
    char buf[128];
    std::snprintf(buf, sizeof buf, "%.3f %.3f %.3f\n", offA.x, offA.y, offA.z);
    hs::test::writeText(path("tiles/a/tile_offset.xyz"), buf);
    std::snprintf(buf, sizeof buf, "%.3f %.3f %.3f\n", offB.x, offB.y, offB.z);
    hs::test::writeText(path("tiles/b/tile_offset.xyz"), buf);

    TileImportOptions o;
    o.import = zUp();
    o.import.geoOffsetMode = ImportOptions::GeoOffsetMode::Auto;
    const TileImportResult r = importTiles({path("tiles/a/tile.obj"), path("tiles/b/tile.obj")}, o);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.tiles.size(), size_t(2));
    QCOMPARE(r.mesh->triangleCount(), grid.triangleCount());
    // 21 shared border vertices merged into one each (no UVs differ).
    QCOMPARE(r.mesh->vertexCount(), grid.vertexCount());
    QCOMPARE(r.borderVerticesMerged, size_t(21));
    for (const auto& w : hs::test::world(*r.mesh)) {
      const glm::dvec3 local = w - site;
      QVERIFY(local.x > -1e-4 && local.x < 20.0001 && local.y > -1e-4 && local.y < 20.0001);
    }
    // One connected surface: the seam between the tiles is gone.
    ProcessOptions po;
    po.clean = false;
    po.decimate = true;
    po.decimation.targetRatio = 0.1;
    const ProcessResult p = processMesh(*r.mesh, po);
    QVERIFY(p.ok());
    QCOMPARE(p.report.decimation.boundaryVertices, size_t(80));  // the outer square only
  }

  // Four tiles read at once (maxParallel 4), finishing last-first: the
  // same mesh, reports and welds as reading them one by one.
  void tilesReadAtOnceMergeInTheOrderGiven() {
    const MeshData grid = hs::test::curvedGrid(24, 24.0, 0.5, false);
    std::vector<std::string> files;
    for (int k = 0; k < 4; ++k) {
      MeshData strip = grid;
      strip.indices.clear();
      for (size_t f = 0; f < grid.triangleCount(); ++f) {
        const float cx = (grid.positions[grid.indices[f * 3]].x + grid.positions[grid.indices[f * 3 + 1]].x +
                          grid.positions[grid.indices[f * 3 + 2]].x) / 3.0f;
        if (int(cx / 6.0f) == k)
          strip.indices.insert(strip.indices.end(),
                               {grid.indices[f * 3], grid.indices[f * 3 + 1], grid.indices[f * 3 + 2]});
      }
      strip.submeshes = {{0, uint32_t(strip.indices.size()), -1}};
      files.push_back(path(("strip" + std::to_string(k) + ".obj").c_str()));
      hs::test::writeObj(files.back(), strip, glm::dvec3(0.0), 9);
    }
    std::atomic<int> running{0}, mostAtOnce{0}, started{0}, done{0};
    std::atomic<bool> lastFirst{false};
    std::mutex m;
    std::vector<size_t> finished;
    auto waitUntil = [](auto ready) {
      for (int i = 0; i < 1000 && !ready(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    };
    TileImportOptions o;
    o.import = zUp();
    // With lastFirst, every tile starts before any ends and tile k ends only
    // after the tiles after it (waits, not sleeps: the order holds on a
    // loaded machine).
    o.readTile = [&](const std::string& file, const ImportOptions& io, const hs::Progress* p) {
      const int now = ++running;
      ++started;
      for (int seen = mostAtOnce.load(); now > seen && !mostAtOnce.compare_exchange_weak(seen, now);) {
      }
      const int k = file[file.size() - 5] - '0';
      if (lastFirst) {
        waitUntil([&] { return started.load() == 4; });
        waitUntil([&] { return done.load() >= 3 - k; });
      }
      ImportResult r = importMesh(file, io, p);
      --running;
      std::lock_guard lock(m);
      finished.push_back(size_t(k));
      ++done;
      return r;
    };
    o.maxParallel = 1;
    const TileImportResult serial = importTiles(files, o);
    QVERIFY2(serial.ok(), serial.error.c_str());
    QCOMPARE(mostAtOnce.load(), 1);
    QCOMPARE(finished, (std::vector<size_t>{0, 1, 2, 3}));

    finished.clear();
    mostAtOnce = 0, started = 0, done = 0;
    lastFirst = true;
    o.maxParallel = 4;
    std::mutex pm;
    std::vector<double> fractions;
    hs::Progress progress([&](double f, std::string_view) {
      std::lock_guard lock(pm);
      fractions.push_back(f);
    });
    const TileImportResult parallel = importTiles(files, o, &progress);
    QVERIFY2(parallel.ok(), parallel.error.c_str());
    QCOMPARE(mostAtOnce.load(), 4);
    QCOMPARE(finished, (std::vector<size_t>{3, 2, 1, 0}));
    QCOMPARE(contentHash(*parallel.mesh), contentHash(*serial.mesh));
    QCOMPARE(parallel.mesh->origin, serial.mesh->origin);
    QCOMPARE(parallel.borderVerticesMerged, serial.borderVerticesMerged);
    QVERIFY(parallel.borderVerticesMerged > 0);
    // Progress: the tiles' reading shares 0..0.9 of the bar (their mean),
    // the weld the rest, ending at 1.
    QVERIFY(fractions.size() > 4);
    QCOMPARE(fractions.back(), 1.0);
    QVERIFY(*std::max_element(fractions.begin(), fractions.end() - 2) <= 0.9 + 1e-12);
    QVERIFY(std::find_if(fractions.begin(), fractions.end(), [](double f) { return f > 0.2 && f <= 0.9; }) !=
            fractions.end());
    QCOMPARE(parallel.tiles.size(), size_t(4));
    for (size_t k = 0; k < 4; ++k) {
      QCOMPARE(parallel.tiles[k].file, files[k]);
      QCOMPARE(parallel.tiles[k].trianglesOut, serial.tiles[k].trianglesOut);
    }
  }

  // Tiles read at once fail as if read one by one: the first failing tile
  // in the order given is named even when a later one fails first; tiles
  // after it are cancelled (a reader waiting on Cancel returns at once) or
  // not started; a Cancel stops every tile.
  void tilesReadAtOnceFailAndCancelInOrder() {
    std::atomic<int> started{0};
    std::atomic<bool> lastSawCancel{false};
    auto waitForCancel = [](const hs::Progress* p) {
      for (int i = 0; i < 500 && !hs::isCancelled(p); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
      ImportResult r;
      r.cancelled = hs::isCancelled(p);
      r.error = r.cancelled ? "cancelled" : "never cancelled";
      return r;
    };
    TileImportOptions o;
    o.maxParallel = 4;
    auto waitFor = [](const std::atomic<bool>& flag) {
      for (int i = 0; i < 500 && !flag.load(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    };
    // "c" fails once all four run; "d" is then cancelled; "b" fails after
    // that, and "a" ends after that, so its thread finds "e" after a failure.
    o.readTile = [&](const std::string& file, const ImportOptions&, const hs::Progress* p) {
      ++started;
      ImportResult r;
      if (file == "b") {
        waitFor(lastSawCancel);
        r.error = "b is broken";
      } else if (file == "c") {
        for (int i = 0; i < 500 && started.load() < 4; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        r.error = "c is broken";
      } else if (file == "d") {
        r = waitForCancel(p);
        lastSawCancel = r.cancelled;
      } else if (file == "a") {
        waitFor(lastSawCancel);
        r.mesh = hs::test::curvedGrid(2, 1.0, 0.0, false);
      }
      return r;
    };
    const auto t0 = std::chrono::steady_clock::now();
    const TileImportResult failed = importTiles({"a", "b", "c", "d", "e"}, o);
    QVERIFY(!failed.ok());
    QCOMPARE(failed.error, std::string("tile 2 of 5: b is broken"));
    QVERIFY(!failed.cancelled);
    QCOMPARE(failed.tiles.size(), size_t(2));
    QVERIFY(lastSawCancel.load());
    QCOMPARE(started.load(), 4);  // "e" comes after a failure: never started
    QVERIFY(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(3));

    // A reader that throws: the exception reaches the caller, as when the
    // tiles were read on its thread; not when an earlier tile failed.
    o.readTile = [&](const std::string& file, const ImportOptions&, const hs::Progress*) -> ImportResult {
      ImportResult r;
      if (file == "bad") r.error = "bad is broken";
      else if (file == "throws") throw std::runtime_error("reader threw");
      else r.mesh = hs::test::curvedGrid(2, 1.0, 0.0, false);
      return r;
    };
    std::string what;
    try {
      importTiles({"a", "throws", "c"}, o);
    } catch (const std::runtime_error& e) {
      what = e.what();
    }
    QCOMPARE(what, std::string("reader threw"));
    const TileImportResult badFirst = importTiles({"bad", "throws"}, o);
    QCOMPARE(badFirst.error, std::string("tile 1 of 2: bad is broken"));

    started = 0;
    o.readTile = [&](const std::string&, const ImportOptions&, const hs::Progress* p) {
      ++started;
      return waitForCancel(p);
    };
    hs::Progress progress;
    std::thread canceller([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      progress.cancel();
    });
    const auto t1 = std::chrono::steady_clock::now();
    const TileImportResult cancelled = importTiles({"a", "b", "c"}, o, &progress);
    canceller.join();
    QVERIFY(!cancelled.ok());
    QVERIFY(cancelled.cancelled);
    QCOMPARE(started.load(), 3);
    QVERIFY(std::chrono::steady_clock::now() - t1 < std::chrono::seconds(2));
  }
};

QTEST_GUILESS_MAIN(TestMeshprocImport)
#include "test_meshproc_import.moc"
