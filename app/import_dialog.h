#pragma once
// File > Import Mesh…'s options, shown after the file choice (several files:
// the tiles of one scan, imported as one asset): up axis, reader, origin
// (offset sidecar, the file's coordinates, or by hand), cleaning, a
// decimation target (share of the triangles, a triangle count or a maximum
// error in metres) and the number of LOD levels. Preview runs the decimation
// at several targets on a worker (progress and Cancel in the dialog) and
// shows triangles against error as a table and a curve, before anything is
// committed. The dialog only gathers values; Import hands request() to the
// main window, which imports on a worker and commits one undo step.
#include <QDialog>
#include <QStringList>

#include "scene/import_pipeline.h"

class QCheckBox;
class QComboBox;
class QLineEdit;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QRadioButton;
class QSpinBox;
class QTableWidget;

namespace hs::app {

class ErrorCurve;
class ImportPreview;

class ImportDialog : public QDialog {
  Q_OBJECT
 public:
  enum class Target { Ratio = 0, Triangles = 1, MaxError = 2 };

  // `defaults`: the reader options to start from (the editor's Import Up Axis).
  ImportDialog(const QStringList& files, const mesh::ImportOptions& defaults, QWidget* parent = nullptr);
  ~ImportDialog() override;

  const QStringList& files() const { return files_; }
  // What Import commits (and what Preview previews).
  scene::MeshImportRequest request() const;
  ImportPreview* preview() const { return preview_; }

  // Setters for the options (tests, and remembered choices).
  void setDecimation(bool on, Target target, double value);
  void setLodLevels(int levels);

 public slots:
  void runPreview();
  void cancelPreview();

 private:
  void onPreviewFinished();
  void updateEnabled();
  void remember() const;

  QStringList files_;
  QComboBox *up_ = nullptr, *reader_ = nullptr, *targetKind_ = nullptr, *clusters_ = nullptr;
  QLineEdit* tilesetCrs_ = nullptr;  // 3D Tiles: the CRS an ECEF tileset goes to
  QRadioButton *originAuto_ = nullptr, *originFile_ = nullptr, *originManual_ = nullptr;
  QDoubleSpinBox* origin_[3] = {nullptr, nullptr, nullptr};
  QCheckBox *clean_ = nullptr, *decimate_ = nullptr, *refine_ = nullptr, *certify_ = nullptr;
  QDoubleSpinBox *ratio_ = nullptr, *maxError_ = nullptr;
  QSpinBox *triangles_ = nullptr, *lods_ = nullptr;
  QPushButton *previewButton_ = nullptr, *cancelPreviewButton_ = nullptr, *importButton_ = nullptr;
  QProgressBar* previewProgress_ = nullptr;
  QLabel* previewStatus_ = nullptr;
  QTableWidget* table_ = nullptr;
  ErrorCurve* curve_ = nullptr;
  ImportPreview* preview_ = nullptr;
};

}  // namespace hs::app
