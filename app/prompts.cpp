#include "app/prompts.h"

#include <cstdio>

#include <QFileDialog>
#include <QMessageBox>
#include <QPushButton>

namespace hs::app {

Prompts::SaveChoice DialogPrompts::askSaveChanges(QWidget* parent, const QString& documentName) {
  QMessageBox box(parent);
  box.setIcon(QMessageBox::Warning);
  box.setWindowTitle("Unsaved changes");
  box.setText(QString("Save the changes to \"%1\"?").arg(documentName));
  box.setInformativeText("Your changes will be lost if you don't save them.");
  box.setStandardButtons(QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
  box.setDefaultButton(QMessageBox::Save);
  switch (box.exec()) {
    case QMessageBox::Save: return SaveChoice::Save;
    case QMessageBox::Discard: return SaveChoice::Discard;
    default: return SaveChoice::Cancel;
  }
}

void DialogPrompts::showError(QWidget* parent, const QString& title, const QString& text) {
  QMessageBox box(parent);
  box.setIcon(QMessageBox::Critical);
  box.setWindowTitle(title);
  // The first line is the summary; details (file, line, reason) follow.
  const qsizetype nl = text.indexOf('\n');
  box.setText(nl < 0 ? text : text.left(nl));
  if (nl >= 0) box.setInformativeText(text.mid(nl + 1).trimmed());
  box.setTextInteractionFlags(Qt::TextSelectableByMouse);
  box.exec();
}

bool DialogPrompts::askYesNo(QWidget* parent, const QString& title, const QString& text, const QString& yesText,
                             const QString& noText) {
  QMessageBox box(parent);
  box.setIcon(QMessageBox::Question);
  box.setWindowTitle(title);
  box.setText(text);
  QPushButton* yes = box.addButton(yesText, QMessageBox::AcceptRole);
  box.addButton(noText, QMessageBox::RejectRole);
  box.setDefaultButton(yes);
  box.exec();
  return box.clickedButton() == yes;
}

QString DialogPrompts::askOpenFile(QWidget* parent, const QString& caption, const QString& dir,
                                   const QString& filter) {
  return QFileDialog::getOpenFileName(parent, caption, dir, filter);
}

QStringList DialogPrompts::askOpenFiles(QWidget* parent, const QString& caption, const QString& dir,
                                        const QString& filter) {
  return QFileDialog::getOpenFileNames(parent, caption, dir, filter);
}

QString DialogPrompts::askSaveFile(QWidget* parent, const QString& caption, const QString& dir,
                                   const QString& filter) {
  QFileDialog dialog(parent, caption, dir, filter);
  dialog.setAcceptMode(QFileDialog::AcceptSave);
  dialog.setDefaultSuffix("hscene");
  if (dialog.exec() != QDialog::Accepted || dialog.selectedFiles().isEmpty()) return {};
  return dialog.selectedFiles().first();
}

void ConsolePrompts::showError(QWidget*, const QString& title, const QString& text) {
  std::fprintf(stderr, "%s: %s\n", qPrintable(title), qPrintable(QString(text).replace('\n', ' ')));
}

}  // namespace hs::app
