#include "app/background_job.h"

#include <cmath>

#include <QEventLoop>
#include <QProgressDialog>
#include <QtConcurrent/QtConcurrentRun>

namespace hs::app {

BackgroundJob::BackgroundJob(QWidget* dialogParent, const QString& title, const QString& label, bool cancellable,
                             int showAfterMs)
    : label_(label) {
  progress_ = std::make_shared<Progress>([this](double fraction, std::string_view stage) {
    // Worker thread: hand over to the UI thread, throttled.
    const int permille = int(std::lround(std::clamp(fraction, 0.0, 1.0) * 1000.0));
    const int last = lastPermille_.load(std::memory_order_relaxed);
    if (std::abs(permille - last) < 5 && permille != 1000) return;
    lastPermille_.store(permille, std::memory_order_relaxed);
    const QString s = QString::fromUtf8(stage.data(), qsizetype(stage.size()));
    QMetaObject::invokeMethod(this, [this, fraction, s] { onProgress(fraction, s); }, Qt::QueuedConnection);
  });
  dialog_ = new QProgressDialog(label, cancellable ? QString("Cancel") : QString(), 0, 1000, dialogParent);
  dialog_->setWindowTitle(title);
  dialog_->setWindowModality(Qt::WindowModal);
  dialog_->setMinimumDuration(showAfterMs);
  dialog_->setAutoClose(false);
  dialog_->setAutoReset(false);
  dialog_->setMinimumWidth(420);
  if (!cancellable) dialog_->setCancelButton(nullptr);
  dialog_->setValue(0);
  connect(dialog_, &QProgressDialog::canceled, this, &BackgroundJob::cancel);
  connect(&watcher_, &QFutureWatcher<void>::finished, this, &BackgroundJob::onFinished);
}

BackgroundJob::~BackgroundJob() {
  if (running_) {
    progress_->cancel();
    watcher_.waitForFinished();
  }
  delete dialog_;
}

void BackgroundJob::start(Work work) {
  running_ = true;
  std::shared_ptr<Progress> progress = progress_;
  watcher_.setFuture(QtConcurrent::run([work = std::move(work), progress] { work(*progress); }));
}

void BackgroundJob::cancel() {
  progress_->cancel();
  if (dialog_) dialog_->setLabelText(label_ + "\nCancelling…");
}

void BackgroundJob::onProgress(double fraction, const QString& stage) {
  if (!dialog_ || !running_) return;
  dialog_->setValue(int(std::lround(std::clamp(fraction, 0.0, 1.0) * 1000.0)));
  if (!progress_->cancelled()) dialog_->setLabelText(stage.isEmpty() ? label_ : label_ + "\n" + stage);
}

void BackgroundJob::onFinished() {
  running_ = false;
  if (dialog_) {
    // reset() stops the dialog's own show-after-delay timer: a job that ends
    // before the delay (a file refused at once) otherwise has the dialog pop
    // up ("Opening ... 0%") on top of the error box the caller then shows,
    // whose modal loop does not run the deleteLater.
    dialog_->disconnect(this);
    dialog_->reset();
    dialog_->hide();
    dialog_->deleteLater();
  }
  emit finished();
}

void BackgroundJob::waitForFinished() {
  if (!running_) return;
  QEventLoop loop;
  connect(this, &BackgroundJob::finished, &loop, &QEventLoop::quit);
  if (running_) loop.exec();
}

}  // namespace hs::app
