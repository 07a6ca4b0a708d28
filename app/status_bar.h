#pragma once
// The permanent part of the status bar: frame time (CPU and GPU), triangles
// drawn, memory (process RSS plus the renderer's GPU allocations) and the
// fly speed. Hovering the frame time lists the passes that ran, each with
// its CPU time, its GPU time (from the last frame that measured them) and
// the GPU memory of the resources it created.
#include <map>
#include <string>

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
  QLabel* clusters_;
  QLabel* speed_;
  size_t gpuBytes_ = 0;
  std::map<std::string, double> passGpuMs_;  // last measured, by pass name
};

// The per-pass table shown when hovering the frame time (rich text).
QString passTableHtml(const render::FrameStats& stats, const std::map<std::string, double>& gpuMsByPass);

QString formatBytes(size_t bytes);

// The status bar's line on huge scans' streaming (render/cluster_source.h):
// clusters drawn, pages resident and their memory, then what is still
// arriving, or that the budget is full.
QString clusterStreamingText(const render::ClusterStats& stats);

// One sentence on the frame's transparency: the mode, the OIT buffers'
// memory, layers, fragments per pixel and what overflowed (or that no
// translucent surface was in view). Shared by the frame tooltip and the
// Scene Settings dock, so the two cannot disagree.
QString oitSummary(const render::OitStats& stats);

}  // namespace hs::app
