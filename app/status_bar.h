#pragma once
// The permanent part of the status bar: frame time (CPU and GPU), triangles
// drawn, memory (process RSS plus the renderer's GPU allocations) and the
// fly speed.
#include <QWidget>

#include "render/renderer.h"

class QLabel;

namespace hs::app {

class StatusBarInfo : public QWidget {
  Q_OBJECT
 public:
  explicit StatusBarInfo(QWidget* parent = nullptr);

  void setFrameStats(const render::FrameStats& stats);
  void setFlySpeed(double metresPerSecond);
  // Re-reads the process RSS (cheap: one small /proc read).
  void refreshMemory();

  // Resident set size of this process in bytes (0 if unknown).
  static size_t processRssBytes();

 private:
  QLabel* frame_;
  QLabel* triangles_;
  QLabel* memory_;
  QLabel* speed_;
  size_t gpuBytes_ = 0;
};

QString formatBytes(size_t bytes);

}  // namespace hs::app
