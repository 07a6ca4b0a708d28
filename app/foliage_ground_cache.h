#pragma once
// The document's foliage ground (scene/foliage_ground.h: the terrain the
// foliage tools place on and every visible mesh, each with a BVH), built
// when first asked for and kept until entities, assets or terrains change.
// Building it costs what the meshes cost (a scan of millions of triangles:
// seconds), so the Foliage panel's scatter and the brush's dabs and hover
// picks share one instead of building their own.
#include <memory>

#include <QObject>

#include "scene/document.h"
#include "scene/foliage_ground.h"

namespace hs::app {

class FoliageGroundCache : public QObject {
  Q_OBJECT
 public:
  explicit FoliageGroundCache(scene::Document& doc, QObject* parent = nullptr);
  ~FoliageGroundCache() override;

  // The ground of the document as it is now (built here when stale, with
  // a busy cursor: on the UI thread, as the tools that use it are).
  const scene::FoliageGround& ground();
  // The same, for a worker: it stays alive while the worker holds it,
  // whatever the document does meanwhile.
  std::shared_ptr<const scene::FoliageGround> shared();
  bool built() const { return bool(ground_); }
  int builds() const { return builds_; }  // how many times it was built (tests)

 private:
  scene::Document& doc_;
  std::shared_ptr<const scene::FoliageGround> ground_;
  int builds_ = 0;
};

}  // namespace hs::app
