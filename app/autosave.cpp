#include "app/autosave.h"

#include <QCoreApplication>
#include <QDir>
#include <QEventLoop>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <QSettings>
#include <QtConcurrent/QtConcurrentRun>

#include <algorithm>

#include "app/app_settings.h"
#include "scene/hscene_file.h"
#include "scene/terrain_file.h"

namespace hs::app {
namespace {

// Field 22 of /proc/<pid>/stat: when the process started, in clock ticks
// since boot. Together with the pid it names a process uniquely, so a pid
// reused by another program is not mistaken for a live editor.
QString processStartTime(qint64 pid) {
  QFile f(QString("/proc/%1/stat").arg(pid));
  if (!f.open(QIODevice::ReadOnly)) return {};
  const QByteArray stat = f.readAll();
  const qsizetype close = stat.lastIndexOf(')');
  if (close < 0) return {};
  const QList<QByteArray> fields = stat.mid(close + 2).split(' ');
  // fields[0] is field 3 (state); field 22 is fields[19].
  return fields.size() > 19 ? QString::fromLatin1(fields[19]) : QString();
}

bool processAlive(qint64 pid, const QString& startTime) {
  const QString now = processStartTime(pid);
  return !now.isEmpty() && now == startTime;
}

}  // namespace

Autosave::Autosave(scene::Document& doc, QObject* parent) : QObject(parent), doc_(doc) {
  const qint64 pid = QCoreApplication::applicationPid();
  session_ = QString("session-%1-%2").arg(pid).arg(processStartTime(pid));
  timer_.setTimerType(Qt::VeryCoarseTimer);
  connect(&timer_, &QTimer::timeout, this, [this] { saveNow(false); });
  connect(&watcher_, &QFutureWatcher<void>::finished, this, &Autosave::onSaveFinished);
  connect(&doc_, &scene::Document::changed, this, [this] { ++revision_; });
  connect(&doc_, &scene::Document::filePathChanged, this, [this] {
    if (started_) writeMarker();
  });
  // Saved (or a fresh document): the recovery copy no longer holds anything
  // the user could lose.
  connect(&doc_, &scene::Document::modifiedChanged, this, [this](bool modified) {
    if (!modified && !saving_) removeRecoveryCopy();
  });
}

Autosave::~Autosave() {
  if (saving_) watcher_.waitForFinished();
}

double Autosave::intervalMinutesSetting() {
  return QSettings().value("autosave/intervalMinutes", kDefaultIntervalMinutes).toDouble();
}

void Autosave::setIntervalMinutesSetting(double minutes) { QSettings().setValue("autosave/intervalMinutes", minutes); }

void Autosave::start() {
  started_ = true;
  writeMarker();
  const double minutes = intervalMinutesSetting();
  if (minutes > 0.0) {
    timer_.start(int(std::max(minutes, 0.05) * 60000.0));
  } else {
    timer_.stop();
  }
}

QString Autosave::recoveryFile() const { return recoveryDirectory() + "/" + session_ + ".hscene"; }
QString Autosave::sessionFile() const { return recoveryDirectory() + "/" + session_ + ".session"; }

void Autosave::writeMarker() {
  QJsonObject o;
  const qint64 pid = QCoreApplication::applicationPid();
  o["pid"] = double(pid);
  o["start"] = processStartTime(pid);
  o["document"] = doc_.filePath();
  if (savedRevision_ && QFileInfo::exists(recoveryFile()))
    o["saved"] = QFileInfo(recoveryFile()).lastModified().toString(Qt::ISODate);
  QSaveFile f(sessionFile());
  if (f.open(QIODevice::WriteOnly)) {
    f.write(QJsonDocument(o).toJson());
    f.commit();
  }
}

bool Autosave::saveNow(bool wait) {
  if (saving_) {
    if (wait) {
      QEventLoop loop;
      connect(this, &Autosave::saved, &loop, &QEventLoop::quit);
      connect(this, &Autosave::failed, &loop, &QEventLoop::quit);
      loop.exec();
    }
    return true;
  }
  if (!doc_.isModified() || revision_ == savedRevision_) return false;
  saving_ = true;
  savingRevision_ = revision_;
  saveError_ = std::make_shared<std::string>();
  // A snapshot: entities are copied, mesh data is shared and immutable.
  // Terrain tiles are shared, not copied: freeze them copy-on-write so the
  // worker writes this moment while the user keeps painting.
  auto snapshot = std::make_shared<scene::SceneState>(scene::snapshotForSave(doc_.state()));
  const std::string path = recoveryFile().toStdString();
  std::shared_ptr<std::string> error = saveError_;
  watcher_.setFuture(QtConcurrent::run([snapshot, path, error] {
    if (!scene::saveScene(*snapshot, path, *error) && error->empty()) *error = path + ": could not be written";
  }));
  if (wait) {
    watcher_.waitForFinished();
    onSaveFinished();
  }
  return true;
}

void Autosave::onSaveFinished() {
  if (!saving_) return;
  saving_ = false;
  if (!saveError_->empty()) {
    emit failed(QString::fromStdString(*saveError_));
    return;
  }
  savedRevision_ = savingRevision_;
  if (!doc_.isModified()) {
    // Saved by the user while this copy was being written.
    removeRecoveryCopy();
    return;
  }
  writeMarker();
  emit saved(recoveryFile());
}

void Autosave::removeRecoveryCopy() {
  QFile::remove(recoveryFile());
  savedRevision_ = 0;
  if (started_) writeMarker();
}

void Autosave::finishCleanly() {
  timer_.stop();
  if (saving_) {
    watcher_.waitForFinished();
    onSaveFinished();
  }
  QFile::remove(recoveryFile());
  QFile::remove(sessionFile());
  started_ = false;
}

std::vector<Autosave::Orphan> Autosave::findOrphans() const {
  std::vector<Orphan> out;
  const QDir dir(recoveryDirectory());
  for (const QFileInfo& fi : dir.entryInfoList({"*.session"}, QDir::Files)) {
    if (fi.absoluteFilePath() == QFileInfo(sessionFile()).absoluteFilePath()) continue;
    QFile f(fi.absoluteFilePath());
    if (!f.open(QIODevice::ReadOnly)) continue;
    const QJsonObject o = QJsonDocument::fromJson(f.readAll()).object();
    f.close();
    if (processAlive(qint64(o["pid"].toDouble()), o["start"].toString())) continue;  // another live editor
    Orphan orphan;
    orphan.sessionFile = fi.absoluteFilePath();
    orphan.recoveryFile = fi.absolutePath() + "/" + fi.completeBaseName() + ".hscene";
    orphan.documentPath = o["document"].toString();
    if (!QFileInfo::exists(orphan.recoveryFile)) {
      // Crashed with nothing unsaved: nothing to offer, just tidy up.
      QFile::remove(orphan.sessionFile);
      continue;
    }
    orphan.savedAt = QFileInfo(orphan.recoveryFile).lastModified();
    out.push_back(orphan);
  }
  std::sort(out.begin(), out.end(), [](const Orphan& a, const Orphan& b) { return a.savedAt > b.savedAt; });
  return out;
}

void Autosave::discard(const Orphan& orphan) {
  QFile::remove(orphan.recoveryFile);
  QFile::remove(orphan.sessionFile);
}

}  // namespace hs::app
