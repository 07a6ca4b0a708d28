// "Leave out what the scene does not need" for shader programs (issue 12):
// a scene without fog, shadows, normal maps or point/spot lights makes the
// renderer compile no fog, shadow, normal-map or clustered-light variant,
// and a scene with them compiles exactly those defines. Read from the
// shader library's list of built programs (Renderer::builtPrograms), not
// from the passes.
#include <QtTest>

#include <algorithm>
#include <string>

#include "material_scenes.h"
#include "mesh/primitives.h"
#include "render/offscreen_renderer.h"
#include "scene/scene_state.h"

using namespace hs;

namespace {

// The programs built with a define starting with `prefix`, by name.
QStringList withDefine(const std::vector<render::BuiltProgram>& built, const std::string& prefix) {
  QStringList out;
  for (const render::BuiltProgram& p : built)
    if (std::any_of(p.defines.begin(), p.defines.end(), [&](const std::string& d) { return d.rfind(prefix, 0) == 0; }))
      out << QString::fromStdString(p.name);
  return out;
}

QStringList named(const std::vector<render::BuiltProgram>& built, const std::string& part) {
  QStringList out;
  for (const render::BuiltProgram& p : built)
    if (p.name.find(part) != std::string::npos) out << QString::fromStdString(p.name);
  return out;
}

// A flat 2 x 2 normal map (straight up), enough to ask for the variant.
mesh::Texture flatNormalMap() {
  mesh::Texture t;
  t.name = "flat";
  t.width = t.height = 2;
  for (int i = 0; i < 16; ++i) t.rgba.push_back(i % 4 < 2 ? 128 : 255);
  return t;
}

}  // namespace

class TestShaderVariants : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

  // A fresh library: programs of earlier frames do not count.
  void restart() {
    r_.renderer().shutdown();
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  void plainSceneBuildsNoOptionalVariant() {
    restart();
    scene::Material m;
    m.model = scene::LightingModel::Lambert;
    test::MaterialScene ms = test::materialScene(mesh::uvSphere(1.0f, 32, 16), m, 64);
    ms.state.settings.shadows = false;
    ms.state.settings.fogMode = scene::FogMode::None;
    render::FrameStats stats;
    const hs::Image img = r_.render(ms.state, ms.view, false, &stats);
    QVERIFY(!img.rgba8.empty());
    const auto built = r_.renderer().builtPrograms();
    // The frame drew the sphere with a mesh program.
    QVERIFY(!named(built, "mesh.frag").isEmpty());
    QVERIFY2(withDefine(built, "FOG_").isEmpty(), qPrintable(withDefine(built, "FOG_").join("; ")));
    QVERIFY2(withDefine(built, "HAS_").isEmpty(), qPrintable(withDefine(built, "HAS_").join("; ")));
    QVERIFY2(withDefine(built, "LIGHTS_CLUSTERED").isEmpty(), qPrintable(withDefine(built, "LIGHTS_").join("; ")));
    QVERIFY2(named(built, "shadow").isEmpty(), qPrintable(named(built, "shadow").join("; ")));
    QVERIFY2(withDefine(built, "SHADOW").isEmpty(), qPrintable(withDefine(built, "SHADOW").join("; ")));
  }

  void sceneWithEverythingBuildsThoseVariants() {
    restart();
    scene::Material m;
    m.model = scene::LightingModel::Lambert;
    test::MaterialScene ms = test::materialScene(mesh::uvSphere(1.0f, 32, 16), m, 64);
    scene::SceneState& s = ms.state;
    s.settings.shadows = true;
    s.entities.at(2).light->castsShadows = true;  // the scene's sun (material_scenes.h); each light's flag is read
    s.settings.fogMode = scene::FogMode::DepthCue;
    scene::TextureAsset ta;
    ta.id = 1;
    ta.name = "flat";
    ta.contentHash = 1;
    ta.image = std::make_shared<const mesh::Texture>(flatNormalMap());
    s.textures[ta.id] = ta;
    s.materials.at(ms.material).normalMap = ta.id;
    scene::Entity lamp;
    lamp.id = s.maxEntityId() + 1;
    lamp.name = "Lamp";
    lamp.light = scene::Light{};
    lamp.light->type = scene::Light::Type::Point;
    lamp.light->range = 10.0f;
    lamp.transform.translation = {0.0, 0.0, 2.0};
    s.entities.emplace(lamp.id, lamp);
    s.roots.push_back(lamp.id);
    r_.render(ms.state, ms.view);
    const auto built = r_.renderer().builtPrograms();
    // One mesh program carries all of them.
    const QStringList mesh = named(built, "mesh.vert + mesh.frag [");
    const auto all = std::any_of(built.begin(), built.end(), [](const render::BuiltProgram& p) {
      auto has = [&](const char* d) { return std::find(p.defines.begin(), p.defines.end(), d) != p.defines.end(); };
      return has("FOG_DEPTH_CUE") && has("HAS_NORMAL_MAP") && has("HAS_TANGENTS") && has("LIGHTS_CLUSTERED");
    });
    QVERIFY2(all, qPrintable(mesh.join("; ")));
    QVERIFY2(!named(built, "shadow_depth.frag").isEmpty(), qPrintable(named(built, "").join("; ")));
  }
};

QTEST_GUILESS_MAIN(TestShaderVariants)
#include "test_shader_variants.moc"
