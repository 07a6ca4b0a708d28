#pragma once
// Every question or error the editor puts to the user goes through Prompts,
// so a test can answer them (RecordingPrompts-style) instead of a modal
// dialog waiting for a click that never comes.
#include <QString>
#include <QStringList>

class QWidget;

namespace hs::app {

class Prompts {
 public:
  enum class SaveChoice { Save, Discard, Cancel };
  virtual ~Prompts() = default;

  virtual SaveChoice askSaveChanges(QWidget* parent, const QString& documentName) = 0;
  virtual void showError(QWidget* parent, const QString& title, const QString& text) = 0;
  virtual bool askYesNo(QWidget* parent, const QString& title, const QString& text,
                        const QString& yesText, const QString& noText) = 0;
  // Empty string: cancelled.
  virtual QString askOpenFile(QWidget* parent, const QString& caption, const QString& dir,
                              const QString& filter) = 0;
  virtual QString askSaveFile(QWidget* parent, const QString& caption, const QString& dir,
                              const QString& filter) = 0;
  // Several files at once (the tiles of a scan); empty: cancelled. By
  // default one file through askOpenFile, so answering prompts stay simple.
  virtual QStringList askOpenFiles(QWidget* parent, const QString& caption, const QString& dir,
                                   const QString& filter) {
    const QString f = askOpenFile(parent, caption, dir, filter);
    return f.isEmpty() ? QStringList() : QStringList{f};
  }
};

// The real dialogs.
class DialogPrompts : public Prompts {
 public:
  SaveChoice askSaveChanges(QWidget* parent, const QString& documentName) override;
  void showError(QWidget* parent, const QString& title, const QString& text) override;
  bool askYesNo(QWidget* parent, const QString& title, const QString& text, const QString& yesText,
                const QString& noText) override;
  QString askOpenFile(QWidget* parent, const QString& caption, const QString& dir, const QString& filter) override;
  QString askSaveFile(QWidget* parent, const QString& caption, const QString& dir, const QString& filter) override;
  QStringList askOpenFiles(QWidget* parent, const QString& caption, const QString& dir, const QString& filter) override;
};

// For unattended runs (--screenshot): errors go to stderr, questions get
// the answer that changes nothing, so nothing ever waits for a click.
class ConsolePrompts : public Prompts {
 public:
  SaveChoice askSaveChanges(QWidget*, const QString&) override { return SaveChoice::Cancel; }
  void showError(QWidget* parent, const QString& title, const QString& text) override;
  bool askYesNo(QWidget*, const QString&, const QString&, const QString&, const QString&) override { return false; }
  QString askOpenFile(QWidget*, const QString&, const QString&, const QString&) override { return {}; }
  QString askSaveFile(QWidget*, const QString&, const QString&, const QString&) override { return {}; }
};

}  // namespace hs::app
