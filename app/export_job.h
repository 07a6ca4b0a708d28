#pragma once
// An export off the UI thread: a worker makes its own headless GL context
// (render::OffscreenRenderer, EGL), renders the frames of a snapshot of the
// scene through render::StereoFrameSource and writes them with
// sequencer::runExport, exactly as `hybridscape-cli render --frames` does,
// so the editor and the CLI write the same files and resume each other's
// runs. Progress arrives on the UI thread; cancel() stops after the frames in
// flight are written.
#include <memory>

#include <QFutureWatcher>
#include <QObject>

#include "core/progress.h"
#include "render/stereo_frame_source.h"
#include "scene/scene_state.h"
#include "sequencer/export_loop.h"

namespace hs::app {

struct ExportRequest {
  scene::SceneState scene;  // a snapshot: editing goes on while it runs
  sequencer::ExportSettings settings;
  render::StereoFrameOptions frame;
};

struct ExportOutcome {
  sequencer::ExportResult result;
  std::vector<sequencer::FrameComfort> comfort;
  std::vector<std::string> warnings;
  std::string setupError;  // no GL, ...
};

class ExportJob : public QObject {
  Q_OBJECT
 public:
  explicit ExportJob(QObject* parent = nullptr);
  ~ExportJob() override;  // cancels and waits for the worker

  void start(ExportRequest request);
  void cancel();
  bool isRunning() const { return running_; }
  // Keeps the event loop turning until finished() (tests, closing).
  void waitForFinished();
  const ExportOutcome& outcome() const { return *outcome_; }

 signals:
  void progress(const hs::sequencer::ExportProgress& progress);
  void finished();

 private:
  std::shared_ptr<Progress> cancel_;
  std::shared_ptr<ExportOutcome> outcome_;
  QFutureWatcher<void> watcher_;
  bool running_ = false;
};

}  // namespace hs::app
