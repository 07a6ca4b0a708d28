// The editor's fields for every shared operation, checked against the
// declarations in the registry (scene/operation_registry.h): each dialog or
// panel that runs an operation is opened, and for every parameter the
// declaration marks as shown in the editor its field (found by the
// parameter's key, app/param_widgets.h) has exactly the declared range, and
// a choice lists exactly the declared choices in order. The CLI is checked
// against the same declarations (tests/cli/test_cli_params.cpp): the two
// frontends cannot drift apart.
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QSpinBox>
#include <QTest>

#include <functional>
#include <map>
#include <memory>

#include "app/camera_path_panel.h"
#include "app/export_dialog.h"
#include "app/foliage_dialogs.h"
#include "app/particles_panel.h"
#include "app/import_dialog.h"
#include "app/main_window.h"
#include "app/mesh_export_dialog.h"
#include "app/param_widgets.h"
#include "app/terrain_dialogs.h"
#include "app/timeline_panel.h"
#include "editor_fixture.h"
#include "scene/operation_registry.h"

using namespace hs;

class EditorParamsTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private:
  std::unique_ptr<app::MainWindow> w_;
  std::vector<std::unique_ptr<QWidget>> dialogs_;

  // The widgets showing each operation's parameters.
  std::map<std::string, std::vector<QWidget*>> roots_;

  template <class D, class... A>
  QWidget* open(A&&... args) {
    dialogs_.push_back(std::make_unique<D>(std::forward<A>(args)...));
    return dialogs_.back().get();
  }

  // Every widget under `roots` made for number `component` of parameter `key`.
  static std::vector<QWidget*> fieldsOf(const std::vector<QWidget*>& roots, const std::string& key, int component) {
    std::vector<QWidget*> out;
    for (QWidget* root : roots)
      for (QWidget* w : root->findChildren<QWidget*>())
        if (w->property(app::kParamProperty).toString() == QString::fromStdString(key) &&
            w->property(app::kComponentProperty).toInt() == component)
          out.push_back(w);
    return out;
  }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    QVERIFY(app::settingsSandboxed());
    w_ = std::make_unique<app::MainWindow>();
    test::setQuietPrompts(*w_, test::QuietPrompts::Errors::Warn);
    w_->newScene();
    roots_["import"] = {open<app::ImportDialog>(QStringList{HS_TEST_DATA_DIR "/mesh/textured_quad.obj"},
                                                mesh::ImportOptions{})};
    roots_["terrain new"] = {open<app::NewTerrainDialog>(nullptr, "Terrain")};
    roots_["terrain import"] = {open<app::DemImportDialog>(nullptr, "dem.tif", true)};
    roots_["terrain erode"] = {open<app::ErosionDialog>(nullptr, false, QStringList{}),
                               open<app::ErosionDialog>(nullptr, true, QStringList{"Grass"})};
    roots_["render"] = {w_->exportDialog()};
    roots_["sequence"] = {w_->timeline()};
    roots_["path"] = {w_->cameraPathPanel()};
    dialogs_.push_back(w_->makeMeshExportDialog());
    roots_["mesh export"] = {dialogs_.back().get()};
    foliage::FoliageType pines;
    pines.name = "Pines";
    pines.mesh = "Pine";
    roots_["foliage type add"] = {open<app::FoliageTypeDialog>(nullptr, QStringList{"Pine"}, QStringList{"Grass"}),
                                  open<app::FoliageTypeDialog>(nullptr, QStringList{"Pine"}, QStringList{}, &pines)};
    roots_["foliage scatter"] = {
        open<app::FoliageScatterDialog>(nullptr, std::vector<foliage::FoliageType>{pines}, 0, QStringList{"Grass"})};
    roots_["foliage fill"] = {
        open<app::FoliageFillDialog>(nullptr, std::vector<foliage::FoliageType>{pines}, 0, QStringList{"Grass"})};
    roots_["foliage plant"] = {open<app::PlantDialog>(nullptr, "Plant")};
    roots_["foliage move"] = {open<app::FoliageMoveDialog>(nullptr, size_t(3))};
    roots_["particles add"] = {open<app::ParticlesAddDialog>(nullptr, glm::dvec3(0.0))};
  }

  void cleanupTestCase() {
    dialogs_.clear();
    w_.reset();
  }

  void everyEditorFieldHasTheDeclaredRange_data() {
    QTest::addColumn<QString>("operation");
    QTest::addColumn<QString>("key");
    int rows = 0;
    for (const OperationDecl* op : scene::sharedOperations())
      for (const ParamDecl& p : op->params)
        if (p.editor) {
          QTest::newRow((op->name + " " + p.key).c_str()) << QString::fromStdString(op->name)
                                                          << QString::fromStdString(p.key);
          ++rows;
        }
    QVERIFY(rows > 20);
  }

  void everyEditorFieldHasTheDeclaredRange() {
    QFETCH(QString, operation);
    QFETCH(QString, key);
    const OperationDecl* op = scene::findOperation(operation.toStdString());
    QVERIFY(op);
    const ParamDecl& p = op->param(key.toStdString());
    QVERIFY2(roots_.count(op->name), qPrintable(operation + " shows parameters in the editor but this test opens "
                                                            "none of its dialogs"));
    const std::vector<QWidget*>& roots = roots_.at(op->name);
    // A flag is a check box; a text a line to type in or a list of names
    // (a type's mesh: the scene's assets). Neither has a range to compare.
    if (p.type == ParamType::Flag || p.type == ParamType::Text) {
      const std::vector<QWidget*> fields = fieldsOf(roots, p.key, -1);
      QVERIFY2(!fields.empty(), qPrintable(operation + ": no field for " + key));
      for (QWidget* w : fields) {
        const bool fits = p.type == ParamType::Flag ? qobject_cast<QCheckBox*>(w) != nullptr
                                                    : qobject_cast<QLineEdit*>(w) || qobject_cast<QComboBox*>(w);
        QVERIFY2(fits, qPrintable(operation + ": the field of " + key + " is a " + w->metaObject()->className()));
      }
      return;
    }
    if (p.type == ParamType::Choice) {
      const std::vector<QWidget*> fields = fieldsOf(roots, p.key, -1);
      QVERIFY2(!fields.empty(), qPrintable(operation + ": no field for " + key));
      for (QWidget* w : fields) {
        auto* combo = qobject_cast<QComboBox*>(w);
        QVERIFY2(combo, qPrintable(operation + ": " + key + " is not a list"));
        QCOMPARE(combo->count(), int(p.choices.size()));
        for (int i = 0; i < combo->count(); ++i)
          QCOMPARE(combo->itemData(i).toString(),
                   QString::fromStdString(p.choices[size_t(i)].substr(0, p.choices[size_t(i)].find('|'))));
      }
      return;
    }
    QCOMPARE(int(p.type), int(ParamType::Number));
    for (int c = p.count == 1 ? -1 : 0; c < (p.count == 1 ? 0 : p.count); ++c) {
      const std::vector<QWidget*> fields = fieldsOf(roots, p.key, c);
      QVERIFY2(!fields.empty(), qPrintable(QString("%1: no field for %2 [%3]").arg(operation, key).arg(c)));
      const double lo = componentMin(p, std::max(c, 0)), hi = componentMax(p, std::max(c, 0));
      for (QWidget* w : fields) {
        if (auto* i = qobject_cast<QSpinBox*>(w)) {
          QVERIFY2(p.integer, qPrintable(operation + ": " + key + " takes fractions but its field whole numbers"));
          QCOMPARE(double(i->minimum()), lo);
          QCOMPARE(double(i->maximum()), hi);
        } else if (auto* d = qobject_cast<QDoubleSpinBox*>(w)) {
          // Exactly: a field that rounds a bound away (too few decimals) fails.
          QVERIFY2(d->minimum() == lo && d->maximum() == hi,
                   qPrintable(QString("%1: %2 [%3] spans %4..%5, declared %6..%7")
                                  .arg(operation, key)
                                  .arg(c)
                                  .arg(d->minimum(), 0, 'g', 17)
                                  .arg(d->maximum(), 0, 'g', 17)
                                  .arg(lo, 0, 'g', 17)
                                  .arg(hi, 0, 'g', 17)));
        } else {
          QFAIL(qPrintable(operation + ": the field of " + key + " is not a number field"));
        }
      }
    }
  }

  // A value the editor starts with is one the CLI accepts: each number
  // field's initial value checked by the declaration.
  void initialValuesAreWithinTheDeclarations() {
    for (const OperationDecl* op : scene::sharedOperations()) {
      if (!roots_.count(op->name)) continue;
      for (const ParamDecl& p : op->params) {
        if (!p.editor || p.type != ParamType::Number) continue;
        for (int c = p.count == 1 ? -1 : 0; c < (p.count == 1 ? 0 : p.count); ++c)
          for (QWidget* w : fieldsOf(roots_.at(op->name), p.key, c)) {
            double v = 0.0;
            if (auto* i = qobject_cast<QSpinBox*>(w)) v = i->value();
            else if (auto* d = qobject_cast<QDoubleSpinBox*>(w)) v = d->value();
            ParamDecl one = p;
            one.count = 1;
            one.min = componentMin(p, std::max(c, 0));
            one.max = componentMax(p, std::max(c, 0));
            one.componentRanges.clear();
            std::string error;
            QVERIFY2(checkParam(one, Json(v), error), error.c_str());
          }
      }
    }
  }
};

QTEST_MAIN(EditorParamsTest)
#include "test_editor_params.moc"
