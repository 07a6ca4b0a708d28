#include "app/theme.h"

#include <QApplication>
#include <QPalette>
#include <QStyleFactory>

namespace hs::app {

void applyDarkTheme(QApplication& app) {
  app.setStyle(QStyleFactory::create("Fusion"));
  QPalette p;
  const QColor window(45, 46, 48), base(32, 33, 35), text(220, 221, 224), disabled(120, 121, 124);
  const QColor accent(64, 128, 206);
  p.setColor(QPalette::Window, window);
  p.setColor(QPalette::WindowText, text);
  p.setColor(QPalette::Base, base);
  p.setColor(QPalette::AlternateBase, QColor(38, 39, 41));
  p.setColor(QPalette::ToolTipBase, QColor(60, 61, 64));
  p.setColor(QPalette::ToolTipText, text);
  p.setColor(QPalette::PlaceholderText, disabled);
  p.setColor(QPalette::Text, text);
  p.setColor(QPalette::Button, QColor(56, 57, 60));
  p.setColor(QPalette::ButtonText, text);
  p.setColor(QPalette::BrightText, QColor(255, 90, 90));
  p.setColor(QPalette::Light, QColor(75, 76, 80));
  p.setColor(QPalette::Midlight, QColor(62, 63, 66));
  p.setColor(QPalette::Mid, QColor(40, 41, 43));
  p.setColor(QPalette::Dark, QColor(25, 26, 27));
  p.setColor(QPalette::Shadow, QColor(15, 15, 16));
  p.setColor(QPalette::Highlight, accent);
  p.setColor(QPalette::HighlightedText, Qt::white);
  p.setColor(QPalette::Link, accent.lighter(130));
  for (auto role : {QPalette::WindowText, QPalette::Text, QPalette::ButtonText})
    p.setColor(QPalette::Disabled, role, disabled);
  p.setColor(QPalette::Disabled, QPalette::Highlight, QColor(70, 71, 74));
  app.setPalette(p);
  app.setStyleSheet(
      "QDockWidget::title { background: #333437; padding: 4px 6px; }"
      "QToolTip { border: 1px solid #56575b; }"
      "QToolBar { spacing: 2px; border: none; }"
      "QStatusBar QLabel { padding: 0 6px; color: #b8b9bc; }");
}

}  // namespace hs::app
