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
  triangles_->setToolTip("Triangles drawn in the last frame");
  memory_->setToolTip("Process memory (resident set) and GPU memory held by the renderer");
  for (QLabel* label : {speed_, frame_, triangles_, memory_}) {
    label->setObjectName(label == frame_ ? "statusFrame" : label == triangles_ ? "statusTriangles"
                                                    : label == memory_       ? "statusMemory"
                                                                             : "statusSpeed");
    l->addWidget(label);
  }
  // Huge scans' streaming state, only while a frame draws one.
  clusters_ = new QLabel(this);
  clusters_->setObjectName("statusClusters");
  clusters_->setVisible(false);
  l->insertWidget(2, clusters_);
  refreshMemory();
}

QString clusterStreamingText(const render::ClusterStats& c) {
  QString t = QString("%L1 clusters · %2 pages · %3")
                  .arg(c.clusters)
                  .arg(c.pagesResident)
                  .arg(formatBytes(c.gpuBytes));
  if (c.pagesLoading > 0) t += QString(" · streaming %1 pages").arg(c.pagesLoading);
  else if (c.budgetFull) t += " · GPU budget full";
  else if (!c.complete) t += " · coarser where pages failed";
  return t;
}

QString passTableHtml(const render::FrameStats& stats, const std::map<std::string, double>& gpuMsByPass) {
  QString html = "<table><tr><th align=left>pass</th><th align=right>CPU ms</th><th align=right>GPU ms</th>"
                 "<th align=right>GPU memory</th></tr>";
  size_t bytes = 0;
  for (const render::PassStats& p : stats.passes) {
    const auto g = gpuMsByPass.find(p.name);
    const QString gpu = g != gpuMsByPass.end() ? QString::number(g->second, 'f', 2) : QString("–");
    html += QString("<tr><td>%1</td><td align=right>%2</td><td align=right>%3</td><td align=right>%4</td></tr>")
                .arg(QString::fromStdString(p.name).toHtmlEscaped())
                .arg(p.cpuMs, 0, 'f', 2)
                .arg(gpu)
                .arg(p.gpuBytes ? formatBytes(p.gpuBytes) : QString("–"));
    bytes += p.gpuBytes;
  }
  html += QString("</table><p>%1 passes ran, %2 draw calls, %3 in their transient resources; %4 held in all "
                  "(meshes, terrains, pooled targets). GPU times are measured every few frames.</p>")
              .arg(stats.passes.size())
              .arg(stats.drawCalls)
              .arg(formatBytes(bytes))
              .arg(formatBytes(stats.gpuBytes));
  // The clustered light list (render/passes/light_culling.h).
  if (stats.lightsInView > 0) {
    html += QString("<p>%1 point/spot lights in view").arg(stats.lightsInView);
    if (stats.lightClustersOverCap > 0)
      html += QString("; %1 light clusters over the cap of 128 (up to %2 lights)")
                  .arg(stats.lightClustersOverCap)
                  .arg(stats.lightsMaxPerCluster);
    html += ".</p>";
  }
  // Transparency (render/oit.h): only frames with a translucent surface in view.
  if (stats.oit.active) html += "<p>Transparency " + oitSummary(stats.oit).toHtmlEscaped() + "</p>";
  return html;
}

QString oitSummary(const render::OitStats& o) {
  if (!o.active) return "No translucent surface in view: no OIT buffers.";
  QString s = QString("%1: %2 of OIT buffers").arg(QString::fromStdString(o.mode)).arg(formatBytes(o.bytes));
  if (o.layers > 0) s += QString(", %1 layers per pixel").arg(o.layers);
  if (o.counted)
    s += QString("; fragments per pixel: max %1, mean %2").arg(o.maxPerPixel).arg(o.meanPerPixel, 0, 'f', 2);
  else
    s += "; fragments per pixel not counted in this frame";
  if (o.overflow > 0)
    s += QString("; %L1 fragments over capacity, tail-blended (%2% of their pixels)")
             .arg(qulonglong(o.overflow))
             .arg(o.tailShare * 100.0, 0, 'f', 1);
  else
    s += "; no overflow";
  return s + ".";
}

void StatusBarInfo::setFrameStats(const render::FrameStats& s) {
  for (const render::PassStats& p : s.passes)
    if (p.gpuMs >= 0.0) passGpuMs_[p.name] = p.gpuMs;
  frame_->setToolTip(passTableHtml(s, passGpuMs_));
  const QString gpu = s.gpuMs >= 0.0 ? QString("%1 ms").arg(s.gpuMs, 0, 'f', 1) : QString("–");
  frame_->setText(QString("CPU %1 ms · GPU %2").arg(s.cpuMs, 0, 'f', 1).arg(gpu));
  triangles_->setText(QString("%L1 triangles").arg(s.trianglesDrawn));
  const render::ClusterStats& c = s.clusters;
  clusters_->setVisible(c.instances > 0 || c.pagesWanted > 0);
  clusters_->setText(clusterStreamingText(c));
  clusters_->setToolTip(QString("Huge scans drawn from their cluster hierarchies: %L1 clusters, %L2 triangles in the "
                                "cut; %3 pages resident on the GPU (%4 of the budget's pool), %5 drawn; CPU page "
                                "cache %6; cut and uploads %7 ms%8")
                            .arg(c.clusters)
                            .arg(c.triangles)
                            .arg(c.pagesResident)
                            .arg(formatBytes(c.gpuBytes))
                            .arg(c.pagesDrawn)
                            .arg(formatBytes(c.cpuBytes))
                            .arg(c.cutMs, 0, 'f', 2)
                            .arg(c.budgetFull ? "; the GPU budget holds no more than this frame draws "
                                                "(Scene Settings: cluster GPU budget)"
                                              : ""));
  gpuBytes_ = s.gpuBytes + c.gpuBytes;
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
