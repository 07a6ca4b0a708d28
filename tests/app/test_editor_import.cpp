// The Import dialog as a user drives it: File > Import Mesh… opens it after
// the file choice; Preview decimates at several targets on a worker (the
// dialog keeps answering, Cancel stops it) and fills the table and curve;
// Import commits a decimated mesh with 2 LODs as one undo step, shows the
// error report and its summary in Messages; the Properties panel reopens the
// report; undo removes everything the import added; a file that crashes
// the reader costs an error message, not the session; an import with a
// cluster hierarchy streams in the viewport, the status bar says so.
#include <QApplication>
#include <QPointer>
#include <QPushButton>
#include <QRegularExpression>
#include <QSignalSpy>
#include <QTableWidget>
#include <QCheckBox>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeWidget>

#include "app/app_settings.h"
#include "app/error_curve.h"
#include "app/error_report_dialog.h"
#include "app/import_dialog.h"
#include "app/mesh_export_dialog.h"
#include "app/import_preview.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "app/property_panel.h"
#include "app/selection.h"
#include "app/status_bar.h"
#include "app/viewport_widget.h"
#include "editor_fixture.h"
#include "two_material_obj.h"

using namespace hs;
using hs::app::MainWindow;

namespace {

const QString kBunny = QString(HS_SOURCE_DIR) + "/resources/demo/stanford-bunny.obj";

// Every visible error report window (they delete themselves when closed).
QList<app::ErrorReportDialog*> reportWindows() {
  QList<app::ErrorReportDialog*> out;
  for (QWidget* w : QApplication::topLevelWidgets())
    if (auto* d = qobject_cast<app::ErrorReportDialog*>(w); d && d->isVisible()) out << d;
  return out;
}

bool treeHasField(QTreeWidget* tree, const QString& key) {
  for (int i = 0; i < tree->topLevelItemCount(); ++i)
    for (int j = 0; j < tree->topLevelItem(i)->childCount(); ++j)
      if (tree->topLevelItem(i)->child(j)->text(2) == key) return true;
  return false;
}

}  // namespace

class EditorImportTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    QVERIFY(app::settingsSandboxed());
    w_ = std::make_unique<MainWindow>();
    prompts_ = test::setQuietPrompts(*w_);
    w_->resize(1000, 700);
    w_->newScene();
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
  }

  void fileMenuOpensTheDialogAfterTheFileChoice() {
    prompts_->openAnswer = kBunny;
    w_->requestImport();
    QTRY_VERIFY(w_->findChild<app::ImportDialog*>() != nullptr);
    auto* dialog = w_->findChild<app::ImportDialog*>();
    QVERIFY(dialog->isVisible());
    QCOMPARE(dialog->files(), QStringList{kBunny});
    // Cancel commits nothing.
    const size_t entities = w_->document().state().entities.size();
    dialog->reject();
    QTRY_VERIFY(w_->findChild<app::ImportDialog*>() == nullptr);  // deleted on close
    QCOMPARE(w_->document().state().entities.size(), entities);
  }

  void previewCanBeCancelled() {
    app::ImportDialog* dialog = w_->openImportDialog({kBunny});
    QVERIFY(dialog);
    auto* previewButton = dialog->findChild<QPushButton*>("previewButton");
    auto* cancelButton = dialog->findChild<QPushButton*>("cancelPreviewButton");
    QVERIFY(previewButton && cancelButton);
    QSignalSpy finished(dialog->preview(), &app::ImportPreview::finished);
    QTest::mouseClick(previewButton, Qt::LeftButton);
    QVERIFY(dialog->preview()->isRunning());
    QVERIFY(cancelButton->isEnabled() && !previewButton->isEnabled());
    QTest::mouseClick(cancelButton, Qt::LeftButton);
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 30000);
    QVERIFY(dialog->preview()->cancelled());
    QVERIFY(dialog->preview()->points().empty());
    QVERIFY(previewButton->isEnabled());
    dialog->reject();
  }

  void previewCommitReportAndUndo() {
    app::ImportDialog* dialog = w_->openImportDialog({kBunny});
    QVERIFY(dialog);
    dialog->setDecimation(true, app::ImportDialog::Target::Ratio, 20.0);
    dialog->setLodLevels(2);
    // The refinement is asked the positive way round; --no-refine's words
    // are its tooltip.
    auto* refine = dialog->findChild<QCheckBox*>("refine");
    QVERIFY(refine);
    QVERIFY(refine->toolTip().contains("least-squares"));
    refine->setChecked(false);
    QVERIFY(!dialog->request().processing.refine);
    refine->setChecked(true);
    auto* certify = dialog->findChild<QCheckBox*>("certify");
    QVERIFY(certify);
    certify->setChecked(true);
    QVERIFY(dialog->request().processing.error.certify);
    certify->setChecked(false);
    const scene::MeshImportRequest request = dialog->request();
    QVERIFY(request.processing.refine);
    QVERIFY(request.process && request.processing.decimate);
    QCOMPARE(request.processing.decimation.targetRatio, 0.2);
    QCOMPARE(request.processing.lodLevels, 2);

    // Preview on a worker: the dialog keeps handling events meanwhile.
    QSignalSpy progress(dialog->preview(), &app::ImportPreview::progress);
    QSignalSpy finished(dialog->preview(), &app::ImportPreview::finished);
    QTest::mouseClick(dialog->findChild<QPushButton*>("previewButton"), Qt::LeftButton);
    int turns = 0;
    while (dialog->preview()->isRunning() && turns < 6000) {
      QTest::qWait(5);  // the event loop turns: the UI is not blocked
      ++turns;
    }
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 30000);
    QVERIFY(progress.count() > 0);
    QVERIFY2(dialog->preview()->error().isEmpty(), qPrintable(dialog->preview()->error()));
    const auto& points = dialog->preview()->points();
    QCOMPARE(points.size(), size_t(7));  // 50% .. 1% and the chosen 20%
    auto* table = dialog->findChild<QTableWidget*>("previewTable");
    QCOMPARE(table->rowCount(), 7);
    int chosen = 0;
    for (const auto& p : points) {
      QVERIFY(p.hausdorff > 0 && p.hausdorffRel > 0);
      chosen += p.chosen;
    }
    QCOMPARE(chosen, 1);
    // Fewer triangles, more error: the ends of the curve say so.
    QVERIFY(points.front().triangles > points.back().triangles);
    QVERIFY(points.front().hausdorff < points.back().hausdorff);
    QCOMPARE(dialog->findChild<app::ErrorCurve*>()->points().size(), size_t(7));
    QVERIFY(table->item(0, 1)->text().remove(QRegularExpression("[^0-9]")).toULongLong() == points.front().triangles);

    // Import: one undo step with the decimated mesh, two levels and the report.
    const scene::SceneState before = w_->document().state();
    const int steps = w_->document().undoStack()->count();
    QTest::mouseClick(dialog->findChild<QPushButton*>("importButton"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(!w_->isBusy() && w_->document().state().assets.size() == before.assets.size() + 1, 60000);
    QCOMPARE(w_->document().undoStack()->count(), steps + 1);
    const scene::EntityId id = w_->selection().primary();
    const scene::Entity* e = w_->document().state().find(id);
    QVERIFY(e && e->mesh);
    QCOMPARE(e->name, std::string("stanford-bunny"));
    const scene::MeshAsset* a = w_->document().state().findAsset(e->mesh->mesh);
    QVERIFY(a && a->data);
    QVERIFY2(std::abs(double(a->data->triangleCount()) - 0.2 * 69451) < 0.01 * 69451,
             qPrintable(QString::number(a->data->triangleCount())));
    QCOMPARE(a->lods.size(), size_t(2));
    QVERIFY(a->lods[0].data->triangleCount() < a->data->triangleCount());
    QVERIFY(a->lods[1].hausdorff >= a->lods[0].hausdorff && a->lods[0].hausdorff > 0);
    QVERIFY(a->processReport.contains("error") && a->processReport["error"].contains("hausdorff_m"));
    QVERIFY(a->processReport["refinement"].is_object() && a->processReport["refinement"]["moved"].get<int>() > 0);

    // The error report is shown, and its summary is in Messages.
    QTRY_COMPARE(reportWindows().size(), 1);
    app::ErrorReportDialog* report = reportWindows().front();
    for (const char* key : {"hausdorff_m", "hausdorff_rel", "mean_m", "rms_m", "p95_m", "flipped_normals",
                            "uv_displacement_texels", "boundary_seam_vertices_moved", "area_change_rel", "refinement"})
      QVERIFY2(treeHasField(report->tree(), key), key);
    report->close();
    QTRY_COMPARE(reportWindows().size(), 0);
    QVERIFY2(w_->messages()->lastText().contains("hausdorff_m"), qPrintable(w_->messages()->lastText()));
    QVERIFY(w_->messages()->lastText().contains("2 LOD levels"));

    // The Properties panel reopens it (Mesh section).
    // Looked up afresh until it is shown: the panel rebuilds its sections
    // after the import's selection change, and under load that can come late.
    QPointer<QPushButton> again;
    QTRY_VERIFY_WITH_TIMEOUT((again = w_->properties()->findChild<QPushButton*>("meshReport")) && again->isEnabled() &&
                                 again->isVisible(),
                             10000);
    QTest::qWait(50);  // let a pending rebuild run before the click
    QVERIFY(again);
    QTest::mouseClick(again, Qt::LeftButton);
    QTRY_COMPARE(reportWindows().size(), 1);
    QVERIFY(reportWindows().front()->report() == a->processReport);
    reportWindows().front()->close();
    QTRY_COMPARE(reportWindows().size(), 0);

    // The viewport draws it (at some level of detail).
    QTRY_VERIFY_WITH_TIMEOUT(w_->viewport()->lastStats().trianglesDrawn > 0 || !w_->viewport()->rendererReady(), 30000);

    // Undo: the entity, the asset, its levels and its report are gone.
    const scene::AssetId assetId = a->id;
    w_->document().undoStack()->undo();
    QCOMPARE(w_->document().state().assets.size(), before.assets.size());
    QCOMPARE(w_->document().state().entities.size(), before.entities.size());
    QVERIFY(w_->document().state().roots == before.roots);
    QVERIFY(w_->document().state().findAsset(assetId) == nullptr);
    QVERIFY(w_->document().state().find(id) == nullptr);
  }

  // A file that crashes Assimp (double free) is read in the import worker:
  // the editor stays up, says which file and why, and the document, its undo
  // history and its unsaved changes are as they were.
  void readerCrashKeepsTheSession() {
    const QString crashing = QString(HS_TEST_DATA_DIR) + "/mesh/crashes_assimp_embedded_texture.fbx";
    const scene::SceneState before = w_->document().state();
    const int undoSteps = w_->document().undoStack()->count(), undoIndex = w_->document().undoStack()->index();
    const int errorsBefore = int(prompts_->errors.size());
    QVERIFY(!w_->importMeshFile(crashing, true));
    QCOMPARE(int(prompts_->errors.size()), errorsBefore + 1);
    const QString error = prompts_->errors.back();
    QVERIFY2(error.contains("crashes_assimp_embedded_texture.fbx") && error.contains("crashed on this file (SIGABRT)"),
             qPrintable(error));
    QVERIFY2(w_->messages()->lastText().contains("Nothing was imported"), qPrintable(w_->messages()->lastText()));
    QCOMPARE(w_->document().undoStack()->count(), undoSteps);
    QCOMPARE(w_->document().undoStack()->index(), undoIndex);
    QCOMPARE(w_->document().state().entities.size(), before.entities.size());
    QCOMPARE(w_->document().state().assets.size(), before.assets.size());
    // And the next import works.
    QVERIFY(w_->importMeshFile(QString(HS_TEST_DATA_DIR) + "/mesh/textured_quad.glb", true));
    QCOMPARE(w_->document().undoStack()->index(), undoIndex + 1);
  }

  // File > Export Mesh: the dialog offers the scene's meshes (the selected
  // entity first), the export runs on a worker and writes a file another
  // reader (Assimp, for GLB) reads with the asset's triangles; a refusal
  // (a level the mesh does not have) is shown, and nothing is written.
  void exportMeshFromTheEditor() {
    QVERIFY(w_->importMeshFile(QString(HS_TEST_DATA_DIR) + "/mesh/textured_quad.obj", true));
    const scene::EntityId id = w_->selection().primary();
    const scene::Entity* e = w_->document().state().find(id);
    QVERIFY(e && e->mesh);
    const std::unique_ptr<app::MeshExportDialog> dialog = w_->makeMeshExportDialog();
    QCOMPARE(dialog->targetCombo()->currentData().toString(), QString::fromStdString(e->name));
    QVERIFY(dialog->pathEdit()->text().endsWith(".obj"));
    QTemporaryDir dir;
    dialog->pathEdit()->setText(dir.filePath("quad.glb"));
    const scene::MeshExportRequest request = dialog->request();
    QCOMPARE(request.target, e->name);
    QVERIFY(w_->exportMesh(request, true));
    const mesh::ImportResult back = mesh::importMesh(dir.filePath("quad.glb").toStdString());
    QVERIFY2(back.ok(), back.error.c_str());
    QCOMPARE(back.mesh->triangleCount(), w_->document().state().findAsset(e->mesh->mesh)->data->triangleCount());
    QVERIFY2(w_->messages()->lastText().contains("quad.glb"), qPrintable(w_->messages()->lastText()));

    scene::MeshExportRequest bad = request;
    bad.out = dir.filePath("bad.obj").toStdString();
    bad.lod = 3;
    const int errorsBefore = int(prompts_->errors.size());
    QVERIFY(!w_->exportMesh(bad, true));
    QCOMPARE(int(prompts_->errors.size()), errorsBefore + 1);
    QVERIFY2(prompts_->errors.back().contains("--lod 3"), qPrintable(prompts_->errors.back()));
    QVERIFY(!QFile::exists(dir.filePath("bad.obj")));

    // A PLY of a mesh with two materials: written, and what PLY drops is
    // in Messages.
    const std::string two = test::writeTwoMaterialObj(dir.path().toStdString());
    QVERIFY(w_->importMeshFile(QString::fromStdString(two), true));
    scene::MeshExportRequest ply = request;
    ply.target = w_->document().state().find(w_->selection().primary())->name;
    ply.out = dir.filePath("two.ply").toStdString();
    QVERIFY(w_->exportMesh(ply, true));
    QVERIFY(QFile::exists(dir.filePath("two.ply")));
    QVERIFY2(w_->messages()->lastText().contains("PLY holds no materials") &&
                 w_->messages()->lastText().contains("2 materials"),
             qPrintable(w_->messages()->lastText()));
  }

  // Import with a cluster hierarchy (the dialog's Cluster hierarchy: Build
  // one): the viewport streams its pages in, the status bar says so, and
  // View > Cluster Levels colours it by level.
  void clusteredImportStreamsInTheViewport() {
    app::ImportDialog* dialog = w_->openImportDialog({kBunny});
    QVERIFY(dialog);
    auto* clusters = dialog->findChild<QComboBox*>("clusters");
    QVERIFY(clusters);
    QCOMPARE(clusters->currentData().toString(), QString("auto"));
    QCOMPARE(dialog->request().clusters, scene::MeshImportRequest::Clusters::Auto);
    clusters->setCurrentIndex(clusters->findData("streamed"));
    QCOMPARE(dialog->request().clusters, scene::MeshImportRequest::Clusters::Streamed);
    clusters->setCurrentIndex(clusters->findData("on"));
    QCOMPARE(dialog->request().clusters, scene::MeshImportRequest::Clusters::On);
    const size_t assets = w_->document().state().assets.size();
    QTest::mouseClick(dialog->findChild<QPushButton*>("importButton"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(!w_->isBusy() && w_->document().state().assets.size() == assets + 1, 120000);
    const scene::Entity* e = w_->document().state().find(w_->selection().primary());
    QVERIFY(e && e->mesh);
    const scene::MeshAsset* a = w_->document().state().findAsset(e->mesh->mesh);
    QVERIFY(a && a->clusters);
    w_->viewport()->frameSelection();
    auto* status = w_->findChild<QLabel*>("statusClusters");
    QVERIFY(status);
    render::ClusterStats last;
    QObject::connect(w_->viewport(), &app::ViewportWidget::frameRendered, this,
                     [&](const render::FrameStats& s) { last = s.clusters; });
    test::waitForNextFrame(*w_->viewport());
    QTRY_VERIFY_WITH_TIMEOUT(last.instances == 1 && last.pagesLoading == 0, 20000);
    QVERIFY(status->isVisible());
    QVERIFY2(status->text().contains("clusters") && !status->text().contains("streaming"), qPrintable(status->text()));
    QCOMPARE(status->text(), app::clusterStreamingText(last));
    QAction* levels = w_->findChild<QAction*>("clusterLevelsAction");
    QVERIFY(levels);
    levels->trigger();
    QVERIFY(w_->viewport()->showClusterLevels());
    test::waitForNextFrame(*w_->viewport());
    levels->trigger();
    QVERIFY(!w_->viewport()->showClusterLevels());
    w_->document().undoStack()->undo();
    QCOMPARE(w_->document().state().assets.size(), assets);
  }

  void cleanupTestCase() { w_.reset(); }

 private:
  std::unique_ptr<MainWindow> w_;
  test::QuietPrompts* prompts_ = nullptr;
};

QTEST_MAIN(EditorImportTest)
#include "test_editor_import.moc"
