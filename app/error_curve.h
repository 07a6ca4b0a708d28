#pragma once
// The preview's curve: Hausdorff error (as a share of the bounding-box
// diagonal) against triangle count, both on log scales, one dot per
// previewed target and the chosen target ringed. Drawn with QPainter (the
// editor has no chart library).
#include <vector>

#include <QWidget>

#include "app/import_preview.h"

namespace hs::app {

class ErrorCurve : public QWidget {
  Q_OBJECT
 public:
  explicit ErrorCurve(QWidget* parent = nullptr);
  void setPoints(std::vector<PreviewPoint> points, size_t trianglesIn);
  const std::vector<PreviewPoint>& points() const { return points_; }
  QSize sizeHint() const override { return {360, 200}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  std::vector<PreviewPoint> points_;
  size_t trianglesIn_ = 0;
};

}  // namespace hs::app
