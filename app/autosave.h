#pragma once
// Autosave to a recovery copy and crash recovery.
//
// Each editor session writes, in recoveryDirectory(), a marker
// "<session>.session" (JSON: pid, process start time, the document's path)
// and, every few minutes while the document has unsaved changes, a recovery
// copy "<session>.hscene" (saveScene on a worker, from a snapshot of the
// state: meshes are shared, so the snapshot is cheap). A clean exit removes
// both. A marker whose process is gone therefore means a session that did
// not end cleanly, and its recovery copy is offered at the next start.
#include <vector>

#include <QDateTime>
#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <QTimer>

#include "scene/document.h"

namespace hs::app {

class Autosave : public QObject {
  Q_OBJECT
 public:
  struct Orphan {
    QString sessionFile;
    QString recoveryFile;
    QString documentPath;  // the file the crashed session was editing ("" if untitled)
    QDateTime savedAt;
  };

  static constexpr double kDefaultIntervalMinutes = 3.0;

  explicit Autosave(scene::Document& doc, QObject* parent = nullptr);
  ~Autosave() override;

  // Writes this session's marker and starts the timer (interval from
  // QSettings "autosave/intervalMinutes"; 0 turns autosave off).
  void start();
  int intervalMs() const { return timer_.interval(); }
  static double intervalMinutesSetting();
  static void setIntervalMinutesSetting(double minutes);

  // Writes the recovery copy now if there are unsaved changes it does not
  // hold yet. With `wait` it returns once written (the event loop keeps
  // turning). Returns whether a save was started (or done).
  bool saveNow(bool wait = false);
  bool saving() const { return saving_; }
  // A clean exit: removes this session's copy and marker.
  void finishCleanly();

  QString recoveryFile() const;
  QString sessionFile() const;

  // Recovery copies of sessions that are gone, newest first.
  std::vector<Orphan> findOrphans() const;
  static void discard(const Orphan& orphan);

 signals:
  void saved(const QString& recoveryFile);
  void failed(const QString& error);

 private:
  void writeMarker();
  void removeRecoveryCopy();
  void onSaveFinished();

  scene::Document& doc_;
  QString session_;
  QTimer timer_;
  QFutureWatcher<void> watcher_;
  quint64 revision_ = 0;       // bumps on every document change
  quint64 savedRevision_ = 0;  // what the recovery copy holds
  quint64 savingRevision_ = 0;
  bool saving_ = false;
  bool started_ = false;
  std::shared_ptr<std::string> saveError_;
};

}  // namespace hs::app
