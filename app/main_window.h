#pragma once
// The editor's main window: the viewport in the middle, Outliner, Properties,
// Scene Settings and Messages docks around it, menus, toolbar and status bar.
// Document operations (new, open, save, import, recovery) are public methods
// without dialogs, which the menu actions call after their dialogs and the
// GUI test calls directly, so both take the same path. They live in
// main_window_files.cpp; this file builds the window.
#include <functional>
#include <memory>

#include <QMainWindow>
#include <QStringList>

#include "app/gizmo.h"
#include "mesh/mesh_import.h"
#include "scene/mesh_export_operation.h"
#include "scene/document.h"
#include "scene/import_pipeline.h"

class QAction;
class QActionGroup;
class QDoubleSpinBox;
class QMenu;
class QToolBar;

namespace hs::app {

class Autosave;
class CameraPathPanel;
class PathEditor;
class BackgroundJob;
class MeshExportDialog;
class ExportDialog;
class FoliagePanel;
class Keying;
class StereoPreviewSettings;
class TimelineClock;
class TimelinePanel;
class TerrainPanel;
class ImportDialog;
class ImportJob;
class MessagePanel;
class OutlinerPanel;
class Prompts;
class PropertyPanel;
class Selection;
class SettingsPanel;
class MaterialsPanel;
class LightsPanel;
class ParticlesPanel;
class StatusBarInfo;
class ViewportWidget;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  scene::Document& document() { return doc_; }
  Selection& selection() { return *selection_; }
  ViewportWidget* viewport() const { return viewport_; }
  OutlinerPanel* outliner() const { return outliner_; }
  PropertyPanel* properties() const { return properties_; }
  SettingsPanel* sceneSettings() const { return settings_; }
  SettingsPanel* postSettings() const { return post_; }
  MaterialsPanel* materialsPanel() const { return materials_; }
  LightsPanel* lightsPanel() const { return lights_; }
  MessagePanel* messages() const { return messages_; }
  Autosave* autosave() const { return autosave_; }
  // The timeline side (main_window_timeline.cpp).
  TimelineClock* timelineClock() const { return clock_; }
  TimelinePanel* timeline() const { return timeline_; }
  // The Terrain panel and its brush (terrain_panel.h).
  TerrainPanel* terrainPanel() const { return terrain_; }
  // The Foliage panel and its brush (foliage_panel.h).
  FoliagePanel* foliagePanel() const { return foliage_; }
  // The Particles panel (particles_panel.h).
  ParticlesPanel* particlesPanel() const { return particles_; }
  Keying* keying() const { return keying_; }
  StereoPreviewSettings* stereoPreview() const { return stereo_; }
  // Camera paths: the editing state and actions, and the Camera Path dock.
  PathEditor* pathEditor() const { return pathEditor_; }
  CameraPathPanel* cameraPathPanel() const { return cameraPath_; }
  // File > Export Frames…: the dialog, made on first use.
  ExportDialog* exportDialog();
  // Replaces the dialogs (tests answer questions without a modal loop).
  void setPrompts(std::unique_ptr<Prompts> prompts);
  Prompts& prompts() { return *prompts_; }

  // --- Document operations, no dialogs (main_window_files.cpp) ---
  // The built-in demo as an untitled document.
  void loadDemoScene();
  // File > New's content: scene::buildStarterScene(), untitled.
  void newScene();
  // Loads on a worker with progress; on success replaces the document, on
  // failure reports and leaves it as it was. With `wait` it returns when
  // done (the event loop keeps turning) and says whether it succeeded;
  // without, it says whether the work started.
  bool openSceneFile(const QString& path, bool wait);
  // Saves a snapshot on a worker; the document stays modified on failure.
  bool saveSceneTo(const QString& path, bool wait);
  // Imports on a worker with progress and Cancel; on success adds the mesh
  // (one undo step), selects and frames it, and lists warnings in Messages;
  // on failure says why, naming the file, and changes nothing. Reads with
  // importOptions() and no processing (main_window_import.cpp).
  bool importMeshFile(const QString& path, bool wait);
  // The same for one file or the tiles of one scan with the Import dialog's
  // options (cleaning, decimation, LODs); after a decimation the error
  // report is shown and summarised in Messages.
  bool importMeshFiles(const scene::MeshImportRequest& request, bool wait);
  // File > Import Mesh… after the file choice: the Import dialog for
  // `paths`, shown without blocking; its Import runs importMeshFiles.
  ImportDialog* openImportDialog(const QStringList& paths);
  // A job (open, save, import) is running: document-replacing commands wait.
  bool isBusy() const;
  mesh::ImportOptions importOptions() const;

  // --- The same with their questions (what menus and shortcuts run) ---
  void requestNew();
  void requestOpen();
  void requestOpenRecent(const QString& path);
  bool requestSave();
  bool requestSaveAs();
  void requestImport();
  // File > Export Mesh…: the dialog, then exportMesh().
  void requestExportMesh();
  // The dialog File > Export Mesh shows (tests check its fields).
  std::unique_ptr<MeshExportDialog> makeMeshExportDialog();
  // Runs `mesh export` on a worker (progress, Cancel); `wait`: until done,
  // returning whether it succeeded (errors are shown through the prompts).
  bool exportMesh(const scene::MeshExportRequest& request, bool wait);
  // Save / Discard / Cancel when there are unsaved changes; false means stop.
  bool maybeSave();
  // Offers recovery copies left by sessions that did not end cleanly.
  void offerRecovery();
  // File > Save a Repaired Copy…: asks for the damaged scene (unless given)
  // and a new file, then repairSceneFile(). Also offered when opening a
  // damaged file fails.
  void requestRepair(const QString& damaged = {});
  // Salvages `damaged` into the new file `out` (scene/hscene_repair.h) on a
  // worker; what was dropped goes to the message panel, then the copy is
  // offered for opening. `wait`: until done, returning whether it was written.
  bool repairSceneFile(const QString& damaged, const QString& out, bool wait);

  // The window as shown, with the GL viewport's image composed in.
  bool writeScreenshot(const QString& path);
  bool selectByName(const QString& name);
  QString documentTitle() const;

 protected:
  void closeEvent(QCloseEvent* e) override;
  // Files dropped on the window: a .hscene opens, a mesh is imported.
  void dragEnterEvent(QDragEnterEvent* e) override;
  void dropEvent(QDropEvent* e) override;

 private:
  enum class Create { Empty, Camera, Sun, PointLight, SpotLight };

  void createActions();
  void createMenus();
  void createToolBar();
  void createDocks();
  void createStatusBar();
  void createTimeline();                                  // main_window_timeline.cpp
  void createCameraPathDock();                            // main_window_timeline.cpp
  void addTimelineMenus(QMenu* file, QMenu* view);        // Export Frames…, Stereo Preview, playback
  void restoreLayout();
  void saveLayout();
  void resetLayout();
  void rebuildRecentMenu();
  void updateTitle();
  void updateSelectionActions();
  void setGizmoMode(GizmoMode mode);
  void createEntity(Create what);
  void deleteSelection();
  void duplicateSelection();
  void showControls();
  void showAbout();
  void editAutosaveInterval();
  std::string uniqueName(const std::string& base) const;
  bool openInternal(const QString& path, bool wait, bool remember, std::function<void()> onSuccess);
  void onImportFinished(bool* ok);
  QString lastDirectory() const;
  void rememberDirectory(const QString& file);

  scene::Document doc_;
  Selection* selection_ = nullptr;
  std::unique_ptr<Prompts> prompts_;
  ViewportWidget* viewport_ = nullptr;
  OutlinerPanel* outliner_ = nullptr;
  PropertyPanel* properties_ = nullptr;
  SettingsPanel* settings_ = nullptr;
  SettingsPanel* post_ = nullptr;  // the Post dock
  MaterialsPanel* materials_ = nullptr;
  LightsPanel* lights_ = nullptr;
  MessagePanel* messages_ = nullptr;
  StatusBarInfo* statusInfo_ = nullptr;
  Autosave* autosave_ = nullptr;
  TimelineClock* clock_ = nullptr;
  Keying* keying_ = nullptr;
  StereoPreviewSettings* stereo_ = nullptr;
  TimelinePanel* timeline_ = nullptr;
  PathEditor* pathEditor_ = nullptr;
  CameraPathPanel* cameraPath_ = nullptr;
  int errorsShown_ = 0;  // errors the Messages tab was raised for (main_window_timeline.cpp)
  ExportDialog* exportDialog_ = nullptr;
  TerrainPanel* terrain_ = nullptr;
  FoliagePanel* foliage_ = nullptr;
  ParticlesPanel* particles_ = nullptr;
  std::unique_ptr<BackgroundJob> docJob_;
  std::unique_ptr<BackgroundJob> exportJob_;  // File > Export Mesh
  std::unique_ptr<ImportJob> importJob_;
  QString untitledName_ = "Untitled";
  quint64 revision_ = 0;  // bumps on every document change (save checks it)
  QByteArray defaultState_;

  QMenu* recentMenu_ = nullptr;
  QToolBar* toolBar_ = nullptr;
  QAction *newAct_ = nullptr, *openAct_ = nullptr, *saveAct_ = nullptr, *saveAsAct_ = nullptr,
          *importAct_ = nullptr, *exportMeshAct_ = nullptr, *repairAct_ = nullptr, *quitAct_ = nullptr;
  QAction *undoAct_ = nullptr, *redoAct_ = nullptr, *deleteAct_ = nullptr, *duplicateAct_ = nullptr,
          *renameAct_ = nullptr, *selectAllAct_ = nullptr, *selectNoneAct_ = nullptr;
  QAction *frameAct_ = nullptr, *frameAllAct_ = nullptr, *gridAct_ = nullptr, *resetLayoutAct_ = nullptr;
  QAction* depthComplexityAct_ = nullptr;
  QAction* clusterLevelsAct_ = nullptr;
  QAction* postSplitAct_ = nullptr;
  QAction *selectModeAct_ = nullptr, *moveAct_ = nullptr, *rotateAct_ = nullptr, *scaleAct_ = nullptr,
          *localAct_ = nullptr, *snapAct_ = nullptr;
  QActionGroup* upAxisGroup_ = nullptr;
  QDoubleSpinBox *snapMove_ = nullptr, *snapRotate_ = nullptr, *snapScale_ = nullptr;
};

}  // namespace hs::app
