// Materials and textures as document objects (scene/material.h): an import
// creates them, edits are checked by the fields' declarations and undo
// exactly, the .hscene keeps them (format 5), and files from before format
// 5 get them from their meshes on load.
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <filesystem>
#include <limits>

#include "scene/document.h"
#include "scene/edit.h"
#include "scene/fields.h"
#include "scene/hscene_file.h"
#include "scene/material_ops.h"
#include "scene/mesh_materials.h"
#include "scene/operations.h"
#include "scene/scene_json.h"
#include "scene/texture_blob.h"

using namespace hs;
using namespace hs::scene;

namespace {

// Two triangles per material: "red" (plain), "brick" (a 2x2 texture), and
// two triangles with no material (the default slot).
mesh::MeshData threeMaterialMesh() {
  mesh::MeshData m;
  for (int q = 0; q < 3; ++q) {
    const float x = float(q) * 2.0f;
    const uint32_t b = uint32_t(m.positions.size());
    for (auto p : {glm::vec3(x, 0, 0), glm::vec3(x + 1, 0, 0), glm::vec3(x + 1, 1, 0), glm::vec3(x, 1, 0)}) {
      m.positions.push_back(p);
      m.normals.emplace_back(0, 0, 1);
      m.uvs.emplace_back(p.x - x, p.y);
    }
    m.indices.insert(m.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
    m.submeshes.push_back({uint32_t(q * 6), 6, q < 2 ? q : -1});
  }
  mesh::Material red;
  red.name = "red";
  red.baseColor = {0.9f, 0.1f, 0.1f, 0.75f};
  mesh::Material brick;
  brick.name = "brick";
  brick.diffuseTexture = 0;
  m.materials = {red, brick};
  mesh::Texture t;
  t.name = "brick.png";
  t.width = t.height = 2;
  t.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  m.textures.push_back(t);
  return m;
}

EntityId importQuad(Document& doc, const std::string& name) {
  return ops::addImportedMesh(doc, threeMaterialMesh(), name, name + ".obj", mesh::ImportReport{});
}

const MaterialField& field(const char* key) {
  const MaterialField* f = findMaterialField(key);
  if (!f) qFatal("no material field %s", key);
  return *f;
}

const std::string kFileData = HS_TEST_DATA_DIR "/file";

}  // namespace

class TestSceneMaterials : public QObject {
  Q_OBJECT
 private slots:
  void importCreatesNamedMaterialsPerSlot() {
    Document doc;
    const EntityId e = importQuad(doc, "Wall");
    const MeshAsset& a = doc.state().assets.at(doc.state().find(e)->mesh->mesh);
    QCOMPARE(a.materialSlots.size(), size_t(3));  // red, brick, and the default slot
    QCOMPARE(doc.state().materials.size(), size_t(3));
    const Material& red = doc.state().materials.at(a.materialSlots[0]);
    QCOMPARE(red.name, std::string("Wall / red"));
    QCOMPARE(red.asset, a.id);
    QCOMPARE(red.baseColor, glm::vec3(0.9f, 0.1f, 0.1f));
    QCOMPARE(red.opacity, 0.75f);  // the mesh material's alpha
    const Material& brick = doc.state().materials.at(a.materialSlots[1]);
    QCOMPARE(brick.name, std::string("Wall / brick"));
    const TextureAsset* tex = doc.state().findTexture(brick.baseColorTexture);
    QVERIFY(tex);
    QCOMPARE(tex->asset, a.id);
    QCOMPARE(tex->meshTexture, 0);
    // The image is the mesh's own (no copy of its bytes).
    QCOMPARE(static_cast<const void*>(tex->image.get()), static_cast<const void*>(&a.data->textures[0]));
    QCOMPARE(doc.state().materials.at(a.materialSlots[2]).name, std::string("Wall / default"));
    // Each submesh's slot.
    QCOMPARE(materialSlotOf(*a.data, a.data->submeshes[0]), size_t(0));
    QCOMPARE(materialSlotOf(*a.data, a.data->submeshes[2]), size_t(2));
    QCOMPARE(doc.state().validate(), std::string());

    // A second import of the same name gets names of its own.
    importQuad(doc, "Wall");
    QVERIFY(doc.state().findMaterialByName("Wall / red 2") != kNoMaterial);
    QCOMPARE(doc.state().materials.size(), size_t(6));

    // Undo takes the materials and textures with the mesh; redo brings them back.
    doc.undoStack()->undo();
    QCOMPARE(doc.state().materials.size(), size_t(3));
    doc.undoStack()->undo();
    QVERIFY(doc.state().materials.empty());
    QVERIFY(doc.state().textures.empty());
    doc.undoStack()->redo();
    QCOMPARE(doc.state().materials.size(), size_t(3));
    QCOMPARE(doc.state().textures.size(), size_t(1));
  }

  void editsUndoAndRedoExactly() {
    Document doc;
    importQuad(doc, "Wall");
    const MaterialId id = doc.state().findMaterialByName("Wall / red");
    const std::string before = canonicalJson(doc.state());
    std::string error;
    QVERIFY(ops::setMaterialField(doc, id, field("roughness"), FieldValue(0.2), error));
    QVERIFY(ops::setMaterialField(doc, id, field("model"), FieldValue(int64_t(LightingModel::BlinnPhong)), error));
    QVERIFY(ops::setMaterialField(doc, id, field("emission"), FieldValue(glm::dvec3(1, 2, 3)), error));
    QCOMPARE(doc.state().materials.at(id).roughness, 0.2f);
    QCOMPARE(doc.state().materials.at(id).model, LightingModel::BlinnPhong);
    QCOMPARE(doc.state().materials.at(id).emission, glm::vec3(1, 2, 3));
    const std::string after = canonicalJson(doc.state());
    QVERIFY(after != before);
    for (int i = 0; i < 3; ++i) doc.undoStack()->undo();
    QCOMPARE(canonicalJson(doc.state()), before);
    for (int i = 0; i < 3; ++i) doc.undoStack()->redo();
    QCOMPARE(canonicalJson(doc.state()), after);
    // Renaming keeps names unique.
    QVERIFY(!ops::setMaterialField(doc, id, field("name"), FieldValue(std::string("Wall / brick")), error));
    QVERIFY2(error.find("another material is named 'Wall / brick'") != std::string::npos, error.c_str());
    QVERIFY(ops::setMaterialField(doc, id, field("name"), FieldValue(std::string("Red wall")), error));
    QCOMPARE(doc.state().findMaterialByName("Red wall"), id);
  }

  void badValuesAreRefusedNamingMaterialAndField() {
    Document doc;
    importQuad(doc, "Wall");
    const MaterialId id = doc.state().findMaterialByName("Wall / red");
    const std::string before = canonicalJson(doc.state());
    const int steps = doc.undoStack()->count();
    struct Case {
      const char* field;
      FieldValue value;
      const char* message;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Case cases[] = {
        {"opacity", 1.5, "material 'Wall / red': opacity: 1.5 is out of range (0 to 1)"},
        {"opacity", -0.1, "material 'Wall / red': opacity: -0.1 is out of range (0 to 1)"},
        {"roughness", nan, "material 'Wall / red': roughness: is not a finite number"},
        {"base_color", glm::dvec3(0.5, -1, 0.5), "material 'Wall / red': base_color: -1 is out of range (0 to 1000)"},
        {"height_scale", 2.0, "material 'Wall / red': height_scale: 2 is out of range (0 to 0.5 m)"},
        {"transmission", 1.5, "material 'Wall / red': transmission: 1.5 is out of range (0 to 1)"},
        {"transmission", nan, "material 'Wall / red': transmission: is not a finite number"},
        {"normal_map", int64_t(99), "material 'Wall / red': normal_map: no texture 99 in this scene (0 for none)"},
        {"name", std::string(" "), "material 'Wall / red': name: a material needs a name"},
    };
    for (const Case& c : cases) {
      std::string error;
      QVERIFY2(!ops::setMaterialField(doc, id, field(c.field), c.value, error), c.field);
      QCOMPARE(error, std::string(c.message));
    }
    QCOMPARE(doc.undoStack()->count(), steps);
    QCOMPARE(canonicalJson(doc.state()), before);
  }

  void fileRoundTripKeepsMaterialsAndTextures() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("m.hscene").toStdString();
    Document doc;
    importQuad(doc, "Wall");
    // A standalone texture (a normal map made in code) used by a material.
    mesh::Texture nm;
    nm.name = "bumps";
    nm.width = 3;
    nm.height = 1;
    nm.rgba = {128, 128, 255, 255, 200, 128, 230, 255, 60, 128, 230, 255};
    TextureAsset t;
    t.name = "bumps";
    t.srgb = false;
    t.contentHash = textureContentHash(nm);
    t.image = std::make_shared<const mesh::Texture>(nm);
    {
      Edit e(doc, "normal map");
      const TextureId tid = e.addTexture(t);
      Material& m = e.material(doc.state().findMaterialByName("Wall / brick"));
      m.normalMap = tid;
      m.normalStrength = 2.5f;
      m.alphaCutout = true;
      m.shading = ShadingMode::Gouraud;
      QVERIFY(e.commit());
    }
    std::string error;
    QVERIFY2(saveScene(doc.state(), path, error), error.c_str());
    QCOMPARE(sceneFileVersion(path), kSceneFormatVersion);
    QVERIFY(kSceneFormatVersion >= kFirstMaterialsFormat);
    const auto loaded = loadScene(path, error);
    QVERIFY2(loaded, error.c_str());
    QCOMPARE(canonicalJson(*loaded), canonicalJson(doc.state()));
    QCOMPARE(loaded->materials, doc.state().materials);
    for (const auto& [id, tex] : loaded->textures) {
      QVERIFY(tex.image);
      QCOMPARE(tex.image->rgba, doc.state().textures.at(id).image->rgba);
      if (!tex.standalone())  // linked into the loaded mesh, not a copy
        QCOMPARE(static_cast<const void*>(tex.image.get()),
                 static_cast<const void*>(&loaded->assets.at(tex.asset).data->textures[size_t(tex.meshTexture)]));
    }
    // A second save writes no blob: nothing changed.
    SaveReport report;
    QVERIFY(saveScene(*loaded, path, error, &report));
    QCOMPARE(report.blobsWritten, size_t(0));
  }

  void damagedTextureBlobIsNamed() {
    std::string error;
    const std::vector<uint8_t> bytes = {1, 2, 3};
    QVERIFY(!decodeTexture(bytes.data(), bytes.size(), "texture 4 ('bumps')", error));
    QVERIFY2(error.find("texture 4 ('bumps'): its data is cut short") == 0, error.c_str());
    mesh::Texture t;
    t.width = 2;
    t.height = 2;
    t.rgba.resize(12);  // 2x2 needs 16 bytes
    std::vector<uint8_t> blob = encodeTexture(t);
    QVERIFY(!decodeTexture(blob.data(), blob.size(), "texture 5", error));
    QVERIFY2(error.find("does not match its 12 bytes of RGBA") != std::string::npos, error.c_str());
  }

  void format3FilesGetMaterialsFromTheirMeshes() {
    for (const char* name : {"format3.hscene", "format3_plain.hscene"}) {
      QTemporaryDir dir;
      const std::string copy = dir.filePath(name).toStdString();
      std::filesystem::copy_file(kFileData + "/" + name, copy);
      QCOMPARE(sceneFileVersion(copy), 3);
      std::string error;
      auto s = loadScene(copy, error);
      QVERIFY2(s, error.c_str());
      QCOMPARE(s->assets.size(), size_t(1));
      const MeshAsset& a = s->assets.begin()->second;
      // bumpy.obj had no material: one default slot.
      QCOMPARE(a.materialSlots.size(), materialSlotCount(*a.data));
      QCOMPARE(a.materialSlots.size(), size_t(1));
      const Material& m = s->materials.at(a.materialSlots[0]);
      QCOMPARE(m.name, std::string("Bumpy / default"));
      QCOMPARE(m.asset, a.id);
      QCOMPARE(s->validate(), std::string());
      // Saved as format 5, and the same after a second load.
      QVERIFY2(saveScene(*s, copy, error), error.c_str());
      QCOMPARE(sceneFileVersion(copy), kSceneFormatVersion);
      auto again = loadScene(copy, error);
      QVERIFY2(again, error.c_str());
      QCOMPARE(canonicalJson(*again), canonicalJson(*s));
    }
  }

  void removingAnAssetTakesItsMaterialsAndTextures() {
    Document doc;
    const EntityId wall = importQuad(doc, "Wall");
    importQuad(doc, "Other");
    const AssetId asset = doc.state().find(wall)->mesh->mesh;
    // Another asset's material borrows the wall's brick texture.
    const TextureId brick = doc.state().materials.at(doc.state().findMaterialByName("Wall / brick")).baseColorTexture;
    const MaterialId other = doc.state().findMaterialByName("Other / red");
    std::string error;
    QVERIFY(ops::setMaterialField(doc, other, field("normal_map"), FieldValue(int64_t(brick)), error));
    const std::string before = canonicalJson(doc.state());
    {
      Edit e(doc, "Delete");
      e.removeEntity(wall);
      e.removeAsset(asset);
      QVERIFY(e.commit());
    }
    QCOMPARE(doc.state().materials.size(), size_t(3));  // Other's three
    QCOMPARE(doc.state().textures.size(), size_t(1));   // Other's brick
    QCOMPARE(doc.state().materials.at(other).normalMap, kNoTexture);
    QCOMPARE(doc.state().validate(), std::string());
    doc.undoStack()->undo();
    QCOMPARE(canonicalJson(doc.state()), before);
  }

  // A material assigned to another asset's slot outlives the asset it came
  // with (it becomes the scene's); undo brings everything back.
  void assignedMaterialsOutliveTheirAsset() {
    Document doc;
    const EntityId wall = importQuad(doc, "Wall");
    const EntityId other = importQuad(doc, "Other");
    const AssetId wallAsset = doc.state().find(wall)->mesh->mesh;
    const AssetId otherAsset = doc.state().find(other)->mesh->mesh;
    const MaterialId wallRed = doc.state().findMaterialByName("Wall / red");
    std::string error;
    QVERIFY(ops::assignMaterial(doc, otherAsset, 1, wallRed, error));
    QCOMPARE(doc.state().assets.at(otherAsset).materialSlots[1], wallRed);
    QVERIFY(!ops::assignMaterial(doc, otherAsset, 1, wallRed, error));  // already: no step
    QVERIFY(error.empty());
    QVERIFY(!ops::assignMaterial(doc, otherAsset, 7, wallRed, error));
    QVERIFY2(error.find("has no material slot 7 (slots 0 to 2)") != std::string::npos, error.c_str());
    const std::string before = canonicalJson(doc.state());
    {
      Edit e(doc, "Delete");
      e.removeEntity(wall);
      e.removeAsset(wallAsset);
      QVERIFY(e.commit());
    }
    const Material* kept = doc.state().findMaterial(wallRed);
    QVERIFY(kept);
    QCOMPARE(kept->asset, kNoAsset);
    QCOMPARE(doc.state().findMaterialByName("Wall / brick"), kNoMaterial);  // unassigned: gone with it
    QCOMPARE(doc.state().materials.size(), size_t(4));  // Other's three and Wall's red
    QCOMPARE(doc.state().validate(), std::string());
    doc.undoStack()->undo();
    QCOMPARE(canonicalJson(doc.state()), before);

    // A new material copies its model's fields; names are checked as renames are.
    const MaterialId copy = ops::addMaterial(doc, "Copy", wallRed, error);
    QVERIFY2(copy != kNoMaterial, error.c_str());
    Material expect = doc.state().materials.at(wallRed);
    expect.id = copy;
    expect.asset = kNoAsset;
    expect.name = "Copy";
    QVERIFY(doc.state().materials.at(copy) == expect);
    QCOMPARE(ops::addMaterial(doc, "Copy", kNoMaterial, error), kNoMaterial);
    QVERIFY2(error == "new material: name: another material is named 'Copy'", error.c_str());
  }

  void materialsMissingFromTheirAssetAreRefusedOnLoad() {
    Document doc;
    importQuad(doc, "Wall");
    Json j = sceneToJson(doc.state());
    j["materials"].erase(0);  // an asset's slot now names a missing material
    std::string error;
    QVERIFY(!sceneFromJson(j, error));
    QVERIFY2(error.find("uses missing material") != std::string::npos, error.c_str());
  }
};

QTEST_GUILESS_MAIN(TestSceneMaterials)
#include "test_scene_materials.moc"
