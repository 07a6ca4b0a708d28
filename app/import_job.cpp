#include "app/import_job.h"

#include <QFileInfo>

#include "app/background_job.h"
#include "scene/operations.h"
#include "scene/tileset_import.h"

namespace hs::app {

ImportJob::ImportJob(const scene::MeshImportRequest& request, QWidget* dialogParent, QObject* parent)
    : QObject(parent),
      path_(QString::fromStdString(request.files.empty() ? std::string() : request.files.front())),
      request_(request),
      result_(std::make_shared<scene::ImportedMesh>()) {
  const QString what = request.files.size() > 1 ? QString("%1 and %2 more tiles").arg(QFileInfo(path_).fileName()).arg(request.files.size() - 1)
                                                : QFileInfo(path_).fileName();
  job_ = std::make_unique<BackgroundJob>(dialogParent, "Import Mesh", QString("Importing %1…").arg(what), true);
  connect(job_.get(), &BackgroundJob::finished, this, &ImportJob::finished);
}

ImportJob::~ImportJob() = default;

void ImportJob::start() {
  const scene::MeshImportRequest request = request_;
  std::shared_ptr<scene::ImportedMesh> out = result_;
  job_->start([request, out](const Progress& progress) { *out = scene::importMeshFiles(request, &progress); });
}

void ImportJob::waitForFinished() { job_->waitForFinished(); }
bool ImportJob::isRunning() const { return job_->isRunning(); }
void ImportJob::cancel() { job_->cancel(); }

QString importFileFilter() {
  QStringList patterns;
  for (const std::string& ext : mesh::supportedExtensions()) patterns << "*" + QString::fromStdString(ext);
  patterns << "tileset.json";
  return QString("Mesh files (%1);;3D Tiles tilesets (*.json);;All files (*)").arg(patterns.join(' '));
}

QString entityNameForFile(const QString& path) {
  const QString base = QString::fromStdString(scene::importedMeshName(path.toStdString()));
  return base.isEmpty() ? QString("Mesh") : base;
}

QString importSummary(const mesh::ImportReport& r) {
  return QString("Imported %1: %L2 triangles, %L3 vertices (%4 reader) in %5 s")
      .arg(QFileInfo(QString::fromStdString(r.file)).fileName())
      .arg(r.trianglesOut)
      .arg(r.verticesOut)
      .arg(QString::fromStdString(r.reader))
      .arg(r.seconds, 0, 'f', 2);
}

QStringList importWarnings(const mesh::ImportReport& r) {
  QStringList out;
  for (const std::string& w : r.warnings) out << QString::fromStdString(w);
  const QString file = QFileInfo(QString::fromStdString(r.file)).fileName();
  auto count = [&](size_t n, const char* what) {
    if (n) out << QString("%1: %L2 %3").arg(file).arg(n).arg(what);
  };
  count(r.nonFiniteVertices, "vertices with NaN/Inf coordinates (their faces dropped)");
  count(r.outOfRangeFaces, "faces with an index past the vertex count (dropped)");
  count(r.degenerateFaces, "degenerate faces (dropped)");
  count(r.skippedLines, "unsupported statements skipped (lines, points, ...)");
  return out;
}

scene::EntityId addImportToDocument(scene::Document& doc, scene::ImportedMesh& result, const QString& path) {
  if (!result.ok()) return scene::kNoEntity;
  return scene::ops::addImportedMesh(doc, std::move(result), entityNameForFile(path).toStdString(), path.toStdString());
}

}  // namespace hs::app
