#include "app/status_bar.h"

#include <unistd.h>

#include <QFile>
#include <QHBoxLayout>
#include <QLabel>

namespace hs::app {

QString formatBytes(size_t bytes) {
  const double b = double(bytes);
  if (b >= 1024.0 * 1024.0 * 1024.0) return QString("%1 GB").arg(b / (1024.0 * 1024.0 * 1024.0), 0, 'f', 2);
  if (b >= 1024.0 * 1024.0) return QString("%1 MB").arg(b / (1024.0 * 1024.0), 0, 'f', 0);
  return QString("%1 KB").arg(b / 1024.0, 0, 'f', 0);
}

StatusBarInfo::StatusBarInfo(QWidget* parent) : QWidget(parent) {
  auto* l = new QHBoxLayout(this);
  l->setContentsMargins(0, 0, 0, 0);
  l->setSpacing(0);
  speed_ = new QLabel(this);
  frame_ = new QLabel("Frame: –", this);
  triangles_ = new QLabel("Triangles: –", this);
  memory_ = new QLabel("Memory: –", this);
  speed_->setToolTip("Fly speed (mouse wheel while holding the right button)");
  frame_->setToolTip("Time of the last frame on the CPU and on the GPU (from a timer query)");
  triangles_->setToolTip("Triangles drawn in the last frame");
  memory_->setToolTip("Process memory (resident set) and GPU memory held by the renderer");
  for (QLabel* label : {speed_, frame_, triangles_, memory_}) {
    label->setObjectName(label == frame_ ? "statusFrame" : label == triangles_ ? "statusTriangles"
                                                    : label == memory_       ? "statusMemory"
                                                                             : "statusSpeed");
    l->addWidget(label);
  }
  refreshMemory();
}

void StatusBarInfo::setFrameStats(const render::FrameStats& s) {
  const QString gpu = s.gpuMs >= 0.0 ? QString("%1 ms").arg(s.gpuMs, 0, 'f', 1) : QString("–");
  frame_->setText(QString("CPU %1 ms · GPU %2").arg(s.cpuMs, 0, 'f', 1).arg(gpu));
  triangles_->setText(QString("%L1 triangles").arg(s.trianglesDrawn));
  gpuBytes_ = s.gpuBytes;
  refreshMemory();
}

void StatusBarInfo::setFlySpeed(double v) { speed_->setText(QString("Fly %1 m/s").arg(v, 0, 'g', 3)); }

void StatusBarInfo::refreshMemory() {
  memory_->setText(QString("RAM %1 · GPU %2").arg(formatBytes(processRssBytes()), formatBytes(gpuBytes_)));
}

size_t StatusBarInfo::processRssBytes() {
  // /proc/self/statm: size resident shared text lib data dt, in pages.
  QFile f("/proc/self/statm");
  if (!f.open(QIODevice::ReadOnly)) return 0;
  const QList<QByteArray> fields = f.readAll().split(' ');
  if (fields.size() < 2) return 0;
  return size_t(fields[1].toULongLong()) * size_t(sysconf(_SC_PAGESIZE));
}

}  // namespace hs::app
