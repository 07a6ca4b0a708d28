#pragma once
// What the key-list widgets share (app/life_curve_editor.h over a
// particle's life, app/time_keys_editor.h over scene time): the plot's
// background and the value a list of keys gives between and outside them.
#include <vector>

#include <QRectF>

class QKeyEvent;
class QPainter;
class QWidget;

namespace hs::app {

// The widget's base colour, four vertical grid lines (five edges) and the
// plot's bottom edge.
void paintPlotBackground(QPainter& p, const QWidget& w, const QRectF& plot);

// The row a key list gives at x (rows sorted by their first number; no
// rows: {x}): the first row held before it, the last after it, linear between;
// the returned row's first number is x. The emitter's curves evaluate so.
std::vector<double> rowAt(const std::vector<std::vector<double>>& rows, double x);

// Delete or Backspace: what removes the selected key.
bool isDeleteKey(const QKeyEvent* e);

}  // namespace hs::app
