#pragma once
// File > Export Frames…: frame range, camera, stereo layout, eye size,
// format (PNG 8/16-bit, JPEG, TIFF, EXR, or a film: H.264/H.265 in MP4/MKV
// with stereo metadata), quality, the output pattern, resume or render
// everything again, and the comfort check. The export runs off the UI
// thread (ExportJob) with progress, an ETA and Cancel; it writes the same
// files as `hybridscape-cli render --frames` and, like it, keeps the valid
// frames of an earlier run and renders the rest. Its fields' ranges,
// defaults and tips are `render`'s declarations (sequencer::exportParamDecls).
#include <memory>

#include <QDialog>

#include "app/export_job.h"
#include "scene/document.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QSpinBox;

namespace hs::app {

class StereoPreviewSettings;

class ExportDialog : public QDialog {
  Q_OBJECT
 public:
  ExportDialog(scene::Document& doc, StereoPreviewSettings& stereo, QWidget* parent = nullptr);

  // Fills the fields from the document (range, cameras, default output).
  void resetFromDocument();
  // Starts the export with the fields' settings; false with the reason shown
  // (a bad range, pattern or folder) when it cannot start.
  bool startExport();
  ExportJob& job() { return *job_; }
  QString statusText() const;

  // Fields, for tests and scripts.
  QLineEdit* framesEdit() const { return frames_; }
  QLineEdit* outputEdit() const { return output_; }
  QComboBox* layoutBox() const { return layout_; }
  QComboBox* formatBox() const { return format_; }
  QSpinBox* widthBox() const { return width_; }
  QSpinBox* heightBox() const { return height_; }
  QCheckBox* overwriteBox() const { return overwrite_; }
  QCheckBox* comfortBox() const { return comfort_; }

 signals:
  // A line for the Messages panel when an export ends (ok: it completed).
  void exportFinished(const QString& message, bool ok);

 protected:
  void closeEvent(QCloseEvent* e) override;
  void reject() override;

 private:
  void onFormatChanged();
  void onProgress(const sequencer::ExportProgress& p);
  void onFinished();
  void setRunning(bool running);
  void chooseOutput();

  scene::Document& doc_;
  StereoPreviewSettings& stereo_;
  std::unique_ptr<ExportJob> job_;
  QLineEdit* frames_ = nullptr;
  QComboBox* camera_ = nullptr;
  QComboBox* layout_ = nullptr;
  QSpinBox *width_ = nullptr, *height_ = nullptr;
  QComboBox* format_ = nullptr;
  QLabel* qualityLabel_ = nullptr;
  QSpinBox* quality_ = nullptr;  // JPEG quality (images)
  QSpinBox* crf_ = nullptr;      // constant rate factor (films); one of the two is shown
  QLineEdit* output_ = nullptr;
  QCheckBox* overwrite_ = nullptr;
  QCheckBox* comfort_ = nullptr;
  QProgressBar* bar_ = nullptr;
  QLabel* status_ = nullptr;
  QPushButton *export_ = nullptr, *cancel_ = nullptr, *close_ = nullptr;
  int64_t total_ = 0;
};

}  // namespace hs::app
