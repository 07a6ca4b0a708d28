#include "app/app_settings.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <QSettings>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>

#include "render/gl/gl_debug.h"

namespace hs::app {
namespace {

QTemporaryDir* sandboxDir() {
  // Lives until the process ends; removed with it.
  static QTemporaryDir* dir = nullptr;
  if (!dir && qEnvironmentVariableIsSet("HS_SETTINGS_SANDBOX")) {
    dir = new QTemporaryDir(QDir::tempPath() + "/hybridscape-sandbox-XXXXXX");
    dir->setAutoRemove(true);
    qAddPostRoutine([] {
      delete dir;
      dir = nullptr;
    });
  }
  return dir;
}

}  // namespace

void applyDefaultSurfaceFormat() {
  QSurfaceFormat f;
  f.setRenderableType(QSurfaceFormat::OpenGL);
  f.setVersion(4, 5);
  f.setProfile(QSurfaceFormat::CoreProfile);
  f.setDepthBufferSize(24);
  f.setStencilBufferSize(8);
  f.setSamples(0);
  if (render::gl::debugOutputRequested()) f.setOption(QSurfaceFormat::DebugContext);  // Messages gets GL's reports
  QSurfaceFormat::setDefaultFormat(f);
}

void initApplicationSettings() {
  QCoreApplication::setOrganizationName("Hybridscape");
  QCoreApplication::setOrganizationDomain("hybridscape.org");
  if (QCoreApplication::applicationName().isEmpty() ||
      QCoreApplication::applicationName() == QFileInfo(QCoreApplication::applicationFilePath()).fileName())
    QCoreApplication::setApplicationName("hybridscape");
  if (QTemporaryDir* dir = sandboxDir()) {
    // NativeFormat is IniFormat on Unix; set both so no code path escapes.
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, dir->path() + "/config");
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, dir->path() + "/config");
  }
}

bool settingsSandboxed() { return sandboxDir() != nullptr; }

QString recoveryDirectory() {
  QString dir;
  if (QTemporaryDir* sandbox = sandboxDir())
    dir = sandbox->path() + "/recovery";
  else
    dir = QStandardPaths::writableLocation(QStandardPaths::AppLocalDataLocation) + "/recovery";
  QDir().mkpath(dir);
  return dir;
}

}  // namespace hs::app
