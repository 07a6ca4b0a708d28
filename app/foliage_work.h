#pragma once
// Foliage edits that can take seconds (a scatter or a fill over a valley, a
// reapply of a large selection) run on a worker thread, into a copy of the
// document's store, under a window-modal progress with Cancel, while the
// viewport keeps drawing the document's foliage. At the end the copy's
// touched cells go into the document as one undo step
// (scene::ops::commitFoliageWork, which refuses work whose cells the
// document changed meanwhile). A cancelled work changes nothing.
#include <functional>

#include <QString>

#include "scene/foliage_ops.h"

class QWidget;

namespace hs::app {

// The work on the copy; `progress` reports and may cancel.
using FoliageWorkFn = std::function<scene::ops::FoliageWork(foliage::FoliageStore& copy, const Progress& progress)>;

// `showAfterMs`: work that ends sooner shows no dialog (a small fill).
scene::ops::FoliageOutcome runFoliageWork(QWidget* dialogParent, scene::Document& doc, const QString& title,
                                          const QString& label, FoliageWorkFn work, int showAfterMs = 0);

}  // namespace hs::app
