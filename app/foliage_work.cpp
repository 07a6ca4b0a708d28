#include "app/foliage_work.h"

#include <memory>

#include "app/background_job.h"

namespace hs::app {

scene::ops::FoliageOutcome runFoliageWork(QWidget* dialogParent, scene::Document& doc, const QString& title,
                                          const QString& label, FoliageWorkFn work, int showAfterMs) {
  // The copy is the worker's alone; the document's store is only read
  // again on this thread, after the worker ended.
  auto copy = std::make_shared<foliage::FoliageStore>(doc.foliage().store());
  auto done = std::make_shared<scene::ops::FoliageWork>();
  BackgroundJob job(dialogParent, title, label, true, showAfterMs);
  job.start([copy, done, work = std::move(work)](const Progress& p) { *done = work(*copy, p); });
  job.waitForFinished();
  return scene::ops::commitFoliageWork(doc, *copy, std::move(*done));
}

}  // namespace hs::app
