#pragma once
// What the editor suites set up the same way: the start before QApplication
// exists, prompts that answer the editor's questions without a dialog, and
// waiting for the viewport to draw.
// Each suite still makes its own window (size, first scene, what it waits
// for), since those differ from suite to suite.
#include <QString>
#include <QStringList>
#include <QTest>
#include <QtGlobal>

#include <memory>

#include "app/app_settings.h"
#include "app/main_window.h"
#include "app/prompts.h"
#include "app/viewport_widget.h"

namespace hs::test {

// A suite's initMain() (QTEST_MAIN calls it before QApplication exists):
// settings go to a sandbox, never the user's, even when run by hand; and
// the GL surface format is the editor's.
inline void initEditorMain() {
  qputenv("HS_SETTINGS_SANDBOX", "1");
  app::applyDefaultSurfaceFormat();
}

// Answers so that nothing waits for a click: Discard unsaved changes, No to
// every question, `openAnswer` when a file to open is asked for (empty:
// cancelled), no file to save to. An error is kept in `errors` ("title:
// text"), or with Errors::Warn printed as a warning instead.
class QuietPrompts : public app::Prompts {
 public:
  enum class Errors { Keep, Warn };
  explicit QuietPrompts(Errors errorsGo = Errors::Keep) : errorsGo_(errorsGo) {}

  QString openAnswer;
  QStringList errors;

  SaveChoice askSaveChanges(QWidget*, const QString&) override { return SaveChoice::Discard; }
  void showError(QWidget*, const QString& title, const QString& text) override {
    if (errorsGo_ == Errors::Warn)
      qWarning("error dialog: %s: %s", qPrintable(title), qPrintable(text));
    else
      errors << title + ": " + text;
  }
  bool askYesNo(QWidget*, const QString&, const QString&, const QString&, const QString&) override { return false; }
  QString askOpenFile(QWidget*, const QString&, const QString&, const QString&) override { return openAnswer; }
  QString askSaveFile(QWidget*, const QString&, const QString&, const QString&) override { return {}; }

 private:
  Errors errorsGo_;
};

// Gives `w` a QuietPrompts (the window owns it) and returns it, for a suite
// that sets its answers or reads its errors.
inline QuietPrompts* setQuietPrompts(app::MainWindow& w, QuietPrompts::Errors errorsGo = QuietPrompts::Errors::Keep) {
  auto prompts = std::make_unique<QuietPrompts>(errorsGo);
  QuietPrompts* p = prompts.get();
  w.setPrompts(std::move(prompts));
  return p;
}

// Asks the viewport for a new frame and waits (20 s at most) until it has
// drawn it; fails the test if it does not.
inline void waitForNextFrame(app::ViewportWidget& vp) {
  const int before = vp.framesRendered();
  vp.update();
  QTRY_VERIFY_WITH_TIMEOUT(vp.framesRendered() > before, 20000);
}

}  // namespace hs::test
