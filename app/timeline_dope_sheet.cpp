#include "app/timeline_dope_sheet.h"

#include <algorithm>
#include <cmath>

#include <QContextMenuEvent>
#include <QKeyEvent>
#include <QMenu>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QWheelEvent>

#include "app/selection.h"
#include "sequencer/binding_target.h"

namespace hs::app {

namespace {

constexpr double kHitX = 6.0;

void diamond(QPainter& p, const QPointF& c, double r, const QColor& fill) {
  QPainterPath path;
  path.moveTo(c.x(), c.y() - r);
  path.lineTo(c.x() + r, c.y());
  path.lineTo(c.x(), c.y() + r);
  path.lineTo(c.x() - r, c.y());
  path.closeSubpath();
  p.fillPath(path, fill);
  p.setPen(QColor(20, 20, 22));
  p.drawPath(path);
}

}  // namespace

TimelineDopeSheet::TimelineDopeSheet(TimelineActions& actions, TimeWindow& window, Selection& selection,
                                     QWidget* parent)
    : QWidget(parent), actions_(actions), window_(window), selection_(selection) {
  setObjectName("timelineDopeSheet");
  setFocusPolicy(Qt::StrongFocus);
  setMinimumHeight(kRulerHeight + 3 * kRowHeight);
  connect(&actions_.document(), &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.sequence || c.hierarchy || c.reset) {
      actions_.keys().prune(actions_.document().state().sequence);
      rebuild();
    }
    update();
  });
  connect(&actions_.clock(), &TimelineClock::frameChanged, this, qOverload<>(&QWidget::update));
  connect(&actions_.clock(), &TimelineClock::loopChanged, this, qOverload<>(&QWidget::update));
  connect(&actions_.keys(), &KeySelection::changed, this, qOverload<>(&QWidget::update));
  connect(&window_, &TimeWindow::changed, this, qOverload<>(&QWidget::update));
  rebuild();
}

void TimelineDopeSheet::rebuild() {
  rows_ = timelineRows(actions_.document().state(), collapsed_);
  scrollRows_ = std::clamp(scrollRows_, 0, std::max(0, int(rows_.size()) - 1));
  update();
}

void TimelineDopeSheet::setCollapsed(scene::EntityId id, bool collapsed) {
  if (collapsed) collapsed_.insert(id);
  else collapsed_.erase(id);
  rebuild();
}

TimeAxis TimelineDopeSheet::axis() const {
  return TimeAxis{window_.start(), window_.end(), kNamesWidth, std::max(1, width() - kNamesWidth)};
}

RulerMarks TimelineDopeSheet::marks() const {
  TimelineClock& c = actions_.clock();
  const sequencer::Sequence& s = actions_.document().state().sequence;
  return RulerMarks{c.frame(), s.startFrame, s.endFrame, c.loopFirst(), c.loopLast(), c.looping(), s.rate};
}

int TimelineDopeSheet::rowTop(int index) const { return kRulerHeight + (index - scrollRows_) * kRowHeight; }

int TimelineDopeSheet::rowAt(int y) const {
  if (y < kRulerHeight) return -1;
  const int i = (y - kRulerHeight) / kRowHeight + scrollRows_;
  return i >= 0 && i < int(rows_.size()) ? i : -1;
}

QPoint TimelineDopeSheet::rulerPoint(int64_t frame) const {
  const double t = sequencer::frameTime(frame, actions_.document().state().sequence.rate);
  return QPoint(int(std::lround(axis().x(t))), kRulerHeight / 2);
}

std::optional<QPointF> TimelineDopeSheet::keyPosition(const sequencer::KeyRef& k) const {
  const auto t = sequencer::keyTime(actions_.document().state().sequence, k);
  if (!t) return std::nullopt;
  for (size_t i = 0; i < rows_.size(); ++i) {
    const TimelineRow& r = rows_[i];
    if (r.entity != k.entity) continue;
    if (r.property == k.property || (r.isEntity() && collapsed_.count(k.entity))) {
      const int top = rowTop(int(i));
      if (top < kRulerHeight || top > height()) return std::nullopt;
      return QPointF(axis().x(*t), top + kRowHeight / 2.0);
    }
  }
  return std::nullopt;
}

std::vector<sequencer::KeyRef> TimelineDopeSheet::keysAt(const QPointF& pos) const {
  const int row = rowAt(int(pos.y()));
  if (row < 0 || pos.x() < kNamesWidth) return {};
  const sequencer::Sequence& seq = actions_.document().state().sequence;
  const TimeAxis ax = axis();
  std::optional<double> best;
  for (const sequencer::KeyRef& k : rowKeys(seq, rows_[size_t(row)])) {
    const double x = ax.x(*sequencer::keyTime(seq, k));
    if (std::abs(x - pos.x()) <= kHitX && (!best || std::abs(x - pos.x()) < std::abs(ax.x(*best) - pos.x())))
      best = *sequencer::keyTime(seq, k);
  }
  if (!best) return {};
  std::vector<sequencer::KeyRef> out;
  for (const sequencer::KeyRef& k : rowKeys(seq, rows_[size_t(row)]))
    if (sequencer::sameKeyTime(*sequencer::keyTime(seq, k), *best)) out.push_back(k);
  return out;
}

void TimelineDopeSheet::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), QColor(40, 41, 44));
  const TimeAxis ax = axis();
  const RulerMarks m = marks();
  const QRect keysArea(kNamesWidth, kRulerHeight, width() - kNamesWidth, height() - kRulerHeight);
  paintTimeBackground(p, keysArea, ax, m);
  const sequencer::Sequence& seq = actions_.document().state().sequence;
  const KeySelection& sel = actions_.keys();
  p.setFont(QFont(p.font().family(), 9));
  for (size_t i = size_t(scrollRows_); i < rows_.size(); ++i) {
    const int top = rowTop(int(i));
    if (top > height()) break;
    const TimelineRow& r = rows_[i];
    const QRect nameRect(0, top, kNamesWidth, kRowHeight);
    p.fillRect(nameRect, r.isEntity() ? QColor(56, 57, 61) : QColor(47, 48, 51));
    if (r.isEntity()) p.fillRect(QRect(kNamesWidth, top, width() - kNamesWidth, kRowHeight), QColor(255, 255, 255, 8));
    const bool entitySelected = selection_.contains(r.entity);
    p.setPen(entitySelected ? QColor(255, 170, 70) : QColor(205, 206, 210));
    if (r.isEntity()) {
      p.drawText(QRect(4, top, 12, kRowHeight), Qt::AlignCenter, collapsed_.count(r.entity) ? "▸" : "▾");
      QFont bold = p.font();
      bold.setBold(true);
      p.setFont(bold);
      p.drawText(nameRect.adjusted(18, 0, -4, 0), Qt::AlignVCenter | Qt::AlignLeft, r.label);
      p.setFont(QFont(p.font().family(), 9));
    } else {
      p.setPen(QColor(170, 172, 178));
      p.drawText(nameRect.adjusted(30, 0, -4, 0), Qt::AlignVCenter | Qt::AlignLeft, r.label);
    }
    p.setPen(QColor(30, 30, 32));
    p.drawLine(0, top + kRowHeight - 1, width(), top + kRowHeight - 1);
    // Keys: a summary row shows one diamond per time.
    std::vector<std::pair<double, bool>> shown;
    for (const sequencer::KeyRef& k : rowKeys(seq, r)) {
      const double t = *sequencer::keyTime(seq, k);
      const bool selected = sel.contains(k);
      auto same = std::find_if(shown.begin(), shown.end(), [&](const auto& s) { return sequencer::sameKeyTime(s.first, t); });
      if (same == shown.end()) shown.push_back({t, selected});
      else same->second = same->second || selected;
    }
    for (const auto& [t, selected] : shown) {
      const double x = ax.x(t);
      if (x < kNamesWidth - 6 || x > width() + 6) continue;
      const QColor fill = selected ? QColor(255, 160, 40) : r.isEntity() ? QColor(150, 152, 160) : QColor(215, 216, 220);
      diamond(p, QPointF(x, top + kRowHeight / 2.0), r.isEntity() ? 5.0 : 4.5, fill);
    }
  }
  if (rows_.empty()) {
    p.setPen(QColor(143, 144, 149));
    p.drawText(keysArea.adjusted(12, 8, -12, -8), Qt::AlignLeft | Qt::AlignTop | Qt::TextWordWrap,
               "No keys yet. Select an entity and click a ◇ beside a field in Properties (or turn on Auto Key "
               "and edit) to key it at the playhead.");
  }
  paintRuler(p, QRect(kNamesWidth, 0, width() - kNamesWidth, kRulerHeight), ax, m);
  p.fillRect(QRect(0, 0, kNamesWidth, kRulerHeight), QColor(44, 45, 48));
  p.setClipRect(QRect(kNamesWidth, 0, width() - kNamesWidth, height()));
  paintPlayhead(p, rect(), ax, m);
  if (drag_ == Drag::Box && dragStarted_) {
    p.setPen(QPen(QColor(255, 170, 70), 1, Qt::DashLine));
    p.setBrush(QColor(255, 170, 70, 30));
    p.drawRect(box_.normalized());
  }
}

void TimelineDopeSheet::scrubTo(double x) {
  const sequencer::FrameRate rate = actions_.document().state().sequence.rate;
  actions_.clock().setFrame(sequencer::frameAtTime(axis().time(x), rate));
}

void TimelineDopeSheet::mousePressEvent(QMouseEvent* e) {
  setFocus(Qt::MouseFocusReason);
  if (e->button() != Qt::LeftButton) return;
  const QPointF pos = e->position();
  pressPos_ = pos;
  dragStarted_ = false;
  if (pos.y() < kRulerHeight && pos.x() >= kNamesWidth) {
    drag_ = Drag::Scrub;
    scrubTo(pos.x());
    return;
  }
  const int row = rowAt(int(pos.y()));
  if (pos.x() < kNamesWidth) {
    if (row < 0) return;
    const TimelineRow r = rows_[size_t(row)];
    if (r.isEntity() && pos.x() < 18) {
      setCollapsed(r.entity, !collapsed_.count(r.entity));
      return;
    }
    if (sequencer::isEntityTarget(r.entity)) {
      if (actions_.document().state().find(r.entity)) selection_.select(r.entity);
    } else {
      emit objectActivated(r.entity);
    }
    if (!r.isEntity()) emit trackActivated(r.entity, QString::fromStdString(r.property));
    return;
  }
  const std::vector<sequencer::KeyRef> hits = keysAt(pos);
  KeySelection& sel = actions_.keys();
  if (!hits.empty()) {
    if (e->modifiers() & Qt::ShiftModifier) {
      for (const auto& k : hits) sel.toggle(k);
    } else if (std::none_of(hits.begin(), hits.end(), [&](const auto& k) { return sel.contains(k); })) {
      sel.set(hits);
    }
    drag_ = Drag::Keys;
    return;
  }
  if (!(e->modifiers() & Qt::ShiftModifier)) sel.clear();
  drag_ = Drag::Box;
  box_ = QRectF(pos, pos);
}

void TimelineDopeSheet::mouseMoveEvent(QMouseEvent* e) {
  const QPointF pos = e->position();
  switch (drag_) {
    case Drag::Scrub: scrubTo(pos.x()); break;
    case Drag::Keys:
      if (!dragStarted_ && std::abs(pos.x() - pressPos_.x()) > 3.0) {
        dragStarted_ = true;
        actions_.beginMove();
      }
      if (dragStarted_) actions_.moveBy((pos.x() - pressPos_.x()) / axis().pixelsPerSecond());
      break;
    case Drag::Box:
      dragStarted_ = dragStarted_ || (pos - pressPos_).manhattanLength() > 3.0;
      box_.setBottomRight(pos);
      update();
      break;
    case Drag::None: break;
  }
}

void TimelineDopeSheet::mouseReleaseEvent(QMouseEvent* e) {
  if (e->button() != Qt::LeftButton) return;
  if (drag_ == Drag::Scrub) scrubTo(e->position().x());
  if (drag_ == Drag::Keys && dragStarted_) actions_.endMove();
  if (drag_ == Drag::Box && dragStarted_) {
    const QRectF r = box_.normalized();
    const sequencer::Sequence& seq = actions_.document().state().sequence;
    std::vector<sequencer::KeyRef> inside;
    for (size_t i = size_t(scrollRows_); i < rows_.size(); ++i) {
      const double y = rowTop(int(i)) + kRowHeight / 2.0;
      if (y < r.top() || y > r.bottom()) continue;
      for (const auto& k : rowKeys(seq, rows_[i]))
        if (const double x = axis().x(*sequencer::keyTime(seq, k)); x >= r.left() && x <= r.right()) inside.push_back(k);
    }
    actions_.keys().add(inside);
  }
  drag_ = Drag::None;
  dragStarted_ = false;
  update();
}

void TimelineDopeSheet::wheelEvent(QWheelEvent* e) {
  const double steps = e->angleDelta().y() / 120.0;
  if (steps == 0.0) return;
  if (e->modifiers() & Qt::ControlModifier) {
    scrollRows_ = std::clamp(scrollRows_ - int(steps), 0, std::max(0, int(rows_.size()) - 1));
    update();
  } else if (e->modifiers() & Qt::ShiftModifier) {
    window_.pan(-steps * 0.1 * (window_.end() - window_.start()));
  } else {
    window_.zoom(std::pow(0.85, steps), axis().time(e->position().x()));
  }
  e->accept();
}

void TimelineDopeSheet::keyPressEvent(QKeyEvent* e) {
  TimelineClock& clock = actions_.clock();
  if (e->matches(QKeySequence::Copy)) return actions_.copySelected();
  if (e->matches(QKeySequence::Paste)) return void(actions_.paste());
  switch (e->key()) {
    case Qt::Key_Delete:
    case Qt::Key_Backspace: actions_.deleteSelected(); return;
    case Qt::Key_Left: clock.stepFrames(-1); return;
    case Qt::Key_Right: clock.stepFrames(1); return;
    case Qt::Key_Home: clock.goToStart(); return;
    case Qt::Key_End: clock.goToEnd(); return;
    case Qt::Key_Space: clock.togglePlay(); return;
    case Qt::Key_Escape:
      if (actions_.moving()) {
        actions_.cancelMove();
        drag_ = Drag::None;
        dragStarted_ = false;
      } else {
        actions_.keys().clear();
      }
      return;
    default: QWidget::keyPressEvent(e);
  }
}

void TimelineDopeSheet::contextMenuEvent(QContextMenuEvent* e) {
  const std::vector<sequencer::KeyRef> hits = keysAt(e->pos());
  if (!hits.empty() && std::none_of(hits.begin(), hits.end(), [&](const auto& k) { return actions_.keys().contains(k); }))
    actions_.keys().set(hits);
  QMenu* menu = actions_.contextMenu(this);
  menu->setAttribute(Qt::WA_DeleteOnClose);
  menu->popup(e->globalPos());
}

}  // namespace hs::app
