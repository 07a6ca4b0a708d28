#pragma once
// The editor's look: Fusion with a dark palette, as DCC users expect (a
// bright UI around a dark viewport makes judging exposure harder).
class QApplication;

namespace hs::app {

void applyDarkTheme(QApplication& app);

}  // namespace hs::app
