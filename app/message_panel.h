#pragma once
// The Messages dock: what the editor has to say that is not worth a dialog
// (import warnings, autosaves, GL information) and every error, newest last,
// with a time stamp, a per-level filter and Clear.
#include <QWidget>

class QTreeWidget;
class QToolButton;

namespace hs::app {

enum class MessageLevel { Info = 0, Warning = 1, Error = 2 };

class MessagePanel : public QWidget {
  Q_OBJECT
 public:
  explicit MessagePanel(QWidget* parent = nullptr);

  void add(MessageLevel level, const QString& text);
  void info(const QString& text) { add(MessageLevel::Info, text); }
  void warning(const QString& text) { add(MessageLevel::Warning, text); }
  void error(const QString& text) { add(MessageLevel::Error, text); }
  void clear();

  int count(MessageLevel level) const { return counts_[int(level)]; }
  int total() const { return counts_[0] + counts_[1] + counts_[2]; }
  // Text of the n-th message (0 = oldest), for tests and copy.
  QString text(int n) const;
  QString lastText() const { return total() ? text(total() - 1) : QString(); }

 signals:
  void countsChanged();

 private:
  void applyFilter();

  QTreeWidget* list_ = nullptr;
  QToolButton* filters_[3] = {};
  int counts_[3] = {0, 0, 0};
};

}  // namespace hs::app
