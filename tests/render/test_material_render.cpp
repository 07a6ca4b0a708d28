// Materials on screen (headless EGL, llvmpipe): each lighting model against
// its formula computed here in double precision, goldens per model and per
// shading mode, unlit, emission, alpha cut-out, one- and two-sided faces,
// and textures that cannot be drawn (reported, the frame still renders).
#include <QtTest>

#include <cmath>

#include "image_compare.h"
#include "render_golden.h"
#include "mesh/procedural_textures.h"
#include "foliage/plants.h"
#include "material_scenes.h"
#include "mesh/alpha_coverage_mips.h"
#include "render/offscreen_renderer.h"
#include "scene/demo_scene.h"

using namespace hs;
using scene::LightingModel;
using scene::ShadingMode;

namespace {


glm::vec3 hdrAt(const hs::Image& img, int x, int y) {
  const float* p = &img.rgbaF[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  return {p[0], p[1], p[2]};
}

// Where the ray through pixel (x, y) meets the unit sphere at the origin.
bool sphereHit(const render::RenderView& v, int x, int y, glm::dvec3& hit) {
  const double t = std::tan(v.fovY * 0.5);
  const double ndcX = (2.0 * (x + 0.5) / v.width - 1.0) * t * v.aspect();
  const double ndcY = (1.0 - 2.0 * (y + 0.5) / v.height) * t;
  const glm::dvec3 d = glm::normalize(v.forward() + ndcX * v.right() + ndcY * v.up());
  const double b = glm::dot(v.eye, d), c = glm::dot(v.eye, v.eye) - 1.0, disc = b * b - c;
  if (disc < 0.0) return false;
  hit = v.eye + (-b - std::sqrt(disc)) * d;
  return true;
}

// The models of shaders/brdf.glsl, written again from their definitions:
// radiance per unit of illuminance (BRDF x cos), a Lambert surface
// albedo/pi, the survey's lobes (no normalisation) over pi as well.
glm::dvec3 reference(const scene::Material& m, glm::dvec3 n, glm::dvec3 l, glm::dvec3 v) {
  const double pi = 3.14159265358979;
  const double ndl = glm::dot(n, l);
  if (ndl <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 albedo(m.baseColor);
  const double ks = m.specular, shininess = m.shininess, roughness = m.roughness, metallic = m.metallic;
  switch (m.model) {
    case LightingModel::Lambert: return albedo * ndl / pi;
    case LightingModel::Phong: {
      const glm::dvec3 r = 2.0 * ndl * n - l;
      return (albedo * ndl + glm::dvec3(ks * std::pow(std::max(glm::dot(r, v), 0.0), shininess))) / pi;
    }
    case LightingModel::BlinnPhong: {
      const glm::dvec3 h = glm::normalize(l + v);
      return (albedo * ndl + glm::dvec3(ks * std::pow(std::max(glm::dot(n, h), 0.0), shininess))) / pi;
    }
    case LightingModel::Pbr: break;
  }
  const glm::dvec3 h = glm::normalize(l + v);
  const double ndv = std::max(glm::dot(n, v), 1e-4), ndh = std::max(glm::dot(n, h), 0.0),
               vdh = std::max(glm::dot(v, h), 0.0);
  const double a = std::max(roughness * roughness, 0.002), a2 = a * a;
  const double dd = ndh * ndh * (a2 - 1.0) + 1.0;
  const double D = a2 / (pi * dd * dd);
  const double V = 0.5 / (ndl * std::sqrt(ndv * ndv * (1 - a2) + a2) + ndv * std::sqrt(ndl * ndl * (1 - a2) + a2));
  const glm::dvec3 f0 = glm::mix(glm::dvec3(0.16 * ks * ks), albedo, metallic);
  const glm::dvec3 F = f0 + (glm::dvec3(1.0) - f0) * std::pow(1.0 - vdh, 5.0);
  const glm::dvec3 diffuse = (glm::dvec3(1.0) - F) * (1.0 - metallic) * albedo / pi;
  return (diffuse + D * V * F) * ndl;
}

scene::Material modelMaterial(LightingModel model) {
  scene::Material m;
  m.baseColor = {0.7f, 0.45f, 0.25f};
  m.model = model;
  m.roughness = 0.45f;
  m.metallic = 0.0f;
  m.specular = 0.5f;
  m.shininess = 24.0f;
  m.twoSided = false;
  return m;
}

const char* modelName(LightingModel m) {
  switch (m) {
    case LightingModel::Pbr: return "pbr";
    case LightingModel::Lambert: return "lambert";
    case LightingModel::Phong: return "phong";
    case LightingModel::BlinnPhong: return "blinn_phong";
  }
  return "?";
}

// A plane facing the camera (on -Y): the XY grid plane turned to face -Y.
mesh::MeshData facingPlane(float size) {
  mesh::MeshData p = mesh::gridPlane(size, 1);
  for (auto& v : p.positions) v = glm::vec3(v.x, 0.0f, v.y);  // XY -> XZ; +Z normal -> -Y
  for (auto& n : p.normals) n = glm::vec3(0, -1, 0);
  // (x, y, 0) -> (x, 0, y) is a mirror: triangles counter-clockwise seen
  // from +Z are counter-clockwise seen from -Y afterwards.
  return p;
}

// A standalone texture in `state`, used by material `id` as `slot`
// (0 base colour, 1 normal map, 2 height map).
void addMaterialTexture(scene::SceneState& state, scene::MaterialId id, int slot, const mesh::Texture& t,
                        scene::TextureId tid) {
  scene::TextureAsset ta;
  ta.id = tid;
  ta.name = t.name;
  ta.srgb = slot == 0;
  ta.contentHash = tid;  // any value that stays the same: the renderer keys its upload by it
  ta.image = std::make_shared<const mesh::Texture>(t);
  state.textures[tid] = ta;
  scene::Material& m = state.materials.at(id);
  (slot == 0 ? m.baseColorTexture : slot == 1 ? m.normalMap : m.heightMap) = tid;
}

// Height h(x, y) = kAmp sin(2 pi x) cos(2 pi y) on the 2 x 2 m plane, and its normal.
constexpr double kAmp = 0.04, kTwoPi = 6.283185307179586;
glm::dvec3 bumpNormal(double x, double y) {
  const double hx = kAmp * kTwoPi * std::cos(kTwoPi * x) * std::cos(kTwoPi * y);
  const double hy = -kAmp * kTwoPi * std::sin(kTwoPi * x) * std::sin(kTwoPi * y);
  return glm::normalize(glm::dvec3(-hx, -hy, 1.0));
}

// The normal map of that bump over the plane (u along +x, v along -y).
mesh::Texture bumpNormalMap(int size) {
  mesh::Texture t;
  t.name = "analytic bumps";
  t.width = t.height = size;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double u = (i + 0.5) / size, v = (j + 0.5) / size;
      const glm::dvec3 n = bumpNormal((u - 0.5) * 2.0, (0.5 - v) * 2.0);
      for (int c = 0; c < 3; ++c) t.rgba.push_back(uint8_t(std::lround((n[c] * 0.5 + 0.5) * 255.0)));
      t.rgba.push_back(255);
    }
  return t;
}

}  // namespace

class TestMaterialRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;


 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  void modelsMatchTheirFormulas_data() {
    QTest::addColumn<int>("model");
    for (LightingModel m : {LightingModel::Pbr, LightingModel::Lambert, LightingModel::Phong, LightingModel::BlinnPhong})
      QTest::newRow(modelName(m)) << int(m);
  }
  void modelsMatchTheirFormulas() {
    QFETCH(int, model);
    const scene::Material mat = modelMaterial(LightingModel(model));
    test::MaterialScene ms = test::materialScene(mesh::uvSphere(1.0f, 192, 96), mat);
    const hs::Image hdr = r_.render(ms.state, ms.view, true);
    QVERIFY(hdr.isFloat());
    int checked = 0;
    double worst = 0.0, sum = 0.0;
    for (int y = 4; y < ms.view.height; y += 6)
      for (int x = 4; x < ms.view.width; x += 6) {
        glm::dvec3 hit;
        if (!sphereHit(ms.view, x, y, hit)) continue;
        const glm::dvec3 v = glm::normalize(ms.view.eye - hit);
        if (glm::dot(hit, v) < 0.35) continue;  // grazing: the tessellation shows
        const glm::dvec3 want = reference(mat, hit, ms.toSun, v) * glm::dvec3(ms.sunColor);
        const glm::dvec3 got(hdrAt(hdr, x, y));
        for (int c = 0; c < 3; ++c) {
          // Half floats, and the polygon's interpolated normal against the true sphere's.
          const double err = std::abs(got[c] - want[c]) / (0.02 + 0.03 * want[c]);
          worst = std::max(worst, err);
          sum += err;
        }
        ++checked;
      }
    QVERIFY(checked > 150);
    QVERIFY2(worst <= 1.0, qPrintable(QString("worst error %1 of the tolerance (mean %2) over %3 pixels")
                                          .arg(worst).arg(sum / (3 * checked)).arg(checked)));
    // And the picture, to look at.
    test::verifyGolden(std::string("model_") + modelName(LightingModel(model)), r_.render(ms.state, ms.view));
  }

  void modelsDiffer() {
    // Their highlights differ where the formulas say: a check that the
    // model reaches the shader at all.
    std::vector<hs::Image> images;
    for (LightingModel m : {LightingModel::Pbr, LightingModel::Lambert, LightingModel::Phong, LightingModel::BlinnPhong}) {
      test::MaterialScene ms = test::materialScene(mesh::uvSphere(1.0f, 64, 32), modelMaterial(m), 96);
      images.push_back(r_.render(ms.state, ms.view));
    }
    for (size_t a = 0; a < images.size(); ++a)
      for (size_t b = a + 1; b < images.size(); ++b) {
        const auto cmp = test::compareImages(test::toTest(images[a]), test::toTest(images[b]), 6);
        QVERIFY2(cmp.differingShare > 0.01, qPrintable(QString("models %1 and %2: %3").arg(a).arg(b).arg(cmp.summary().c_str())));
      }
  }

  void shadingModeGoldens_data() {
    QTest::addColumn<int>("mode");
    QTest::newRow("phong") << int(ShadingMode::Phong);
    QTest::newRow("gouraud") << int(ShadingMode::Gouraud);
    QTest::newRow("flat") << int(ShadingMode::Flat);
  }
  void shadingModeGoldens() {
    QFETCH(int, mode);
    scene::Material m = modelMaterial(LightingModel::BlinnPhong);
    m.shininess = 40.0f;
    m.shading = ShadingMode(mode);
    // Coarse on purpose: the modes differ where triangles are large.
    test::MaterialScene ms = test::materialScene(mesh::uvSphere(1.0f, 16, 8), m);
    const hs::Image img = r_.render(ms.state, ms.view);
    const char* names[] = {"phong", "gouraud", "flat"};
    test::verifyGolden(std::string("shading_") + names[mode], img);
    if (ShadingMode(mode) == ShadingMode::Phong) return;
    // Against per-pixel shading of the same mesh: visibly different.
    m.shading = ShadingMode::Phong;
    test::MaterialScene ref = test::materialScene(mesh::uvSphere(1.0f, 16, 8), m);
    const auto cmp = test::compareImages(test::toTest(img), test::toTest(r_.render(ref.state, ref.view)), 6);
    QVERIFY2(cmp.differingShare > 0.02, cmp.summary().c_str());
  }

  void unlitShowsItsColourExactly() {
    scene::Material m = modelMaterial(LightingModel::Pbr);
    m.unlit = true;
    m.baseColor = {0.3f, 0.6f, 0.1f};
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat}) {
      m.shading = mode;
      test::MaterialScene ms = test::materialScene(mesh::uvSphere(1.0f, 32, 16), m, 64);
      const hs::Image hdr = r_.render(ms.state, ms.view, true);
      const glm::vec3 c = hdrAt(hdr, 32, 32);
      QVERIFY2(glm::all(glm::lessThan(glm::abs(c - m.baseColor), glm::vec3(2e-3f))),
               qPrintable(QString("%1 %2 %3").arg(c.r).arg(c.g).arg(c.b)));
      // The same in the shadowed lower right as in the lit upper left.
      QVERIFY(glm::all(glm::lessThan(glm::abs(hdrAt(hdr, 44, 44) - hdrAt(hdr, 20, 20)), glm::vec3(2e-3f))));
    }
  }

  // A thin two-sided surface (a leaf) with transmission t, the sun behind
  // it and then in front, sun shadows on, no ambient light: lit from behind
  // it returns t x albedo x |N.L| / pi (and is not in its own shadow), lit
  // from the front (1 - t) x albedo x N.L / pi; t = 0 is the opaque
  // surface, black from behind (Lambert: exact by hand).
  void transmissionLetsLightThroughThinSurfaces() {
    scene::Material m = modelMaterial(LightingModel::Lambert);
    m.twoSided = true;
    const double pi = 3.14159265358979;
    for (const double side : {-1.0, 1.0}) {  // -1: the sun behind the plane (seen from -Y), 1: in front
      for (const float t : {0.0f, 0.3f, 0.8f}) {
        m.transmission = t;
        test::MaterialScene ms = test::materialScene(facingPlane(3.0f), m, 64);
        scene::Entity& sun = ms.state.entities.at(2);
        sun.light->castsShadows = true;
        // Shining along (0, 0.8 side', -0.6): from above, behind or in front.
        sun.transform.rotation = scene::fromEulerDegrees({side < 0 ? -53.130102 : 53.130102, 0, 0});
        const glm::dvec3 toSun = -glm::normalize(sun.transform.rotation * glm::dvec3(0, 0, -1));
        const double ndl = glm::dot(glm::dvec3(0, -1, 0), toSun);  // the face the camera sees
        QVERIFY(std::abs(std::abs(ndl) - 0.8) < 1e-6 && ndl * side > 0.0);
        const hs::Image hdr = r_.render(ms.state, ms.view, true);
        const glm::dvec3 albedo(m.baseColor);
        const glm::dvec3 want = (ndl > 0 ? (1.0 - double(t)) : double(t)) * albedo * std::abs(ndl) / pi * glm::dvec3(ms.sunColor);
        for (const glm::ivec2 p : {glm::ivec2(32, 32), glm::ivec2(20, 40), glm::ivec2(44, 24)}) {
          const glm::dvec3 got(hdrAt(hdr, p.x, p.y));
          for (int c = 0; c < 3; ++c)
            QVERIFY2(std::abs(got[c] - want[c]) <= 2e-3 + 4e-3 * want[c],
                     qPrintable(QString("sun %1, t %2, channel %3: %4, want %5")
                                    .arg(side < 0 ? "behind" : "in front").arg(t).arg(c).arg(got[c]).arg(want[c])));
        }
      }
    }
  }

  void emissionAddsItsLight() {
    scene::Material m = modelMaterial(LightingModel::Lambert);
    test::MaterialScene dark = test::materialScene(mesh::uvSphere(1.0f, 32, 16), m, 64);
    m.emission = {0.2f, 0.1f, 0.0f};
    m.emissionStrength = 2.0f;
    test::MaterialScene glowing = test::materialScene(mesh::uvSphere(1.0f, 32, 16), m, 64);
    const hs::Image a = r_.render(dark.state, dark.view, true), b = r_.render(glowing.state, glowing.view, true);
    for (auto [x, y] : {std::pair{32, 32}, {22, 24}, {44, 44}}) {
      const glm::vec3 d = hdrAt(b, x, y) - hdrAt(a, x, y);
      QVERIFY2(glm::all(glm::lessThan(glm::abs(d - glm::vec3(0.4f, 0.2f, 0.0f)), glm::vec3(3e-3f))),
               qPrintable(QString("%1 %2 %3").arg(d.r).arg(d.g).arg(d.b)));
    }
  }

  void alphaCutoutDiscards() {
    // A texture opaque on its right half, transparent on its left.
    mesh::MeshData plane = facingPlane(2.0f);
    mesh::Texture t;
    t.name = "half";
    t.width = t.height = 8;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) t.rgba.insert(t.rgba.end(), {255, 255, 255, uint8_t(x < 4 ? 0 : 255)});
    plane.textures.push_back(t);
    plane.materials[0].diffuseTexture = 0;
    scene::Material m = modelMaterial(LightingModel::Lambert);
    m.unlit = true;
    m.baseColor = glm::vec3(1.0f);
    for (bool cutout : {false, true}) {
      m.alphaCutout = cutout;
      test::MaterialScene ms = test::materialScene(plane, m, 64);
      // The mesh's texture as a document texture of the material.
      scene::TextureAsset tex;
      tex.id = 1;
      tex.name = "half";
      tex.asset = 1;
      tex.meshTexture = 0;
      tex.image = std::shared_ptr<const mesh::Texture>(ms.state.assets.at(1).data, &ms.state.assets.at(1).data->textures[0]);
      ms.state.textures.emplace(1, tex);
      ms.state.materials.at(ms.material).baseColorTexture = 1;
      const hs::Image hdr = r_.render(ms.state, ms.view, true);
      QVERIFY(hdrAt(hdr, 44, 32).r > 0.9f);  // the opaque half
      const float left = hdrAt(hdr, 20, 32).r;
      if (cutout) QVERIFY2(left < 1e-3f, qPrintable(QString::number(left)));  // background
      else QVERIFY2(left > 0.9f, qPrintable(QString::number(left)));         // drawn (opaque pass)
    }
  }

  // A cut-out leaf texture seen far away (512 texels over 16 pixels: mip
  // level 5) keeps the cover it has close up: its mips keep level 0's
  // alpha coverage (mesh/alpha_coverage_mips.h). With GL's box-filtered
  // mips, as before, the needles fell under the threshold (none left four
  // levels down). Measured: 30 % of the plane's pixels for 24 % of level
  // 0's texels (pixel centres on texel centres: the level's texels). The plane's own pixels come
  // from the same plane with an opaque texture.
  void cutoutKeepsItsCoverageFarAway() {
    // The generated conifer's needles: thin lines, what box-filtered mips
    // lose first (test_alpha_mips).
    const mesh::Texture leaves = foliage::leafTexture(foliage::PlantKind::Conifer, 512);
    const double c0 = mesh::alphaCoverage(leaves.rgba, 0.5f);
    mesh::Texture opaque = leaves;
    for (size_t i = 3; i < opaque.rgba.size(); i += 4) opaque.rgba[i] = 255;
    scene::Material m = modelMaterial(LightingModel::Lambert);
    m.unlit = true;
    m.baseColor = glm::vec3(1.0f);
    m.alphaCutout = true;
    m.twoSided = true;
    size_t counts[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      test::MaterialScene ms = test::materialScene(facingPlane(2.0f), m, 64, 12.3);
      addMaterialTexture(ms.state, ms.material, 0, k == 0 ? leaves : opaque, 7);
      const hs::Image hdr = r_.render(ms.state, ms.view, true);
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) counts[k] += hdrAt(hdr, x, y).g > 0.02f;
    }
    const double cover = double(counts[0]) / double(std::max<size_t>(counts[1], 1));
    qInfo("cut-out leaves 16 px across: %zu of the plane's %zu pixels (%.3f); level 0 covers %.3f", counts[0],
          counts[1], cover, c0);
    QVERIFY2(counts[1] > 150 && counts[1] < 400, qPrintable(QString::number(counts[1])));  // about 16 x 16
    QVERIFY2(std::abs(cover - c0) < 0.12, qPrintable(QString::number(cover)));
  }

  void oneSidedFacesAreCulledFromBehind() {
    mesh::MeshData plane = facingPlane(2.0f);
    // Seen from behind: turn the triangles (and normals) away from the camera.
    for (size_t i = 0; i + 2 < plane.indices.size(); i += 3) std::swap(plane.indices[i + 1], plane.indices[i + 2]);
    for (auto& n : plane.normals) n = -n;
    scene::Material m = modelMaterial(LightingModel::Lambert);
    m.unlit = true;
    for (bool twoSided : {true, false}) {
      m.twoSided = twoSided;
      test::MaterialScene ms = test::materialScene(plane, m, 64);
      const float c = hdrAt(r_.render(ms.state, ms.view, true), 32, 32).r;
      if (twoSided) QVERIFY2(std::abs(c - m.baseColor.r) < 2e-3f, qPrintable(QString::number(c)));
      else QVERIFY2(c < 1e-3f, qPrintable(QString::number(c)));
    }
  }

  void normalMapGivesTheAnalyticNormals() {
    scene::Material m = modelMaterial(LightingModel::Lambert);
    test::MaterialScene ms = test::materialScene(mesh::gridPlane(2.0f, 4), m, 200);
    addMaterialTexture(ms.state, ms.material, 1, bumpNormalMap(256), 1);
    // Straight down on the plane (the identity looks along -Z with +Y up).
    ms.view.eye = {0.0, 0.0, 2.6};
    ms.view.orientation = glm::dquat(1.0, 0.0, 0.0, 0.0);
    render::RenderOptions debug;
    debug.debugShadingNormal = true;
    const hs::Image n = r_.render(ms.state, ms.view, true, nullptr, debug);
    const double t = std::tan(ms.view.fovY * 0.5);
    double worstDeg = 0.0, sumDeg = 0.0;
    int count = 0;
    for (int y = 8; y < 200; y += 8)
      for (int x = 8; x < 200; x += 8) {
        // Where the pixel's ray meets the plane z = 0.
        const double wx = (2.0 * (x + 0.5) / 200 - 1.0) * t * 2.6, wy = (1.0 - 2.0 * (y + 0.5) / 200) * t * 2.6;
        if (std::abs(wx) > 0.95 || std::abs(wy) > 0.95) continue;
        const glm::dvec3 want = bumpNormal(wx, wy), got = glm::normalize(glm::dvec3(hdrAt(n, x, y)));
        const double deg = glm::degrees(std::acos(std::clamp(glm::dot(want, got), -1.0, 1.0)));
        worstDeg = std::max(worstDeg, deg);
        sumDeg += deg;
        ++count;
      }
    QVERIFY(count > 300);
    // 8-bit texels and bilinear filtering of a map at 128 texels per metre.
    QVERIFY2(worstDeg < 2.0 && sumDeg / count < 0.6,
             qPrintable(QString("worst %1 deg, mean %2 deg over %3 pixels").arg(worstDeg).arg(sumDeg / count).arg(count)));
    // Strength 0: the flat plane's own normal.
    ms.state.materials.at(ms.material).normalStrength = 0.0f;
    const glm::vec3 flat = hdrAt(r_.render(ms.state, ms.view, true, nullptr, debug), 60, 70);
    QVERIFY2(glm::length(flat - glm::vec3(0, 0, 1)) < 2e-3f, qPrintable(QString("%1 %2 %3").arg(flat.x).arg(flat.y).arg(flat.z)));
  }

  void tangentsOnlyForMeshesWithMaps() {
    auto tangentBytes = [&] {
      size_t b = 0;
      for (const auto& a : r_.renderer().resourceRegistry())
        if (a.name == "mesh_tangents") b += a.bytes;
      return b;
    };
    r_.renderer().shutdown();
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    scene::Material m = modelMaterial(LightingModel::Lambert);
    test::MaterialScene plain = test::materialScene(mesh::uvSphere(1.0f, 32, 16), m, 64);
    r_.render(plain.state, plain.view);
    QCOMPARE(tangentBytes(), size_t(0));
    test::MaterialScene mapped = test::materialScene(mesh::uvSphere(1.0f, 32, 16), m, 64);
    addMaterialTexture(mapped.state, mapped.material, 1, bumpNormalMap(32), 1);
    r_.render(mapped.state, mapped.view);
    // One vec4 per vertex of the sphere (33 x 17).
    QCOMPARE(tangentBytes(), size_t(33 * 17 * 16));
  }

  void parallaxChangesTheRelief() {
    // Bricks on a wall seen at 60 degrees from its normal: the same normal
    // map with and without parallax occlusion mapping.
    const mesh::Texture height = mesh::brickHeightMap(256, 8, 4);
    const mesh::Texture normals = mesh::normalMapFromHeight(height, 0.03f);
    scene::Material m = modelMaterial(LightingModel::Pbr);
    m.twoSided = true;
    m.heightScale = 0.0f;
    test::MaterialScene ms = test::materialScene(mesh::gridPlane(2.0f, 1), m, 200);
    addMaterialTexture(ms.state, ms.material, 0, mesh::tintByHeight(height, {0.25f, 0.23f, 0.2f}, {0.55f, 0.2f, 0.12f}), 1);
    addMaterialTexture(ms.state, ms.material, 1, normals, 2);
    addMaterialTexture(ms.state, ms.material, 2, height, 3);
    ms.view.eye = {0.0, -1.5, 0.9};
    ms.view.orientation = test::lookFrom(ms.view.eye, {0, 0, 0}).rotation;
    ms.view.fovY = glm::radians(50.0);
    const hs::Image flat = r_.render(ms.state, ms.view);
    test::verifyGolden("normal_map_bricks", flat);
    ms.state.materials.at(ms.material).heightScale = 0.06f;  // 6 cm of relief on 25 cm courses
    const hs::Image relief = r_.render(ms.state, ms.view);
    test::verifyGolden("parallax_bricks", relief);
    const auto cmp = test::compareImages(test::toTest(relief), test::toTest(flat), 12);
    QVERIFY2(cmp.differingShare > 0.10, cmp.summary().c_str());
    // Parallax moves what is seen, it does not darken the picture: the mean stays close.
    double a = 0, b = 0;
    for (size_t i = 0; i < flat.rgba8.size(); i += 4) {
      a += flat.rgba8[i];
      b += relief.rgba8[i];
    }
    QVERIFY2(std::abs(a - b) / a < 0.1, qPrintable(QString("%1 %2").arg(a).arg(b)));
  }

  void demoHasANormalMappedAndAParallaxMappedMaterial() {
    std::string error;
    auto demo = scene::buildDemoScene(error);
    QVERIFY2(demo, error.c_str());
    const scene::MaterialId bricks = demo->findMaterialByName("Brick paving (normal map) / surface");
    const scene::MaterialId rock = demo->findMaterialByName("Rock slab (parallax) / surface");
    QVERIFY(bricks != scene::kNoMaterial && rock != scene::kNoMaterial);
    QVERIFY(demo->materials.at(bricks).normalMap != scene::kNoTexture);
    QVERIFY(demo->materials.at(rock).heightMap != scene::kNoTexture && demo->materials.at(rock).heightScale > 0.0f);
    // Standing in the clearing, looking south at the two slabs on the ground.
    render::RenderView v;
    v.width = 320;
    v.height = 180;
    v.fovY = glm::radians(45.0);
    v.eye = {0.0, -7.5, 1.6};
    v.orientation = test::lookFrom(v.eye, {0.0, -12.0, 0.0}).rotation;
    demo->settings.antialiasing = scene::Antialiasing::None;
    demo->settings.showGrid = false;
    r_.renderer().takeMaterialProblems();
    const hs::Image withParallax = r_.render(*demo, v);
    QVERIFY2(r_.renderer().takeMaterialProblems().empty(), "every texture of the samples draws");
    test::verifyGolden("demo_detail_samples", withParallax, {40, 6, 0.01});
    // Their tangents, and only theirs: 2 slabs x 4 vertices (the bunnies have no maps).
    size_t tangents = 0;
    for (const auto& a : r_.renderer().resourceRegistry())
      if (a.name == "mesh_tangents") tangents += a.bytes;
    QCOMPARE(tangents, size_t(2 * 4 * 16));
    // The rock's relief is parallax's doing: without it, a visibly different picture.
    demo->materials.at(rock).heightScale = 0.0f;
    // (The slab covers about a sixth of the view.)
    const auto cmp = test::compareImages(test::toTest(r_.render(*demo, v)), test::toTest(withParallax), 12);
    QVERIFY2(cmp.differingShare > 0.015 && cmp.maxChannelDiff > 60, cmp.summary().c_str());
  }

  void texturesThatCannotBeDrawnAreReported_data() {
    QTest::addColumn<int>("kind");
    QTest::addColumn<QString>("message");
    QTest::newRow("missing") << 0 << "material 'Sample / material': base_color_texture: texture 9 is not in the scene";
    QTest::newRow("0x0") << 1 << "material 'Sample / material': base_color_texture: texture 'bad' is empty (0x0)";
    QTest::newRow("65536x65536") << 2
                                 << "material 'Sample / material': base_color_texture: texture 'bad' is 65536x65536, "
                                    "larger than this GPU's limit of";
    QTest::newRow("damaged") << 3
                             << "material 'Sample / material': base_color_texture: texture 'bad' holds 12 bytes, not the 4x4x4";
    QTest::newRow("grey normal map") << 4
                                     << "material 'Sample / material': normal_map: texture 'bad' has one channel (grey)";
  }
  void texturesThatCannotBeDrawnAreReported() {
    QFETCH(int, kind);
    QFETCH(QString, message);
    scene::Material m = modelMaterial(LightingModel::Lambert);
    m.unlit = true;
    test::MaterialScene ms = test::materialScene(mesh::uvSphere(1.0f, 32, 16), m, 64);
    auto img = std::make_shared<mesh::Texture>();
    img->name = "bad";
    if (kind == 2) img->width = img->height = 65536;  // no pixels: it is refused before any are read
    if (kind == 3) {
      img->width = img->height = 4;
      img->rgba.resize(12);
    }
    if (kind == 4) {
      img->width = img->height = 4;
      img->rgba.assign(64, 128);
    }
    scene::TextureAsset t;
    t.id = kind == 0 ? 8 : 9;  // "missing": the material names 9, the scene has 8
    t.name = "bad";
    t.image = img;
    ms.state.textures.emplace(t.id, t);
    scene::Material& mat = ms.state.materials.at(ms.material);
    (kind == 4 ? mat.normalMap : mat.baseColorTexture) = 9;
    r_.renderer().takeMaterialProblems();
    const float c = hdrAt(r_.render(ms.state, ms.view, true), 32, 32).r;
    QVERIFY2(std::abs(c - m.baseColor.r) < 2e-3f, "the frame still renders the material without the texture");
    const std::vector<std::string> problems = r_.renderer().takeMaterialProblems();
    QCOMPARE(problems.size(), size_t(1));
    QVERIFY2(QString::fromStdString(problems[0]).startsWith(message), problems[0].c_str());
    // Reported once, not every frame.
    r_.render(ms.state, ms.view);
    QVERIFY(r_.renderer().takeMaterialProblems().empty());
  }
};

QTEST_GUILESS_MAIN(TestMaterialRender)
#include "test_material_render.moc"
