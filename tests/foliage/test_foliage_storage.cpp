// Foliage types (declarations, validation, JSON), the 16-byte instance
// record (its error bounds, at UTM coordinates too), cell blobs (round
// trip, corrupt and truncated blobs), dirty tracking, stable ids, undo;
// impostor atlas blobs (round trip, every damage named).
#include <map>
#include <random>

#include "foliage/foliage_operations.h"
#include "foliage/impostor_images.h"
#include "foliage/manifest.h"
#include "foliage_fixtures.h"

using namespace fx;

namespace {

bool anyContains(const std::vector<std::string>& v, const std::vector<std::string>& parts) {
  for (const std::string& s : v) {
    bool all = true;
    for (const std::string& p : parts) all = all && s.find(p) != std::string::npos;
    if (all) return true;
  }
  return false;
}

// A store with two types and instances spread over several cells.
FoliageStore filled(size_t n, uint32_t seed, const glm::dvec3& base) {
  FoliageStore s;
  addType(s, type("Pine", 100, 1));
  FoliageType grass = type("Grass", 100, 1);
  grass.scaleMode = ScaleMode::XyZ;
  addType(s, grass);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 200.0), a(-1.0, 1.0);
  for (size_t i = 0; i < n; ++i) {
    Instance in;
    in.type = uint16_t(i % 2);
    in.surface = i % 3 == 0 ? Surface::Mesh : Surface::Terrain;
    in.position = base + glm::dvec3(u(rng), u(rng), u(rng) * 0.2);
    in.rotation = glm::normalize(glm::dquat(a(rng), a(rng), a(rng), a(rng)));
    in.scale = glm::dvec3(0.5 + u(rng) / 100.0);
    s.add(in, nullptr);
  }
  return s;
}

}  // namespace

class TestFoliageStorage : public QObject {
  Q_OBJECT
 private slots:
  void declarationsCoverEveryField() {
    FoliageType t = type("Pine", 250, 3);
    QVERIFY(validate(t).empty());
    const hs::Json j = toJson(t);
    size_t declared = 0;
    for (const hs::ParamDecl& p : foliageTypeParamDecls()) {
      QVERIFY2(j.contains(p.key), p.key.c_str());
      std::string error;
      QVERIFY2(hs::checkParam(p, p.defaultValue, error), error.c_str());
      ++declared;
    }
    QCOMPARE(j.size(), declared + 2);  // + name and mesh
    // Defaults of the declarations are the struct's.
    FoliageType d;
    d.mesh = "m";
    FoliageType fromDefaults;
    std::string error;
    hs::Json dj = hs::Json::object();
    dj["name"] = d.name;
    dj["mesh"] = "m";
    for (const hs::ParamDecl& p : foliageTypeParamDecls()) dj[p.key] = p.defaultValue;
    QVERIFY2(fromJson(dj, fromDefaults, error), error.c_str());
    QVERIFY(fromDefaults == d);
  }

  void validateNamesTypeAndField() {
    FoliageType t = type("Pine", -1, 3);
    auto e = validate(t);
    QVERIFY(anyContains(e, {"foliage type \"Pine\"", "density_per_ha", "-1", "out of range"}));
    t.densityPerHa = 1e9;
    QVERIFY(anyContains(validate(t), {"foliage type \"Pine\"", "density_per_ha", "1000000000"}));
    t = type("Pine", 10, 3);
    t.mesh.clear();
    QVERIFY(anyContains(validate(t), {"foliage type \"Pine\"", "mesh"}));
    t = type("Pine", 10, 3);
    t.slopeDeg = {40, 10};
    QVERIFY(anyContains(validate(t), {"foliage type \"Pine\"", "slope_deg", "not in order"}));
    t = type("Pine", 10, 3);
    t.cullDistance = 100;
    t.fadeLength = 200;
    QVERIFY(anyContains(validate(t), {"foliage type \"Pine\"", "fade_m"}));
    // The file's and the domain's path: clamped, with a warning naming both.
    std::vector<std::string> w;
    t = type("Pine", 1e9, 3);
    const FoliageType s = sanitized(t, w);
    QCOMPARE(s.densityPerHa, kMaxDensityPerHa);
    QVERIFY(anyContains(w, {"foliage type \"Pine\"", "Density", "1000000000"}));
  }

  void jsonIsStrict() {
    FoliageType t = type("Birch", 80, 2.5);
    t.scaleMode = ScaleMode::XyZ;
    t.scaleZ = {0.8, 1.6};
    t.layer = "Grass";
    t.layerWeight = {0.25, 1};
    t.surface = SurfaceFilter::Meshes;
    FoliageType back;
    std::string error;
    const std::string text = hs::writeJson(typesToJson({t, type("Rock", 5, 4)}));
    auto parsed = hs::parseJson(text, error);
    QVERIFY(parsed);
    std::vector<FoliageType> types;
    QVERIFY2(typesFromJson(*parsed, types, error), error.c_str());
    QCOMPARE(types.size(), size_t(2));
    QVERIFY(types[0] == t);

    hs::Json bad = toJson(t);
    bad["densty"] = 3;
    QVERIFY(!fromJson(bad, back, error, "types[0]"));
    QVERIFY2(error.find("types[0].densty") != std::string::npos && error.find("unknown key") != std::string::npos,
             error.c_str());
    bad = toJson(t);
    bad["spacing_m"] = "wide";
    QVERIFY(!fromJson(bad, back, error, "types[0]"));
    QVERIFY2(error.find("types[0].spacing_m") != std::string::npos && error.find("Birch") != std::string::npos,
             error.c_str());
    bad = toJson(t);
    bad["density_per_ha"] = 1e9;
    QVERIFY(!fromJson(bad, back, error));
    QVERIFY2(error.find("density_per_ha") != std::string::npos && error.find("out of range") != std::string::npos,
             error.c_str());
    bad = toJson(t);
    bad.erase("mesh");
    QVERIFY(!fromJson(bad, back, error));
    QVERIFY2(error.find("mesh") != std::string::npos, error.c_str());
    // Two types of one name.
    QVERIFY(!typesFromJson(typesToJson({t, t}), types, error));
    QVERIFY2(error.find("second foliage type named \"Birch\"") != std::string::npos, error.c_str());
  }

  // Every axis within half a step (2^-11 m) of what was stored, near the
  // origin and at UTM coordinates alike; re-encoding is idempotent.
  void quantisationErrorBound() {
    std::mt19937_64 rng(5);
    for (const glm::dvec3 base : {glm::dvec3(0.0), glm::dvec3(-3000, 1234, -50), glm::dvec3(5e5, 4.4e6, 350.0),
                                  glm::dvec3(9.99e6, -9.99e6, 2e4)}) {
      std::uniform_real_distribution<double> u(-500.0, 500.0);
      double worst = 0.0;
      for (int i = 0; i < 200000; ++i) {
        Instance in;
        in.position = base + glm::dvec3(u(rng), u(rng), u(rng));
        const CellKey k = cellOf(in.position);
        const PackedInstance p = pack(in, ScaleMode::Uniform, k);
        const glm::dvec3 back = unpackPosition(p, k);
        const glm::dvec3 err = glm::abs(back - in.position);
        worst = std::max({worst, err.x, err.y, err.z});
        // The cell holds it, and packing the decoded position gives the same bits.
        Instance again = in;
        again.position = back;
        QCOMPARE(cellOf(back), k);
        QVERIFY(pack(again, ScaleMode::Uniform, k) == p);
      }
      QVERIFY2(worst <= kMaxPositionError, qPrintable(QString::number(worst, 'g', 17)));
      QVERIFY(worst > 0.9 * kMaxPositionError);  // the bound is tight, so the test can fail
    }
    QCOMPARE(kMaxPositionError, 1.0 / 2048.0);
  }

  // At UTM coordinates a float relative to 0 would be off by up to 0.25 m;
  // the cell-relative record keeps the half-millimetre bound, and a store
  // round trip (pack, blob, load) returns the same doubles.
  void utmPrecision() {
    const glm::dvec3 p(500123.4567891, 4400987.6543219, 312.3456789);
    QVERIFY(std::abs(double(float(p.y)) - p.y) > 0.01);
    FoliageStore s;
    addType(s, type("Pine", 100, 1));
    Instance in;
    in.position = p;
    const uint32_t id = s.add(in, nullptr);
    const auto found = s.find(id);
    QVERIFY(found);
    const glm::dvec3 err = glm::abs(found->position - p);
    QVERIFY(err.x <= kMaxPositionError && err.y <= kMaxPositionError && err.z <= kMaxPositionError);
    const SaveSet save = s.dirty(1);
    FoliageStore t;
    addType(t, type("Pine", 100, 1));
    for (size_t i = 0; i < save.write.size(); ++i) QVERIFY(t.load(save.write[i], save.blobs[i]).ok());
    QCOMPARE(t.find(id)->position, found->position);
  }

  void rotationAndScaleBounds() {
    std::mt19937_64 rng(9);
    std::normal_distribution<double> g;
    double worst = 0.0;
    for (int i = 0; i < 1000000; ++i) {
      const glm::dquat q = glm::normalize(glm::dquat(g(rng), g(rng), g(rng), g(rng)));
      const glm::dquat b = unpackRotation(packRotation(q));
      const double d = std::min(1.0, std::abs(glm::dot(q, b)));
      worst = std::max(worst, 2.0 * std::acos(d));
    }
    qInfo("rotation: worst angle error %.5f rad over 1M random rotations", worst);
    QVERIFY(worst <= 0.0048);  // instance.h's bound
    QVERIFY(worst > 0.003);    // and it is nearly reached: the test can fail
    std::uniform_real_distribution<double> s(std::log2(0.01), std::log2(100.0));
    double worstU = 0.0, worstXy = 0.0;
    for (int i = 0; i < 100000; ++i) {
      const double v = std::exp2(s(rng));
      worstU = std::max(worstU, std::abs(unpackScale(ScaleMode::Uniform, packScale(ScaleMode::Uniform, glm::dvec3(v))).x / v - 1));
      const glm::dvec3 xy = unpackScale(ScaleMode::XyZ, packScale(ScaleMode::XyZ, glm::dvec3(v, v, 2 * v)));
      worstXy = std::max({worstXy, std::abs(xy.x / v - 1), std::abs(xy.z / (2 * v) - 1)});
    }
    QVERIFY(worstU <= std::exp2(1.0 / 8192.0) - 1.0 + 1e-12);
    QVERIFY(worstXy <= std::exp2(1.0 / 32.0) - 1.0 + 1e-12);
  }

  void blobRoundTrip() {
    FoliageStore s = filled(20000, 3, glm::dvec3(5e5, 4.4e6, 300));
    const SaveSet save = s.dirty();
    QCOMPARE(save.write.size(), s.cellCount());
    FoliageStore t;
    addType(t, s.type(0));
    addType(t, s.type(1));
    for (size_t i = 0; i < save.write.size(); ++i) {
      const Status st = t.load(save.write[i], save.blobs[i]);
      QVERIFY2(st.ok(), st.error.c_str());
      QVERIFY(*t.cell(save.write[i]) == *s.cell(save.write[i]));
    }
    QVERIFY(same(snapshot(s), snapshot(t)));  // ids included: stable across save and load
    QCOMPARE(t.nextId(), s.nextId());
    QCOMPARE(t.dirtyCount(), size_t(0));  // what was loaded is saved
    qInfo("%zu instances in %zu cells: %.2f bytes per instance in the blobs", s.instanceCount(), s.cellCount(),
          double(save.bytes()) / double(s.instanceCount()));
    QVERIFY(double(save.bytes()) / double(s.instanceCount()) <= 16.5);
  }

  void corruptAndTruncatedBlobs() {
    FoliageStore s = filled(3000, 4, glm::dvec3(10, 10, 0));
    const CellKey key = s.cells().begin()->first;
    const std::vector<uint8_t> blob = encodeCell(key, *s.cell(key));
    const std::string name = "foliage cell " + cellName(key);
    auto message = [&](std::vector<uint8_t> b, size_t types = 2, CellKey k = CellKey{}) {
      Cell c;
      const Status st = decodeCell(b, k == CellKey{} ? key : k, types, c);
      return st.error;
    };
    auto check = [&](const std::string& m, const std::vector<std::string>& parts) {
      QVERIFY2(m.find(name) == 0 || m.find("foliage cell (") == 0, m.c_str());
      for (const std::string& p : parts) QVERIFY2(m.find(p) != std::string::npos, (m + "  [wanted: " + p + "]").c_str());
    };
    QVERIFY(message(blob).empty());
    check(message({blob.begin(), blob.begin() + 17}), {"byte offset 17", "truncated", "header needs 40"});
    check(message({blob.begin(), blob.end() - 5}), {"truncated", "byte offset " + std::to_string(blob.size() - 5)});
    std::vector<uint8_t> b = blob;
    b[0] = 'X';
    check(message(b), {"byte offset 0", "signature"});
    b = blob;
    b[4] = 7;
    check(message(b), {"byte offset 4", "version 7"});
    b = blob;
    b[blob.size() / 2] ^= 0x5A;
    check(message(b), {"byte offset"});
    const std::string corrupt = message(b);
    QVERIFY2(corrupt.find("corrupt") != std::string::npos || corrupt.find("hash") != std::string::npos, corrupt.c_str());
    b = blob;
    b.push_back(0);
    check(message(b), {"byte offset " + std::to_string(blob.size()), "after the payload"});
    check(message(blob, 2, CellKey{key.x + 1, key.y, key.z}), {"byte offset 8", "cell " + cellName(key)});
    check(message(blob, 1), {"raw payload byte offset", "not one of the scene's 1 foliage types"});
    // A store refuses the bad blob whole and keeps what it had.
    FoliageStore t;
    addType(t, s.type(0));
    addType(t, s.type(1));
    QVERIFY(!t.load(key, {blob.begin(), blob.end() - 1}).ok());
    QCOMPARE(t.instanceCount(), size_t(0));
  }

  // An impostor's blob gives back every byte of both images, packs a
  // mostly empty atlas tight, and refuses damage naming the place.
  void impostorBlobRoundTripAndDamage() {
    ImpostorImages im;
    im.frames = 6;
    im.framePixels = 16;
    im.sphere = glm::vec4(0.5f, -1.0f, 4.0f, 3.25f);
    im.sourceKey = 0x123456789abcdef0ull;
    im.albedo.assign(im.imageBytes(), 0);
    im.normalDepth.assign(im.imageBytes(), 0);
    // A disc per frame with smooth colour, empty around it (as a baked plant).
    std::mt19937 rng(7);
    const int side = im.side();
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const double fx = (x % im.framePixels + 0.5) / im.framePixels - 0.5, fy = (y % im.framePixels + 0.5) / im.framePixels - 0.5;
        if (fx * fx + fy * fy > 0.16) continue;
        uint8_t* a = &im.albedo[size_t(y * side + x) * 4];
        uint8_t* n = &im.normalDepth[size_t(y * side + x) * 4];
        a[0] = uint8_t(60 + x % 40), a[1] = uint8_t(120 + y % 30), a[2] = uint8_t(rng() % 8), a[3] = 255;
        n[0] = uint8_t(128 + 100 * fx), n[1] = uint8_t(128 + 100 * fy), n[2] = 200, n[3] = uint8_t(rng() % 256);
      }
    const std::vector<uint8_t> blob = encodeImpostor(im);
    QVERIFY2(blob.size() * 3 < 2 * im.imageBytes(), qPrintable(QString::number(blob.size())));
    std::string error;
    auto back = decodeImpostor(blob, "pine impostor", error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(back->frames, 6);
    QCOMPARE(back->framePixels, 16);
    QCOMPARE(back->sphere, im.sphere);
    QCOMPARE(back->sourceKey, im.sourceKey);
    QVERIFY(back->albedo == im.albedo);
    QVERIFY(back->normalDepth == im.normalDepth);
    QCOMPARE(back->contentHash(), im.contentHash());
    ImpostorImages other = im;
    other.normalDepth[100] ^= 1;
    QVERIFY(other.contentHash() != im.contentHash());

    auto refused = [&](std::vector<uint8_t> b, const char* part) {
      std::string e;
      const bool ok = decodeImpostor(b, "pine impostor", e).has_value();
      const bool named = e.find("pine impostor: byte offset") == 0 && e.find(part) != std::string::npos;
      if (ok || !named) qWarning("%s: %s", part, e.c_str());
      return !ok && named;
    };
    QVERIFY(refused({}, "truncated"));
    QVERIFY(refused(std::vector<uint8_t>(blob.begin(), blob.begin() + 30), "truncated"));
    QVERIFY(refused(std::vector<uint8_t>(blob.begin(), blob.end() - 10), "truncated"));
    std::vector<uint8_t> b = blob;
    b[0] = 'X';
    QVERIFY(refused(b, "signature"));
    b = blob;
    b[4] = 9;
    QVERIFY(refused(b, "format version 9"));
    b = blob;
    b[6] = 0;
    QVERIFY(refused(b, "0 frames"));
    b = blob;
    b[9] = 0x40;  // 16384 pixels a frame
    QVERIFY(refused(b, "pixels a frame"));
    b = blob;
    const float nan = std::nanf("");
    std::memcpy(&b[24], &nan, 4);  // the radius
    QVERIFY(refused(b, "bounding sphere"));
    b = blob;
    b[36] ^= 4;
    QVERIFY(refused(b, "raw size"));
    b = blob;
    b.push_back(0);
    QVERIFY(refused(b, "after the payload"));
    b = blob;
    b[b.size() / 2] ^= 0x5a;
    QVERIFY(refused(b, "corrupt") || refused(b, "hash mismatch"));
    b = blob;
    b[47] ^= 1;  // the stored hash
    QVERIFY(refused(b, "hash mismatch"));
  }

  void dirtyTrackingWritesOnlyChangedCells() {
    FoliageStore s = filled(5000, 6, glm::dvec3(0.0));
    QCOMPARE(s.dirtyCount(), s.cellCount());
    s.markSaved();
    QCOMPARE(s.dirtyCount(), size_t(0));
    QVERIFY(s.dirty().write.empty());
    // One instance added: one cell to write.
    Instance in;
    in.position = {30, 30, 5};
    FoliageUndo undo;
    s.add(in, &undo);
    SaveSet d = s.dirty();
    QCOMPARE(d.write.size(), size_t(1));
    QCOMPARE(d.write[0], cellOf(in.position));
    QVERIFY(d.remove.empty());
    s.markSaved();
    // Undo makes that cell dirty again; a cell emptied is to remove.
    undo.swap(s);
    QCOMPARE(s.dirty().write.size() + s.dirty().remove.size(), size_t(1));
    const EditResult er = erase(s, Region2::rect({-1e3, -1e3}, {1e3, 1e3}));
    QCOMPARE(s.instanceCount(), size_t(0));
    d = s.dirty();
    QVERIFY(d.write.empty());
    QCOMPARE(d.remove.size(), er.undo.cellCount());
  }

  void idsAreStableAndNeverReused() {
    FoliageStore s = filled(100, 7, glm::dvec3(0.0));
    const uint32_t next = s.nextId();
    erase(s, Region2::rect({-1e3, -1e3}, {1e3, 1e3}));
    Instance in;
    QCOMPARE(s.add(in, nullptr), next);
    // Loading a store keeps ids and continues after the highest.
    const SaveSet save = s.dirty();
    FoliageStore t;
    addType(t, s.type(0));
    addType(t, s.type(1));
    for (size_t i = 0; i < save.write.size(); ++i) QVERIFY(t.load(save.write[i], save.blobs[i]).ok());
    QCOMPARE(t.allInstances()[0].id, next);
    QCOMPARE(t.nextId(), next + 1);
  }

  // The scene's view: a manifest and a blob per cell. One damaged, stale or
  // missing blob drops that cell with a message naming it; the rest loads
  // with the same ids.
  void manifestLoadsAroundDamagedCells() {
    FoliageStore s = filled(8000, 12, glm::dvec3(5e5, 4.4e6, 100));
    erase(s, Region2::disc({5e5 + 50, 4.4e6 + 50}, 10));  // ids with gaps, next id past them
    const hs::Json manifest = manifestJson(s);
    const SaveSet save = s.dirty();
    std::map<CellKey, std::vector<uint8_t>> file;
    for (size_t i = 0; i < save.write.size(); ++i) file[save.write[i]] = save.blobs[i];
    auto reader = [&](const CellKey& k) -> std::optional<std::vector<uint8_t>> {
      auto it = file.find(k);
      if (it == file.end()) return std::nullopt;
      return it->second;
    };
    const hs::Json info = infoJson(s);
    QCOMPARE(info["instances"].get<size_t>(), s.instanceCount());
    QCOMPARE(info["types"][1]["name"].get<std::string>(), std::string("Grass"));
    QCOMPARE(info["types"][1]["instances"].get<size_t>(), s.instanceCount(1));
    // Through text, as the document keeps it.
    std::string error;
    const auto parsed = hs::parseJson(hs::writeJson(manifest), error);
    QVERIFY(parsed);
    FoliageStore t;
    LoadReport rep;
    QVERIFY2(loadStore(*parsed, reader, t, rep, error), error.c_str());
    QCOMPARE(rep.cellsDropped, size_t(0));
    QVERIFY(same(snapshot(s), snapshot(t)));
    QVERIFY(t.types() == s.types());

    // Damage three cells: truncate one, drop one, replace one by a valid
    // blob of another version of that cell.
    auto it = file.begin();
    const CellKey truncated = it->first, missing = std::next(it)->first, stale = std::next(it, 2)->first;
    file[truncated].resize(file[truncated].size() - 3);
    file.erase(missing);
    Cell other = *s.cell(stale);
    other.runs[0].items.pop_back();
    file[stale] = encodeCell(stale, other);
    FoliageStore u;
    LoadReport bad;
    QVERIFY(loadStore(*parsed, reader, u, bad, error));
    QCOMPARE(bad.cellsDropped, size_t(3));
    QCOMPARE(bad.cellsLoaded, s.cellCount() - 3);
    const size_t lost = s.cell(truncated)->count() + s.cell(missing)->count() + s.cell(stale)->count();
    QCOMPARE(bad.instancesDropped, lost);
    QCOMPARE(u.instanceCount(), s.instanceCount() - lost);
    QVERIFY(anyContains(bad.messages, {"foliage cell " + cellName(truncated), "byte offset", "truncated"}));
    QVERIFY(anyContains(bad.messages, {"foliage cell " + cellName(missing), "missing"}));
    QVERIFY(anyContains(bad.messages, {"foliage cell " + cellName(stale), "another version"}));
    QCOMPARE(u.nextId(), s.nextId());  // ids of the lost cells are not handed out again
    // A bad manifest is an error with its path.
    hs::Json broken = manifest;
    broken["cells"][1]["hash"] = "xyz";
    QVERIFY(!loadStore(broken, reader, u, bad, error));
    QVERIFY2(error.find("foliage.cells[1].hash") != std::string::npos, error.c_str());
  }

  // The operations the CLI and the editor will share: declared once, the
  // type's options among them, values checked with messages naming the
  // option, and turned into the domain's structs.
  void operationsAreDeclaredOnce() {
    for (const hs::OperationDecl* op : {&foliageTypeAddOperation(), &foliageScatterOperation(),
                                        &foliageClearOperation(), &foliagePlantOperation(),
                                        &foliageImpostorsOperation()}) {
      QVERIFY(!op->name.empty() && !op->positionals.empty());
      for (const hs::ParamDecl& p : op->params) {
        std::string error;
        if (!p.defaultValue.is_null()) QVERIFY2(hs::checkParam(p, p.defaultValue, error), (op->name + ": " + error).c_str());
      }
    }
    for (const hs::ParamDecl& p : foliageTypeParamDecls()) QVERIFY(foliageTypeAddOperation().find(p.key));
    std::string error;
    QVERIFY(!hs::parseParam(foliageTypeAddOperation().param("density_per_ha"), "1e9", error));
    QVERIFY2(error.find("--density") == 0 && error.find("out of range") != std::string::npos, error.c_str());
    QVERIFY(!hs::parseParam(foliageScatterOperation().param("slope_deg"), "40,10", error));
    QVERIFY2(error.find("--slope") == 0, error.c_str());
    const auto slope = hs::parseParam(foliageScatterOperation().param("slope_deg"), "5,30", error);
    QVERIFY(slope);

    FoliageType t;
    hs::Json v = hs::Json::object();
    v["mesh"] = "Pine LOD";
    v["density_per_ha"] = 250;
    v["slope_deg"] = hs::Json::array({0, 30});
    v["surface"] = "terrain";
    QVERIFY2(typeFromValues("Pine", v, t, error), error.c_str());
    QCOMPARE(t.name, std::string("Pine"));
    QCOMPARE(t.mesh, std::string("Pine LOD"));
    QCOMPARE(t.densityPerHa, 250.0);
    QCOMPARE(t.slopeDeg, glm::dvec2(0, 30));
    QCOMPARE(t.surface, SurfaceFilter::Terrain);
    QCOMPARE(t.spacing, FoliageType{}.spacing);  // not given: the default
    v.erase("mesh");
    QVERIFY(!typeFromValues("Pine", v, t, error));
    QVERIFY2(error.find("\"Pine\"") != std::string::npos && error.find("mesh") != std::string::npos, error.c_str());

    hs::Json sv = hs::Json::object();
    sv["density_per_ha"] = 40;
    sv["slope_deg"] = *slope;
    sv["region"] = hs::Json::array({10, 20, -5, 70});
    const FoliageType r = scatterRules(type("Pine", 100, 2), sv);
    QCOMPARE(r.densityPerHa, 40.0);
    QCOMPARE(r.slopeDeg, glm::dvec2(5, 30));
    QCOMPARE(r.spacing, 2.0);
    const auto region = regionFromValues(sv);
    QVERIFY(region && region->lo == glm::dvec2(-5, 20) && region->hi == glm::dvec2(10, 70));
    QVERIFY(!regionFromValues(hs::Json::object()));

    hs::Json pv = hs::Json::object();
    pv["kind"] = "conifer";
    pv["seed"] = 5;
    pv["levels"] = 1;
    const PlantParams pp = plantFromValues(pv);
    QCOMPARE(pp.kind, PlantKind::Conifer);
    QCOMPARE(pp.seed, uint64_t(5));
    QCOMPARE(pp.levels, 1);
    QCOMPARE(pp.height, defaultPlant(PlantKind::Conifer).height);
  }

  void scaleModeChangeReencodes() {
    FoliageStore s = filled(1000, 8, glm::dvec3(0.0));
    const Snapshot before = snapshot(s);
    FoliageType t = s.type(0);
    t.scaleMode = ScaleMode::XyZ;
    FoliageUndo undo;
    std::vector<std::string> w;
    s.setType(0, t, &undo, w);
    for (const Instance& in : s.allInstances())
      if (in.type == 0) QVERIFY(std::abs(in.scale.z / before.inst[in.id - 1].scale.z - 1.0) < 0.023);
    QVERIFY(undo.cellCount() > 0);
    t.scaleMode = ScaleMode::Uniform;
    s.setType(0, t, nullptr, w);
    for (const Instance& in : s.allInstances()) QVERIFY(std::abs(in.scale.x / before.inst[in.id - 1].scale.x - 1.0) < 0.023);
  }
};

QTEST_GUILESS_MAIN(TestFoliageStorage)
#include "test_foliage_storage.moc"
