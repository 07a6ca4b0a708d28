#pragma once
// File > Open Recent: the last scenes opened or saved, kept in QSettings.
#include <QStringList>

namespace hs::app {

class RecentFiles {
 public:
  static constexpr int kMax = 10;
  static QStringList list();
  static void add(const QString& path);  // moves it to the top
  static void remove(const QString& path);
  static void clear();
};

}  // namespace hs::app
