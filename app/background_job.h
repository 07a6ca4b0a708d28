#pragma once
// Runs long work (import, open, save) on a worker thread with a progress
// dialog whose Cancel reaches the work through hs::Progress. The UI thread
// only ever sees queued progress updates and the finished() signal, so it
// stays responsive. The work writes its results into state it captured;
// finished() is the moment the UI thread may read them.
#include <atomic>
#include <functional>
#include <memory>

#include <QFutureWatcher>
#include <QObject>
#include <QPointer>
#include <QString>

#include "core/progress.h"

class QProgressDialog;
class QWidget;

namespace hs::app {

class BackgroundJob : public QObject {
  Q_OBJECT
 public:
  using Work = std::function<void(const Progress& progress)>;

  // `dialogParent` gets a window-modal progress dialog if the work takes
  // longer than `showAfterMs` (quick jobs show no flashing dialog).
  BackgroundJob(QWidget* dialogParent, const QString& title, const QString& label, bool cancellable,
                int showAfterMs = 300);
  // Waits for the worker: the work may use what this job owns.
  ~BackgroundJob() override;

  void start(Work work);
  bool isRunning() const { return running_; }
  void cancel();
  bool cancelRequested() const { return progress_->cancelled(); }
  // Keeps the event loop turning (repaints, Cancel) until finished().
  void waitForFinished();

 signals:
  void finished();

 private:
  void onProgress(double fraction, const QString& stage);
  void onFinished();

  std::shared_ptr<Progress> progress_;
  QFutureWatcher<void> watcher_;
  QPointer<QProgressDialog> dialog_;
  QString label_;
  bool running_ = false;
  // Progress from the worker arrives faster than is worth drawing: only
  // changes of at least 0.5% or a new stage are forwarded.
  std::atomic<int> lastPermille_{-10};
};

}  // namespace hs::app
