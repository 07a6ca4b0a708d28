#pragma once
// Where the editor keeps its settings and recovery copies, and the GL format
// it asks for. HS_SETTINGS_SANDBOX redirects both to a temporary directory so
// tests never read or write the user's configuration.
#include <QString>

namespace hs::app {

// Must run before QApplication exists: QOpenGLWidget contexts take the
// default format, and the renderer needs 4.5 core (no MSAA on the widget:
// the renderer resolves its own).
void applyDefaultSurfaceFormat();

// Sets organisation/application names (QSettings keys) and applies the
// sandbox. Call once, after QApplication is constructed.
void initApplicationSettings();

bool settingsSandboxed();
// Folder for autosaved recovery copies (created on demand).
QString recoveryDirectory();

}  // namespace hs::app
