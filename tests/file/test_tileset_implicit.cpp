// 3D Tiles 1.1 implicit tiling (mesh/implicit_tiling.h, read by
// mesh/tileset_reader.h): a quadtree and an octree written by the test
// byte by byte from the specification (binary and JSON subtree files,
// bitstreams and constants, external buffers, child subtrees, levels past
// availableLevels that must be ignored) read into exactly the tiles of the
// same tree written out explicitly (every parent, error, refinement and
// vertex), and through the CLI into the same hierarchy (streamed: its six
// finest tiles, listed without decoding and decoded one at a time). Bad input: a
// missing, a truncated and a short-bitstream subtree, an unknown scheme, a
// tree that names a million tiles: named, and the rest comes in.
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <functional>

#include "cli_runner.h"
#include "tileset_files.h"
#include "core/json.h"
#include "mesh/tileset_reader.h"
#include "scene/import_pipeline.h"

using namespace hs;
namespace fs = std::filesystem;

namespace {

constexpr double kLon = 21.6300, kLat = 39.7217, kHeight = 300.0;  // Meteora
constexpr double kRootError = 40.0;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

// A tile of the tree by its implicit coordinates.
struct Node {
  int level = 0;
  uint64_t x = 0, y = 0, z = 0;
  bool content = true;
  std::vector<Node> children;  // in Morton order
};

std::string contentName(const Node& n, bool octree) {
  return "content/" + std::to_string(n.level) + "_" + std::to_string(n.x) + "_" + std::to_string(n.y) +
         (octree ? "_" + std::to_string(n.z) : "") + ".glb";
}

// Its content: a bumpy grid over the tile's square of [-100, 100]^2, raised by its z.
test::TestGrid gridOf(const Node& n) {
  const double size = 200.0 / double(uint64_t(1) << n.level);
  const double e0 = -100.0 + size * double(n.x), n0 = -100.0 + size * double(n.y);
  const double lift = 30.0 * double(n.z) + 2.0 * n.level;
  return test::testGrid(e0, e0 + size, n0, n0 + size, 4,
                        [&](double e, double nn) { return lift + 4.0 * std::sin(e / 30.0) * std::cos(nn / 40.0); });
}

void writeContents(const std::string& d, const Node& n, bool octree) {
  if (n.content) test::writeBytes(d + "/" + contentName(n, octree), test::glbOf(gridOf(n)));
  for (const Node& c : n.children) writeContents(d, c, octree);
}

Json explicitTile(const Node& n, bool octree) {
  Json t = {{"boundingVolume", {{"sphere", {0, 0, 0, 200}}}},
            {"geometricError", std::ldexp(kRootError, -n.level)}};
  if (n.content) t["content"] = {{"uri", contentName(n, octree)}};
  if (!n.children.empty()) {
    t["children"] = Json::array();
    for (const Node& c : n.children) t["children"].push_back(explicitTile(c, octree));
  }
  return t;
}

Json tilesetOf(Json root) {
  root["transform"] = test::matrixJson(test::enuToEcef(kLon, kLat, kHeight));
  root["refine"] = "REPLACE";
  return {{"asset", {{"version", "1.1"}}}, {"geometricError", 100}, {"root", std::move(root)}};
}

Json implicitRoot(const std::string& scheme, int subtreeLevels, int availableLevels, const std::string& contentUri) {
  return {{"boundingVolume", {{"box", {0, 0, 0, 100, 0, 0, 0, 100, 0, 0, 0, 100}}}},
          {"geometricError", kRootError},
          {"content", {{"uri", contentUri}}},
          {"implicitTiling",
           {{"subdivisionScheme", scheme},
            {"subtreeLevels", subtreeLevels},
            {"availableLevels", availableLevels},
            {"subtrees", {{"uri", "subtrees/{level}.{x}.{y}.{z}.subtree"}}}}}};
}

std::string subtreePath(const std::string& d, int level, uint64_t x, uint64_t y, uint64_t z) {
  return d + "/subtrees/" + std::to_string(level) + "." + std::to_string(x) + "." + std::to_string(y) + "." +
         std::to_string(z) + ".subtree";
}

// A binary subtree whose three availabilities are constants.
std::vector<uint8_t> constantSubtree(int tiles, int content, int children) {
  return test::subtreeOf({{"tileAvailability", {{"constant", tiles}}},
                          {"contentAvailability", Json::array({{{"constant", content}}})},
                          {"childSubtreeAvailability", {{"constant", children}}}},
                         {});
}

// The quadtree of the tests: availableLevels 3, two levels per subtree.
//   0/0/0 (content)
//   +- 1/0/0 (content) -- 2/0/0 (content; a JSON subtree with an external buffer)
//   +- 1/1/0 (no content) -- 2/2/0, 2/3/0, 2/2/1, 2/3/1 (content; constant subtrees that
//   |                        also make level 3 available, past availableLevels)
//   +- 1/0/1 (content, a leaf)          (1/1/1 is not available)
Node quadtree() {
  Node root;
  Node a{1, 0, 0, 0, true, {Node{2, 0, 0, 0, true, {}}}};
  Node b{1, 1, 0, 0, false, {}};
  for (uint64_t m : {0u, 1u, 2u, 3u}) b.children.push_back(Node{2, 2 + (m & 1u), (m >> 1) & 1u, 0, true, {}});
  Node c{1, 0, 1, 0, true, {}};
  root.children = {a, b, c};
  return root;
}

// Its subtree files, written from the specification's bit layout: in each
// subtree, level l's tiles start at bit (4^l - 1) / 3 and follow in Morton
// order (x in the lowest bit); child subtrees by the Morton index of their
// root at level subtreeLevels below.
void writeQuadtreeSubtrees(const std::string& d) {
  fs::create_directories(d + "/subtrees");
  // Tiles: bit 0 the root, 1 + m for level 1: m = 0 (0,0), 1 (1,0), 2 (0,1) -> 0b1111.
  // Content: root, (0,0), (0,1) -> bits 0, 1, 3.
  // Child subtrees: level-2 (0,0) -> m 0; (2,0) (3,0) (2,1) (3,1) -> m 4..7.
  const std::vector<uint8_t> bin = {0x0F, 0x0B, 0xF1, 0x00};
  const Json root = {
      {"buffers", Json::array({{{"byteLength", bin.size()}}})},
      {"bufferViews", Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 1}},
                                   {{"buffer", 0}, {"byteOffset", 1}, {"byteLength", 1}},
                                   {{"buffer", 0}, {"byteOffset", 2}, {"byteLength", 2}}})},
      {"tileAvailability", {{"bitstream", 0}, {"availableCount", 4}}},
      {"contentAvailability", Json::array({{{"bitstream", 1}}})},
      {"childSubtreeAvailability", {{"bitstream", 2}}}};
  test::writeBytes(subtreePath(d, 0, 0, 0, 0), test::subtreeOf(root, bin));
  // 2/0/0 as JSON with its bits in a file beside it: its root and all four
  // level-3 tiles available (ignored: availableLevels is 3), content at its root.
  test::writeBytes(d + "/subtrees/bits200.bin", {0x1F, 0x01});
  test::writeText(subtreePath(d, 2, 0, 0, 0),
                  Json{{"buffers", Json::array({{{"uri", "bits200.bin"}, {"byteLength", 2}}})},
                       {"bufferViews", Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 1}},
                                                    {{"buffer", 0}, {"byteOffset", 1}, {"byteLength", 1}}})},
                       {"tileAvailability", {{"bitstream", 0}}},
                       {"contentAvailability", Json::array({{{"bitstream", 1}}})},
                       {"childSubtreeAvailability", {{"constant", 1}}}}
                      .dump());
  for (auto [x, y] : {std::pair{2, 0}, {3, 0}, {2, 1}, {3, 1}})
    test::writeBytes(subtreePath(d, 2, uint64_t(x), uint64_t(y), 0), constantSubtree(1, 1, 1));
}

// The octree: availableLevels 2, one level per subtree, so each of the
// root's children is the root of its own subtree; child 5 (x 1, y 0, z 1)
// is not available.
Node octree() {
  Node root;
  for (uint64_t m = 0; m < 8; ++m)
    if (m != 5) root.children.push_back(Node{1, m & 1u, (m >> 1) & 1u, (m >> 2) & 1u, true, {}});
  return root;
}

void writeOctreeSubtrees(const std::string& d) {
  fs::create_directories(d + "/subtrees");
  const std::vector<uint8_t> bin = {0xDF};  // child subtrees 0-7 but 5
  test::writeBytes(subtreePath(d, 0, 0, 0, 0),
                   test::subtreeOf({{"buffers", Json::array({{{"byteLength", 1}}})},
                                    {"bufferViews", Json::array({{{"buffer", 0}, {"byteLength", 1}}})},
                                    {"tileAvailability", {{"constant", 1}}},
                                    {"contentAvailability", Json::array({{{"constant", 1}}})},
                                    {"childSubtreeAvailability", {{"bitstream", 0}}}},
                                   bin));
  for (uint64_t m = 0; m < 8; ++m)
    if (m != 5) test::writeBytes(subtreePath(d, 1, m & 1u, (m >> 1) & 1u, (m >> 2) & 1u), constantSubtree(1, 1, 1));
}

void compareTiles(const mesh::Tileset& got, const mesh::Tileset& want) {
  QCOMPARE(got.tiles.size(), want.tiles.size());
  for (size_t i = 0; i < got.tiles.size(); ++i) {
    const mesh::TilesetTile &g = got.tiles[i], &w = want.tiles[i];
    QCOMPARE(g.parent, w.parent);
    QCOMPARE(g.geometricError, w.geometricError);
    QCOMPARE(g.additive, w.additive);
    QCOMPARE(g.contentMissing, w.contentMissing);
    QCOMPARE(g.content, w.content);
    QCOMPARE(g.indices, w.indices);
    QCOMPARE(g.positions.size(), w.positions.size());
    for (size_t v = 0; v < g.positions.size(); ++v) QVERIFY(g.positions[v] == w.positions[v]);
  }
  QCOMPARE(got.contentsRead, want.contentsRead);
}

}  // namespace

class TestTilesetImplicit : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;

  std::string dir(const std::string& name) const {
    const fs::path d = fs::path(tmp_.path().toStdString()) / name;
    fs::create_directories(d / "content");
    return d.string();
  }
  // The quadtree written both ways into `d`: implicit.json and explicit.json.
  std::string quadtreeFiles(const std::string& name) const {
    const std::string d = dir(name);
    writeContents(d, quadtree(), false);
    writeQuadtreeSubtrees(d);
    Json root = implicitRoot("QUADTREE", 2, 3, "content/{level}_{x}_{y}.glb");
    test::writeText(d + "/implicit.json", tilesetOf(root).dump(1));
    test::writeText(d + "/explicit.json", tilesetOf(explicitTile(quadtree(), false)).dump(1));
    return d;
  }
  static mesh::Tileset read(const std::string& path) {
    mesh::Tileset t;
    std::string error;
    if (!mesh::readTileset(path, t, error)) qWarning("%s", error.c_str());
    return t;
  }
  static scene::ImportedMesh imported(const std::string& path) {
    scene::MeshImportRequest r;
    r.files = {path};
    return scene::importMeshFiles(r);
  }

 private slots:
  void quadtreeReadsAsItsExplicitTree() {
    const std::string d = quadtreeFiles("quad");
    const mesh::Tileset implicit = read(d + "/implicit.json"), expl = read(d + "/explicit.json");
    QVERIFY2(implicit.warnings.empty(), joined(implicit.warnings).c_str());
    QVERIFY2(expl.warnings.empty(), joined(expl.warnings).c_str());
    QCOMPARE(implicit.tiles.size(), size_t(9));  // level 3 left out, 1/1/1 not available
    compareTiles(implicit, expl);
    QCOMPARE(implicit.contentsRead, size_t(8));
    // The tree alone (the streamed import's first step): the same tiles,
    // their eight contents listed with their sizes, nothing decoded.
    mesh::Tileset tree;
    std::vector<mesh::TilesetContentRef> listed;
    std::string error;
    QVERIFY2(mesh::readTilesetTree(d + "/implicit.json", tree, listed, error), error.c_str());
    QCOMPARE(tree.tiles.size(), implicit.tiles.size());
    QCOMPARE(listed.size(), size_t(8));
    for (const mesh::TilesetContentRef& c : listed) {
      QVERIFY(tree.tiles[size_t(c.tile)].positions.empty());
      QCOMPARE(c.bytes, uint64_t(fs::file_size(c.file)));
      mesh::TilesetTile decoded;
      mesh::Tileset log;
      QVERIFY(mesh::readTilesetContent(c, decoded, log));
      QVERIFY(decoded.positions == implicit.tiles[size_t(c.tile)].positions);
    }
    // Errors halve per level: 2/3/1 is the eighth tile.
    QCOMPARE(implicit.tiles[7].geometricError, kRootError / 4.0);
    QVERIFY2(contains(implicit.tiles[7].content, "2_3_1.glb"), implicit.tiles[7].content.c_str());
  }

  void octreeReadsAsItsExplicitTree() {
    const std::string d = dir("oct");
    writeContents(d, octree(), true);
    writeOctreeSubtrees(d);
    test::writeText(d + "/implicit.json", tilesetOf(implicitRoot("OCTREE", 1, 2, "content/{level}_{x}_{y}_{z}.glb")).dump());
    test::writeText(d + "/explicit.json", tilesetOf(explicitTile(octree(), true)).dump());
    const mesh::Tileset implicit = read(d + "/implicit.json"), expl = read(d + "/explicit.json");
    QVERIFY2(implicit.warnings.empty(), joined(implicit.warnings).c_str());
    QCOMPARE(implicit.tiles.size(), size_t(8));
    compareTiles(implicit, expl);
  }

  void extensionFormIsRead() {
    // 3DTILES_implicit_tiling (3D Tiles 1.0): maximumLevel, bufferView.
    const std::string d = quadtreeFiles("ext");
    Json root = implicitRoot("QUADTREE", 2, 3, "content/{level}_{x}_{y}.glb");
    Json it = root["implicitTiling"];
    root.erase("implicitTiling");
    it.erase("availableLevels");
    it["maximumLevel"] = 2;
    root["extensions"] = {{"3DTILES_implicit_tiling", it}};
    test::writeText(d + "/implicit.json", tilesetOf(root).dump());
    Json sub = {{"buffers", Json::array({{{"byteLength", 4}}})},
                {"bufferViews", Json::array({{{"buffer", 0}, {"byteLength", 1}},
                                             {{"buffer", 0}, {"byteOffset", 1}, {"byteLength", 1}},
                                             {{"buffer", 0}, {"byteOffset", 2}, {"byteLength", 2}}})},
                {"tileAvailability", {{"bufferView", 0}}},
                {"contentAvailability", {{"bufferView", 1}}},
                {"childSubtreeAvailability", {{"bufferView", 2}}}};
    test::writeBytes(subtreePath(d, 0, 0, 0, 0), test::subtreeOf(sub, {0x0F, 0x0B, 0xF1, 0x00}));
    const mesh::Tileset implicit = read(d + "/implicit.json"), expl = read(d + "/explicit.json");
    QVERIFY2(implicit.warnings.empty(), joined(implicit.warnings).c_str());
    compareTiles(implicit, expl);
  }

  void badSubtreesAreNamed() {
    // A missing subtree below a tile with content: that tile is not refined.
    {
      const std::string d = quadtreeFiles("missing");
      fs::remove(subtreePath(d, 2, 0, 0, 0));
      const scene::ImportedMesh m = imported(d + "/implicit.json");
      QVERIFY2(m.ok(), m.error.c_str());
      const std::string w = joined(m.import.warnings);
      QVERIFY2(contains(w, "2.0.0.0.subtree (subtree 2/0/0 of root in ") && contains(w, "is missing"), w.c_str());
      QVERIFY2(contains(w, "kept at its own level"), w.c_str());
    }
    // A truncated binary subtree, and one whose bitstream is shorter than its bits.
    {
      const std::string d = quadtreeFiles("truncated");
      std::vector<uint8_t> bytes = constantSubtree(1, 1, 1);
      bytes.resize(bytes.size() - 5);
      test::writeBytes(subtreePath(d, 2, 2, 0, 0), bytes);
      test::writeBytes(subtreePath(d, 2, 3, 0, 0),
                       test::subtreeOf({{"buffers", Json::array({{{"byteLength", 1}}})},
                                        {"bufferViews", Json::array({{{"buffer", 0}, {"byteLength", 1}}})},
                                        {"tileAvailability", {{"constant", 1}}},
                                        {"childSubtreeAvailability", {{"bitstream", 0}}}},  // 16 bits needed
                                       {0xFF}));
      const mesh::Tileset t = read(d + "/implicit.json");
      const std::string w = joined(t.warnings);
      QVERIFY2(contains(w, "2.2.0.0.subtree (subtree 2/2/0") && contains(w, "more than the file's"), w.c_str());
      QVERIFY2(contains(w, "2.3.0.0.subtree (subtree 2/3/0") &&
                   contains(w, "childSubtreeAvailability has 1 bytes, fewer than the 2 its 16 bits need"),
               w.c_str());
      // Each stands as a tile that did not come in; the rest as before.
      size_t missing = 0;
      for (const mesh::TilesetTile& tile : t.tiles) missing += tile.contentMissing;
      QCOMPARE(missing, size_t(2));
      QCOMPARE(t.tiles.size(), size_t(9));
      QCOMPARE(t.contentsRead, size_t(6));
    }
    // An unknown scheme beside a good tile: named, that tile empty, the rest in.
    {
      const std::string d = quadtreeFiles("scheme");
      Json bad = implicitRoot("HEXTREE", 2, 3, "content/{level}_{x}_{y}.glb");
      Json root = {{"boundingVolume", {{"sphere", {0, 0, 0, 200}}}},
                   {"geometricError", 80},
                   {"content", {{"uri", "content/0_0_0.glb"}}},
                   {"children", Json::array({bad, explicitTile(quadtree(), false)})}};
      test::writeText(d + "/tileset.json", tilesetOf(root).dump());
      const scene::ImportedMesh m = imported(d + "/tileset.json");
      QVERIFY2(m.ok(), m.error.c_str());
      const std::string w = joined(m.import.warnings);
      QVERIFY2(contains(w, "root.children[0].implicitTiling: subdivisionScheme \"HEXTREE\" is neither"), w.c_str());
    }
  }

  void tooManyTilesAreCapped() {
    // Constant availability over 12 quadtree levels names 5.6 million tiles.
    const std::string d = quadtreeFiles("huge");
    Json huge = implicitRoot("QUADTREE", 12, 12, "content/none.glb");
    test::writeBytes(d + "/subtrees/0.0.0.0.subtree", constantSubtree(1, 0, 0));
    Json root = {{"boundingVolume", {{"sphere", {0, 0, 0, 200}}}},
                 {"geometricError", 80},
                 {"content", {{"uri", "content/0_0_0.glb"}}},
                 {"children", Json::array({huge})}};
    test::writeText(d + "/tileset.json", tilesetOf(root).dump());
    const mesh::Tileset t = read(d + "/tileset.json");
    const std::string w = joined(t.warnings);
    QVERIFY2(contains(w, "root.children[0]: implicit tiling makes more than 1048576 tiles available"), w.c_str());
    QCOMPARE(t.tiles.size(), size_t(1) + (size_t(1) << 20));
  }

  void cliImportsTheSameHierarchy() {
    const std::string d = quadtreeFiles("cli");
    auto clusters = [&](const std::string& file) {
      const QString scene = QString::fromStdString(d + "/" + file + ".hscene");
      if (test::runCli({"new", scene}, tmp_.path()).code != 0) return Json();
      test::CliRun c = test::runCli({"import", QString::fromStdString(d + "/" + file + ".json"), scene}, tmp_.path());
      if (c.code != 0) return Json(c.err.toStdString());
      c = test::runCli({"info", scene, "--json"}, tmp_.path());
      return c.code == 0 ? Json::parse(c.out.toStdString()).at("assets").at(0).at("clusters") : Json();
    };
    Json implicit = clusters("implicit"), expl = clusters("explicit");
    QVERIFY2(implicit.is_object() && expl.is_object(), (implicit.dump() + " / " + expl.dump()).c_str());
    QCOMPARE(implicit.at("levels").get<size_t>(), size_t(3));
    implicit.erase("file");  // the scene's own
    expl.erase("file");
    QVERIFY2(implicit == expl, (implicit.dump() + " vs " + expl.dump()).c_str());
    // Streamed: the six finest tiles' 192 triangles built into a hierarchy here.
    const QString scene = QString::fromStdString(d + "/streamed.hscene");
    QCOMPARE(test::runCli({"new", scene}, tmp_.path()).code, 0);
    test::CliRun c = test::runCli({"import", QString::fromStdString(d + "/implicit.json"), scene, "--clusters", "streamed"},
                                  tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    c = test::runCli({"info", scene, "--json"}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    const Json streamed = Json::parse(c.out.toStdString()).at("assets").at(0).at("clusters");
    QCOMPARE(streamed.at("per_level").at(0).at("triangles").get<size_t>(), size_t(192));
  }
};

QTEST_GUILESS_MAIN(TestTilesetImplicit)
#include "test_tileset_implicit.moc"
