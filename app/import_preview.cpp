#include "app/import_preview.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include <QtConcurrent/QtConcurrentRun>

#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"

namespace hs::app {
namespace {

// The targets every preview shows, as shares of the cleaned triangles.
constexpr double kRatios[] = {0.5, 0.25, 0.1, 0.05, 0.02, 0.01};

QString countText(double n) {
  if (n >= 1e6) return QString::number(n / 1e6, 'g', 3) + "M";
  if (n >= 1e3) return QString::number(n / 1e3, 'g', 3) + "k";
  return QString::number(n, 'f', 0);
}

QString targetText(const mesh::DecimateOptions& d) {
  QString t;
  if (d.targetTriangles > 0) t = countText(double(d.targetTriangles));
  else if (d.targetRatio > 0) t = QString::number(d.targetRatio * 100.0, 'g', 3) + "%";
  if (std::isfinite(d.maxError)) t += (t.isEmpty() ? "" : ", ") + QString("≤ %1 m").arg(d.maxError, 0, 'g', 3);
  return t;
}

}  // namespace

struct ImportPreview::Run {
  explicit Run(Progress::Callback callback) : progress(std::move(callback)) {}
  Progress progress;
  std::vector<PreviewPoint> points;
  size_t trianglesIn = 0;
  std::string error;
  bool cancelled = false;

  void work(scene::MeshImportRequest request) {
    // Read and clean once, as the import will (no decimation, no LODs).
    const mesh::DecimateOptions chosen = request.processing.decimation;
    const bool hasChosen = request.processing.decimate;
    request.process = true;
    request.processing.decimate = false;
    request.processing.lodLevels = 0;
    scene::ImportedMesh read;
    {
      Progress s(&progress, 0.0, 0.3);
      read = scene::importMeshFiles(request, &s);
    }
    if (read.cancelled || progress.cancelled()) {
      cancelled = true;
      return;
    }
    if (!read.ok()) {
      error = read.error;
      return;
    }
    const mesh::MeshData& original = *read.mesh;
    trianglesIn = original.triangleCount();

    std::vector<std::pair<mesh::DecimateOptions, bool>> targets;
    for (double r : kRatios) {
      mesh::DecimateOptions d = chosen;
      d.targetRatio = r;
      d.targetTriangles = 0;
      d.maxError = std::numeric_limits<double>::infinity();
      targets.emplace_back(d, false);
    }
    if (hasChosen) targets.emplace_back(chosen, true);

    mesh::ErrorOptions eo = request.processing.error;
    eo.samplesPerFace = kSamplesPerFace;
    eo.certify = false;  // the preview ranks targets; the import certifies
    const mesh::ErrorMeter meter(original, eo);
    for (size_t i = 0; i < targets.size(); ++i) {
      const auto& [d, isChosen] = targets[i];
      Progress s(&progress, 0.3 + 0.7 * double(i) / double(targets.size()), 0.3 + 0.7 * double(i + 1) / double(targets.size()));
      const auto t0 = std::chrono::steady_clock::now();
      mesh::DecimateResult r = mesh::decimate(original, d, &s);
      if (r.cancelled || progress.cancelled()) {
        cancelled = true;
        return;
      }
      if (!r.ok()) {
        error = read.import.file + ": " + r.error;
        return;
      }
      // As the import will: refined unless the dialog says not to.
      if (request.processing.refine) {
        mesh::RefineOptions ro = request.processing.refinement;
        ro.lockedOriginalVertices = d.lockedVertices;
        if (mesh::refineMaxError(meter, r.mesh, ro, &s).cancelled) {
          cancelled = true;
          return;
        }
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const mesh::ErrorReport e = meter.measure(r.mesh, &s);
      if (e.cancelled) {
        cancelled = true;
        return;
      }
      PreviewPoint p;
      p.target = targetText(d);
      p.chosen = isChosen;
      p.triangles = r.mesh.triangleCount();
      p.hausdorff = e.hausdorff;
      p.hausdorffRel = e.rel(e.hausdorff);
      p.mean = e.mean;
      p.seconds = seconds;
      points.push_back(p);
    }
    std::stable_sort(points.begin(), points.end(),
                     [](const PreviewPoint& a, const PreviewPoint& b) { return a.triangles > b.triangles; });
  }
};

ImportPreview::ImportPreview(QObject* parent) : QObject(parent) {
  connect(&watcher_, &QFutureWatcher<void>::finished, this, &ImportPreview::onFinished);
}

ImportPreview::~ImportPreview() {
  cancel();
  watcher_.waitForFinished();
}

void ImportPreview::start(const scene::MeshImportRequest& request) {
  if (running_) {
    cancel();
    watcher_.waitForFinished();
    running_ = false;
  }
  points_.clear();
  trianglesIn_ = 0;
  error_.clear();
  cancelled_ = false;
  // Worker thread to UI thread, at most every half percent (the worker
  // reports far more often than is worth drawing).
  auto last = std::make_shared<std::atomic<int>>(-10);
  auto run = std::make_shared<Run>([this, last](double fraction, std::string_view stage) {
    const int permille = int(std::lround(std::clamp(fraction, 0.0, 1.0) * 1000.0));
    if (std::abs(permille - last->load()) < 5 && permille != 1000) return;
    last->store(permille);
    const QString s = QString::fromUtf8(stage.data(), qsizetype(stage.size()));
    QMetaObject::invokeMethod(this, [this, fraction, s] { emit progress(fraction, s); }, Qt::QueuedConnection);
  });
  run_ = run;
  running_ = true;
  watcher_.setFuture(QtConcurrent::run([run, request] { run->work(request); }));
}

void ImportPreview::cancel() {
  if (run_) run_->progress.cancel();
}

void ImportPreview::onFinished() {
  // A preview that was replaced by a newer one finishes unnoticed.
  if (!run_ || watcher_.isRunning()) return;
  running_ = false;
  points_ = run_->points;
  trianglesIn_ = run_->trianglesIn;
  error_ = QString::fromStdString(run_->error);
  cancelled_ = run_->cancelled;
  emit finished();
}

}  // namespace hs::app
