#pragma once
// The Import dialog's preview of triangle count against error: on a worker
// thread, the file(s) are read and cleaned once, then decimated at a few
// targets (50% down to 1%, and the dialog's own target) and each result is
// measured against the cleaned original. Progress and Cancel go through
// hs::Progress; the UI thread only sees queued progress and finished(), so
// the dialog stays responsive. Nothing here touches the document.
#include <memory>
#include <vector>

#include <QFutureWatcher>
#include <QObject>
#include <QString>

#include "scene/import_pipeline.h"

namespace hs::app {

struct PreviewPoint {
  QString target;            // "50%", "120k", ...
  bool chosen = false;       // the dialog's own target
  size_t triangles = 0;
  double hausdorff = 0.0;    // metres
  double hausdorffRel = 0.0; // of the bounding-box diagonal
  double mean = 0.0;         // metres
  double seconds = 0.0;      // decimation time
};

class ImportPreview : public QObject {
  Q_OBJECT
 public:
  // The preview measures with fewer samples than the import's report (10
  // per face): it only has to rank targets, and stays quick on large scans.
  static constexpr double kSamplesPerFace = 2.0;

  explicit ImportPreview(QObject* parent = nullptr);
  // Cancels a running preview and waits for the worker.
  ~ImportPreview() override;

  // Starts over with `request` (its files, reader options, cleaning and, when
  // it decimates, its target as the chosen point). A running preview is
  // cancelled first.
  void start(const scene::MeshImportRequest& request);
  void cancel();
  bool isRunning() const { return running_; }

  // Valid after finished().
  const std::vector<PreviewPoint>& points() const { return points_; }  // by triangles, most first
  size_t trianglesIn() const { return trianglesIn_; }                  // after cleaning
  const QString& error() const { return error_; }
  bool cancelled() const { return cancelled_; }

 signals:
  void progress(double fraction, const QString& stage);
  void finished();

 private:
  struct Run;
  void onFinished();

  std::shared_ptr<Run> run_;
  QFutureWatcher<void> watcher_;
  bool running_ = false;
  std::vector<PreviewPoint> points_;
  size_t trianglesIn_ = 0;
  QString error_;
  bool cancelled_ = false;
};

}  // namespace hs::app
