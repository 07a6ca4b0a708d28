#pragma once
// Small widget factories the editor's panels share, so every number field
// behaves the same (no edit per keystroke: a typed value is one undo step
// when it is committed).
#include <QString>

class QDoubleSpinBox;
class QToolButton;
class QWidget;

namespace hs::app {

// A number field that reports only committed values (keyboard tracking off).
QDoubleSpinBox* numberSpin(QWidget* parent, double min, double max, double step, int decimals, const QString& suffix,
                           const QString& tip);

// Fills `panel` with a frameless scroll area holding `content` (a dock's
// panel scrolls when the dock is shorter than it). Without
// `horizontalScroll` the content is squeezed to the dock's width instead.
void putInScrollArea(QWidget* panel, QWidget* content, bool horizontalScroll = false);

// A row holding `editor` (stretched) in a tight horizontal layout, where a
// key button can be added after it (the Properties, Materials and Scene
// Settings panels' animatable fields).
QWidget* editorRow(QWidget* parent, QWidget* editor);

// A text tool button with an object name (tests find it by name) and a tip.
QToolButton* namedToolButton(QWidget* parent, const QString& text, const char* name, const QString& tip);

}  // namespace hs::app
