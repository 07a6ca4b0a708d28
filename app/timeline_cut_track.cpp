#include "app/timeline_cut_track.h"

#include <QContextMenuEvent>
#include <QMenu>
#include <QMouseEvent>
#include <QPainter>

#include "app/selection.h"
#include "app/timeline_clock.h"
#include "app/timeline_dope_sheet.h"
#include "scene/camera_cut_ops.h"
#include "scene/sequence_edits.h"

namespace hs::app {

namespace {
constexpr double kEdgePx = 5.0;  // how near an end a press trims instead of moving
constexpr const char* kUsage =
    "Camera cuts: drag a cut to move it, its ends to trim it, a transition's end to lengthen it; "
    "right-click to add a cut for the selected camera, set a transition or its ease, or remove";
}

TimelineCutTrack::TimelineCutTrack(scene::Document& doc, TimeWindow& window, TimelineClock& clock,
                                   Selection& selection, QWidget* parent)
    : QWidget(parent), doc_(doc), window_(window), clock_(clock), selection_(selection) {
  setObjectName("timelineCutTrack");
  setFixedHeight(kHeight);
  setMouseTracking(true);
  setToolTip(kUsage);
  connect(&window_, &TimeWindow::changed, this, qOverload<>(&QWidget::update));
  connect(&clock_, &TimelineClock::frameChanged, this, qOverload<>(&QWidget::update));
  connect(&doc_, &scene::Document::changed, this, qOverload<>(&QWidget::update));
}

TimeAxis TimelineCutTrack::axis() const {
  // The dope sheet's axis: the same names column, the same window.
  return TimeAxis{window_.start(), window_.end(), TimelineDopeSheet::kNamesWidth,
                  std::max(1, width() - TimelineDopeSheet::kNamesWidth)};
}

QRectF TimelineCutTrack::cutRect(size_t i) const {
  const auto& cuts = doc_.state().sequence.cuts;
  if (i >= cuts.size()) return {};
  const sequencer::FrameRate rate = doc_.state().sequence.rate;
  const TimeAxis ax = axis();
  // A cut covers its frames whole: from its first frame to the frame after its last.
  const double x0 = ax.x(sequencer::frameTime(cuts[i].start, rate));
  const double x1 = ax.x(sequencer::frameTime(cuts[i].end + 1, rate));
  return QRectF(x0, 3.0, std::max(2.0, x1 - x0), kHeight - 6.0);
}

void TimelineCutTrack::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), QColor(36, 37, 40));
  p.fillRect(QRect(0, 0, TimelineDopeSheet::kNamesWidth, height()), QColor(56, 57, 61));
  p.setPen(QColor(205, 206, 210));
  QFont bold = p.font();
  bold.setBold(true);
  bold.setPointSize(9);
  p.setFont(bold);
  p.drawText(QRect(8, 0, TimelineDopeSheet::kNamesWidth - 12, height()), Qt::AlignVCenter, "Camera cuts");
  p.setClipRect(QRect(TimelineDopeSheet::kNamesWidth, 0, width(), height()));
  const scene::SceneState& s = doc_.state();
  const std::string problem = scene::cutsProblem(s);
  const sequencer::FrameRate rate = s.sequence.rate;
  QFont font = p.font();
  font.setBold(false);
  p.setFont(font);
  for (size_t i = 0; i < s.sequence.cuts.size(); ++i) {
    const sequencer::CameraCut& c = s.sequence.cuts[i];
    const QRectF r = cutRect(i);
    const scene::Entity* cam = s.find(scene::EntityId(c.camera));
    const bool ok = cam && cam->camera;
    p.setPen(QPen(QColor(20, 20, 22), 1));
    p.setBrush(ok ? (i % 2 ? QColor(70, 110, 160) : QColor(60, 128, 120)) : QColor(150, 60, 55));
    p.drawRoundedRect(r, 3, 3);
    if (c.transition != sequencer::Transition::Cut && c.transitionFrames > 0) {
      // The transition: a ramp from the shot before into this one.
      const double xe = axis().x(sequencer::frameTime(c.start + c.transitionFrames, rate));
      QPolygonF ramp;
      ramp << QPointF(r.left(), r.bottom()) << QPointF(xe, r.top()) << QPointF(xe, r.bottom());
      p.setBrush(c.transition == sequencer::Transition::DipToBlack ? QColor(10, 10, 12, 160) : QColor(255, 255, 255, 60));
      p.drawPolygon(ramp);
      if (sequencer::isPatterned(c.transition)) {
        // A stylised transition names itself on its ramp (when it fits).
        p.setPen(QColor(20, 20, 22));
        const QRectF on(r.left(), r.top(), xe - r.left(), r.height());
        const QString kind = QString::fromStdString(sequencer::transitionName(c.transition));
        if (p.fontMetrics().horizontalAdvance(kind) + 8 < on.width())
          p.drawText(on.adjusted(4, 0, -4, 0), Qt::AlignBottom | Qt::AlignRight, kind);
      }
    }
    p.setPen(QColor(235, 236, 240));
    const QString label = QString::fromStdString(cam ? cam->name : "#" + std::to_string(c.camera) + " (missing)");
    p.drawText(r.adjusted(6, 0, -4, 0), Qt::AlignVCenter | Qt::AlignLeft, label);
  }
  // The track's problem while it has one, the usage otherwise.
  setToolTip(problem.empty() ? QString(kUsage) : QString::fromStdString("Camera cuts: " + problem));
  // The playhead.
  const double x = axis().x(sequencer::frameTime(clock_.frame(), rate));
  p.setPen(QPen(QColor(255, 90, 74), 1.5));
  p.drawLine(QPointF(x, 0), QPointF(x, height()));
}

std::optional<TimelineCutTrack::Hit> TimelineCutTrack::hitAt(const QPointF& pos) const {
  const auto& cuts = doc_.state().sequence.cuts;
  const sequencer::FrameRate rate = doc_.state().sequence.rate;
  for (size_t i = 0; i < cuts.size(); ++i) {
    const QRectF r = cutRect(i);
    if (pos.x() < r.left() - kEdgePx || pos.x() > r.right() + kEdgePx) continue;
    const sequencer::CameraCut& c = cuts[i];
    if (c.transition != sequencer::Transition::Cut &&
        std::abs(pos.x() - axis().x(sequencer::frameTime(c.start + c.transitionFrames, rate))) <= kEdgePx)
      return Hit{i, Part::Ramp};
    if (std::abs(pos.x() - r.left()) <= kEdgePx) return Hit{i, Part::Start};
    if (std::abs(pos.x() - r.right()) <= kEdgePx) return Hit{i, Part::End};
    if (r.contains(pos)) return Hit{i, Part::Body};
  }
  return std::nullopt;
}

bool TimelineCutTrack::apply(std::vector<sequencer::CameraCut> cuts, const QString& text, const QString& mergeKey) {
  if (!scene::cutsProblem(doc_.state(), cuts).empty()) return false;
  sequencer::Sequence seq = doc_.state().sequence;
  seq.cuts = std::move(cuts);
  return scene::ops::replaceSequence(doc_, std::move(seq), text, mergeKey);
}

void TimelineCutTrack::mousePressEvent(QMouseEvent* e) {
  if (e->button() != Qt::LeftButton) return;
  drag_ = hitAt(e->position());
  if (!drag_) {
    // The empty track: the playhead goes there, as on the ruler.
    if (e->position().x() >= TimelineDopeSheet::kNamesWidth)
      clock_.setFrame(sequencer::frameAtTime(axis().time(e->position().x()), doc_.state().sequence.rate));
    return;
  }
  dragStart_ = doc_.state().sequence.cuts;
  pressX_ = e->position().x();
  ++gesture_;
}

void TimelineCutTrack::mouseMoveEvent(QMouseEvent* e) {
  if (!drag_) {
    const std::optional<Hit> h = hitAt(e->position());
    setCursor(!h ? Qt::ArrowCursor : h->part == Part::Body ? Qt::OpenHandCursor : Qt::SizeHorCursor);
    return;
  }
  const sequencer::FrameRate rate = doc_.state().sequence.rate;
  const int64_t df = int64_t(std::llround((e->position().x() - pressX_) / axis().pixelsPerSecond() * rate.fps()));
  std::vector<sequencer::CameraCut> cuts = dragStart_;
  sequencer::CameraCut& c = cuts[drag_->cut];
  switch (drag_->part) {
    case Part::Body: c.start += df, c.end += df; break;
    case Part::Start: c.start += df; break;
    case Part::End: c.end += df; break;
    case Part::Ramp: c.transitionFrames = std::max<int64_t>(1, c.transitionFrames + df); break;
  }
  const QString text = drag_->part == Part::Body ? "Move Cut" : drag_->part == Part::Ramp ? "Transition Length" : "Trim Cut";
  apply(std::move(cuts), text, QString("cut-drag-%1").arg(gesture_));
}

void TimelineCutTrack::mouseReleaseEvent(QMouseEvent*) { drag_.reset(); }

bool TimelineCutTrack::addCutAtPlayhead() {
  const scene::SceneState& s = doc_.state();
  const scene::Entity* cam = s.find(selection_.primary());
  if (!cam || !cam->camera) return false;
  const int64_t start = clock_.frame();
  int64_t end = start + int64_t(std::llround(5.0 * s.sequence.rate.fps())) - 1;
  for (const sequencer::CameraCut& c : s.sequence.cuts)
    if (c.start > start) end = std::min(end, c.start - 1);
  return apply(scene::withCut(s.sequence.cuts, sequencer::CameraCut{cam->id, start, end}),
               QString("Add Cut to %1").arg(QString::fromStdString(cam->name)));
}

bool TimelineCutTrack::setTransition(size_t i, sequencer::Transition kind, int64_t frames) {
  std::vector<sequencer::CameraCut> cuts = doc_.state().sequence.cuts;
  if (i >= cuts.size()) return false;
  cuts[i].transition = kind;
  cuts[i].transitionFrames = kind == sequencer::Transition::Cut ? 0 : frames;
  return apply(std::move(cuts), "Cut Transition");
}

bool TimelineCutTrack::setEase(size_t i, sequencer::Ease ease) {
  std::vector<sequencer::CameraCut> cuts = doc_.state().sequence.cuts;
  if (i >= cuts.size() || cuts[i].transition == sequencer::Transition::Cut) return false;
  cuts[i].ease = ease;
  return apply(std::move(cuts), "Transition Ease");
}

bool TimelineCutTrack::removeCut(size_t i) {
  std::string error;
  return scene::ops::removeCut(doc_, i, error);
}

void TimelineCutTrack::contextMenuEvent(QContextMenuEvent* e) {
  QMenu menu(this);
  const scene::Entity* cam = doc_.state().find(selection_.primary());
  QAction* add = menu.addAction(cam && cam->camera ? QString("Add Cut: %1 from the Playhead").arg(QString::fromStdString(cam->name))
                                                   : QString("Add Cut (select a camera)"));
  add->setEnabled(cam && cam->camera);
  connect(add, &QAction::triggered, this, [this] { addCutAtPlayhead(); });
  if (const std::optional<Hit> h = hitAt(e->pos())) {
    menu.addSeparator();
    const size_t i = h->cut;
    const int64_t second = int64_t(std::llround(doc_.state().sequence.rate.fps()));
    const int64_t current = doc_.state().sequence.cuts[i].transitionFrames;
    const int64_t length = current > 0 ? current : second;
    QMenu* kinds = menu.addMenu("Transition");
    kinds->setObjectName("cutTransitionMenu");
    for (const std::string& name : sequencer::transitionNameList()) {
      const sequencer::Transition kind = *sequencer::transitionFromName(name);
      QAction* a = kinds->addAction(QString::fromStdString(name));
      a->setCheckable(true);
      a->setChecked(doc_.state().sequence.cuts[i].transition == kind);
      connect(a, &QAction::triggered, this, [this, i, kind, length] { setTransition(i, kind, length); });
    }
    if (doc_.state().sequence.cuts[i].transition != sequencer::Transition::Cut) {
      QMenu* eases = menu.addMenu("Transition Ease");
      for (auto ease : {sequencer::Ease::None, sequencer::Ease::In, sequencer::Ease::Out, sequencer::Ease::InOut}) {
        QAction* a = eases->addAction(sequencer::easeName(ease));
        a->setCheckable(true);
        a->setChecked(doc_.state().sequence.cuts[i].ease == ease);
        connect(a, &QAction::triggered, this, [this, i, ease] { setEase(i, ease); });
      }
    }
    menu.addSeparator();
    connect(menu.addAction("Remove Cut"), &QAction::triggered, this, [this, i] { removeCut(i); });
  }
  menu.exec(e->globalPos());
}

}  // namespace hs::app
