// hybridscape: the editor. With no file it opens the built-in demo as an
// untitled document; with a file, that file. --screenshot FILE renders the
// window once everything is shown, writes a PNG and exits (for the docs).
#include <QApplication>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QScreen>
#include <QTimer>

#include <cstdio>

#include "app/app_settings.h"
#include "app/main_window.h"
#include "app/prompts.h"
#include "app/theme.h"
#include "app/viewport_widget.h"

int main(int argc, char** argv) {
  // Before QApplication: every QOpenGLWidget context takes this format.
  hs::app::applyDefaultSurfaceFormat();
  QApplication app(argc, argv);
  QCoreApplication::setApplicationName("hybridscape");
  QCoreApplication::setApplicationVersion("0.1.0");
  hs::app::initApplicationSettings();
  hs::app::applyDarkTheme(app);

  QCommandLineParser parser;
  parser.setApplicationDescription("Hybridscape editor: large outdoor scenes for stereo films.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument("scene", "A .hscene file to open (default: the built-in demo).", "[scene]");
  QCommandLineOption screenshot("screenshot", "Write a PNG of the window once it is shown, then exit.", "FILE");
  QCommandLineOption select("select", "Select the entity with this name after loading.", "NAME");
  parser.addOption(screenshot);
  parser.addOption(select);
  parser.process(app);

  hs::app::MainWindow window;
  if (parser.isSet(screenshot)) {
    window.setPrompts(std::make_unique<hs::app::ConsolePrompts>());
    // The documentation image shows the window filling the (virtual) screen.
    if (const QScreen* screen = QGuiApplication::primaryScreen()) window.setGeometry(screen->availableGeometry());
  }
  window.show();
  const QStringList files = parser.positionalArguments();
  if (!files.isEmpty()) {
    // Something usable stays open if the file turns out to be unreadable.
    window.newScene();
    window.openSceneFile(files.first(), false);
  }
  else
    window.loadDemoScene();

  const QString selectName = parser.value(select);
  if (!parser.isSet(screenshot)) {
    if (!selectName.isEmpty()) QTimer::singleShot(0, &window, [&] { window.selectByName(selectName); });
    // After the window is up, so the question has something to sit on.
    QTimer::singleShot(0, &window, [&] { window.offerRecovery(); });
    return app.exec();
  }

  // Screenshot: wait until loading is done and the viewport has drawn a few
  // frames (the GPU timer needs two to report), then grab and quit.
  const QString out = parser.value(screenshot);
  QElapsedTimer clock;
  clock.start();
  bool selected = selectName.isEmpty();
  auto* poll = new QTimer(&window);
  QObject::connect(poll, &QTimer::timeout, &window, [&] {
    hs::app::ViewportWidget* vp = window.viewport();
    if (!window.isBusy() && !selected) selected = window.selectByName(selectName) || true;
    const bool ready = !window.isBusy() && (vp->framesRendered() >= 4 || !vp->rendererError().isEmpty());
    if (!ready && clock.elapsed() < 60000) {
      vp->update();
      return;
    }
    poll->stop();
    const bool ok = window.writeScreenshot(out);
    std::fprintf(ok ? stdout : stderr, ok ? "wrote %s\n" : "could not write %s\n", qPrintable(out));
    // Leave the user's document state alone: no save question in this mode.
    window.document().markSaved();
    QCoreApplication::exit(ok ? 0 : 1);
  });
  poll->start(150);
  return app.exec();
}
