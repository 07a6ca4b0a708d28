#include "app/export_job.h"

#include <chrono>

#include <QEventLoop>
#include <QPointer>
#include <QtConcurrent/QtConcurrentRun>

#include "render/offscreen_renderer.h"
#include "render/render_problems.h"

namespace hs::app {

ExportJob::ExportJob(QObject* parent) : QObject(parent), outcome_(std::make_shared<ExportOutcome>()) {
  connect(&watcher_, &QFutureWatcher<void>::finished, this, [this] {
    running_ = false;
    emit finished();
  });
}

ExportJob::~ExportJob() {
  if (running_) {
    cancel();
    watcher_.waitForFinished();
  }
}

void ExportJob::cancel() {
  if (cancel_) cancel_->cancel();
}

void ExportJob::start(ExportRequest request) {
  cancel_ = std::make_shared<Progress>();
  outcome_ = std::make_shared<ExportOutcome>();
  running_ = true;
  auto cancel = cancel_;
  auto outcome = outcome_;
  QPointer<ExportJob> self(this);
  watcher_.setFuture(QtConcurrent::run([request = std::move(request), cancel, outcome, self] {
    // The worker's own GL context: the viewport's stays with the UI thread.
    render::OffscreenRenderer renderer;
    std::string error;
    if (!renderer.initialize(error)) {
      outcome->setupError = "cannot start headless OpenGL for the export: " + error;
      return;
    }
    render::StereoFrameSource source(renderer, request.scene, request.frame);
    sequencer::ExportCallbacks callbacks;
    callbacks.progress = cancel.get();
    auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    callbacks.onFrame = [&last, self](const sequencer::ExportProgress& p) {
      // At most ten updates a second reach the UI thread (and always the last).
      const auto now = std::chrono::steady_clock::now();
      if (now - last < std::chrono::milliseconds(100) && p.written + p.kept < p.total) return;
      last = now;
      if (self) QMetaObject::invokeMethod(self, [self, p] { if (self) emit self->progress(p); }, Qt::QueuedConnection);
    };
    outcome->result = sequencer::runExport(request.settings, source, callbacks);
    outcome->comfort = source.comfort();
    outcome->warnings = source.warnings();
    // What the renderer refused or clamped along the way (each once).
    for (std::string& p : render::takeRenderProblems(renderer.renderer())) outcome->warnings.push_back(std::move(p));
  }));
}

void ExportJob::waitForFinished() {
  if (!running_) return;
  QEventLoop loop;
  connect(this, &ExportJob::finished, &loop, &QEventLoop::quit);
  if (running_) loop.exec();
}

}  // namespace hs::app
