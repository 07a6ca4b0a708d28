#include "app/recent_files.h"

#include <QFileInfo>
#include <QSettings>

namespace hs::app {
namespace {
const char* kKey = "recentFiles";
}

QStringList RecentFiles::list() { return QSettings().value(kKey).toStringList(); }

void RecentFiles::add(const QString& path) {
  const QString abs = QFileInfo(path).absoluteFilePath();
  QStringList l = list();
  l.removeAll(abs);
  l.prepend(abs);
  while (l.size() > kMax) l.removeLast();
  QSettings().setValue(kKey, l);
}

void RecentFiles::remove(const QString& path) {
  QStringList l = list();
  l.removeAll(QFileInfo(path).absoluteFilePath());
  QSettings().setValue(kKey, l);
}

void RecentFiles::clear() { QSettings().remove(kKey); }

}  // namespace hs::app
