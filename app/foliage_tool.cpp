#include "app/foliage_tool.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <QCoreApplication>
#include <QKeyEvent>
#include <QKeySequence>

#include "app/foliage_ground_cache.h"
#include "app/foliage_work.h"
#include "scene/foliage_command.h"
#include "scene/foliage_data.h"
#include "scene/terrain_pick.h"

namespace hs::app {
namespace {

constexpr int kCircleSegments = 96;
// A ray meets a scan within this distance or not at all (the bisection in
// MeshGround::raycast needs a finite interval; 1000 km is past any view).
constexpr double kFarMetres = 1e6;
// Ticks drawn at most, so a brush over a dense meadow stays cheap to draw.
constexpr size_t kMaxTicksUnderBrush = 4000;
constexpr size_t kMaxSelectedTicks = 20000;
// Fill and Reapply on their worker show a progress dialog only when they
// take longer than this (a small fill ends first: no flashing dialog).
constexpr int kShowWorkAfterMs = 250;
// A lasso or fill polygon: a point where the drag has gone this far (XY,
// metres) from the last, and this many points at most (a long drag keeps
// its shape to a few centimetres either way).
constexpr double kPolygonStep = 0.05;
constexpr size_t kMaxPolygonPoints = 8192;
// Warnings listed one by one at most; the rest are counted.
constexpr size_t kMaxListedWarnings = 3;

// A dab's seed: different for every dab of every stroke, the same for the
// same brush seed, stroke and dab (so a session replays the same way).
uint64_t dabSeed(uint64_t seed, uint64_t stroke, uint64_t dab) {
  uint64_t z = seed * 0x9E3779B97F4A7C15ull + (stroke << 24) + dab;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return (z ^ (z >> 31)) & 0x7FFFFFFFull;  // within `foliage scatter`'s declared seed range
}

}  // namespace

const char* foliageToolLabel(FoliageToolKind k) {
  switch (k) {
    case FoliageToolKind::Off: return "Off";
    case FoliageToolKind::Paint: return "Paint";
    case FoliageToolKind::Erase: return "Erase";
    case FoliageToolKind::Select: return "Select";
    case FoliageToolKind::Lasso: return "Lasso";
    case FoliageToolKind::Fill: return "Fill";
    case FoliageToolKind::Move: return "Move";
  }
  return "?";
}

bool foliageToolDrawsPolygon(FoliageToolKind k) { return k == FoliageToolKind::Lasso || k == FoliageToolKind::Fill; }

FoliageTool::FoliageTool(scene::Document& doc, FoliageGroundCache& ground, QObject* parent)
    : QObject(parent), doc_(doc), ground_(ground) {
  // A new or opened document: the selection's ids belong to the old one.
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.reset) clearSelection();
  });
}

FoliageTool::~FoliageTool() {
  if (stroking_) QCoreApplication::instance()->removeEventFilter(this);
}

void FoliageTool::setKind(FoliageToolKind k) {
  if (k == kind_) return;
  if (stroking_) end();
  kind_ = k;
  if (!active()) hover_.reset();
  emit settingsChanged();
}

void FoliageTool::setBrush(const FoliageBrush& b) {
  brush_ = b;
  brush_.radius = std::clamp(b.radius, kMinRadius, kMaxRadius);
  brush_.densityFactor = std::clamp(b.densityFactor, 0.0, kMaxDensityFactor);
  emit settingsChanged();
}

void FoliageTool::scaleRadius(double factor) {
  FoliageBrush b = brush_;
  b.radius *= factor;
  setBrush(b);
}

void FoliageTool::scaleDensity(double factor) {
  FoliageBrush b = brush_;
  b.densityFactor = std::max(b.densityFactor, 0.05) * factor;  // from 0 too
  setBrush(b);
}

std::optional<FoliageTool::GroundHit> FoliageTool::pick(const glm::dvec3& origin, const glm::dvec3& direction) {
  const glm::dvec3 dir = glm::normalize(direction);
  std::optional<GroundHit> best;
  double bestDistance = kFarMetres;
  if (const auto t = scene::pickTerrain(doc_.state(), origin, dir, kFarMetres)) {
    best = GroundHit{t->hit.world, t->entity};
    bestDistance = glm::length(t->hit.world - origin);
  }
  for (const foliage::MeshGround* m : ground_.ground().ground().meshes)
    if (const auto h = m->raycast(origin, dir, bestDistance)) {
      const double d = glm::length(h->position - origin);
      if (d < bestDistance) {
        best = GroundHit{h->position, scene::kNoEntity};
        bestDistance = d;
      }
    }
  return best;
}

bool FoliageTool::hover(const glm::dvec3& origin, const glm::dvec3& direction) {
  if (!active()) return false;
  const auto h = pick(origin, direction);
  const bool changed =
      h.has_value() != hover_.has_value() || (h && glm::length(h->point - hover_->point) > 1e-9);
  hover_ = h;
  return changed;
}

std::optional<glm::dvec3> FoliageTool::hoverPoint() const {
  if (!hover_) return std::nullopt;
  return hover_->point;
}

namespace {

// The instance with `id` as a selection item, when its type is among
// `types` (none: every type). A click's lookup: one pass over the cells.
foliage::Selection selectDrawn(const foliage::FoliageStore& store, uint32_t id, const foliage::TypeSet& types) {
  foliage::Selection s;
  for (const auto& [key, cell] : store.cells())
    for (const foliage::Run& run : cell.runs)
      for (const foliage::PackedInstance& p : run.items)
        if (p.id == id) {
          if (types.empty() || std::find(types.begin(), types.end(), run.type) != types.end())
            s.items.push_back({key, id});
          return s;
        }
  return s;
}

}  // namespace

bool FoliageTool::begin(const glm::dvec3& origin, const glm::dvec3& direction, bool extend,
                        std::optional<uint32_t> drawn) {
  if (!active() || stroking_ || working_) return false;
  const auto h = pick(origin, direction);
  hover_ = h;
  foliage::Selection clicked;
  if (kind_ == FoliageToolKind::Select && drawn) clicked = selectDrawn(doc_.foliage().store(), *drawn, types_);
  if (!h && clicked.empty()) return false;
  if ((kind_ == FoliageToolKind::Paint || kind_ == FoliageToolKind::Fill) && types_.empty()) {
    emit strokeFinished(QString("%1 foliage: no type chosen (select a type in the Foliage panel, or check several)")
                            .arg(foliageToolLabel(kind_)),
                        true);
    return true;  // handled: the click selects no entity either
  }
  if (kind_ == FoliageToolKind::Move && selection_.empty()) {
    emit strokeFinished("Move foliage: nothing selected (the Select or Lasso tool picks instances)", true);
    return true;
  }
  stroking_ = true;
  undo_ = {};
  stats_ = {};
  messages_.clear();
  dabs_ = 0;
  ++strokes_;
  // Undo/Redo wait for the stroke: its cells are being written.
  QCoreApplication::instance()->installEventFilter(this);
  if (kind_ == FoliageToolKind::Select) {
    if (!extend) selection_.items.clear();
    // A click: the instance drawn under the cursor, else the nearest within
    // the radius of the ground point; a drag adds more.
    if (clicked.empty()) clicked = foliage::selectPoint(doc_.foliage().store(), h->point, brush_.radius, types_);
    addToSelection(std::move(clicked));
    if (h) lastDab_ = h->point;
    else if (const auto in = doc_.foliage().store().find(*drawn)) lastDab_ = in->position;
    return true;
  }
  if (foliageToolDrawsPolygon(kind_)) {
    if (kind_ == FoliageToolKind::Lasso && !extend) clearSelection();
    polygon_ = {h->point};
    return true;
  }
  if (kind_ == FoliageToolKind::Move) {
    moveFrom_ = h->point;
    moveOffset_ = glm::dvec3(0.0);
    return true;
  }
  dab(h->point);
  return true;
}

void FoliageTool::drag(const glm::dvec3& origin, const glm::dvec3& direction) {
  if (!stroking_) return;
  const auto h = pick(origin, direction);
  if (!h) return;  // off the ground: the stroke waits where it was
  hover_ = h;
  if (foliageToolDrawsPolygon(kind_)) {
    if (polygon_.size() < kMaxPolygonPoints && glm::length(glm::dvec2(h->point - polygon_.back())) >= kPolygonStep)
      polygon_.push_back(h->point);
    return;
  }
  if (kind_ == FoliageToolKind::Move) {
    moveOffset_ = h->point - moveFrom_;
    return;
  }
  // Dabs every half radius along the drag (in XY, as the dabs' discs are).
  const double step = std::max(brush_.radius * 0.5, 1e-3);
  const glm::dvec3 from = lastDab_;
  const glm::dvec2 d = glm::dvec2(h->point - from);
  const double length = glm::length(d);
  const int n = int(std::floor(length / step));
  for (int i = 1; i <= n; ++i) dab(glm::mix(from, h->point, double(i) * step / length));
}

void FoliageTool::dab(const glm::dvec3& centre) {
  lastDab_ = centre;
  foliage::FoliageStore& store = doc_.foliage().store();
  const foliage::Region2 disc = foliage::Region2::disc(glm::dvec2(centre), brush_.radius);
  if (kind_ == FoliageToolKind::Select) {
    addToSelection(foliage::selectRegion(store, disc, types_));
    return;
  }
  foliage::EditResult r;
  if (kind_ == FoliageToolKind::Paint) {
    foliage::PaintParams p;
    p.region = disc;
    p.types = types_;
    p.densityFactor = brush_.densityFactor;
    p.seed = dabSeed(brush_.seed, strokes_, dabs_);
    r = foliage::paint(store, ground_.ground().ground(), p);
  } else {
    r = foliage::erase(store, disc, types_);
  }
  ++dabs_;
  stats_.placed += r.stats.placed;
  stats_.removed += r.stats.removed;
  for (std::string& m : r.stats.messages)
    if (std::find(messages_.begin(), messages_.end(), m) == messages_.end()) messages_.push_back(std::move(m));
  undo_.merge(std::move(r.undo));
  // Views (the panel's counts, the viewport) see each dab; the undo step
  // comes at release.
  if (!undo_.empty()) doc_.notifyFoliageChanged();
}

void FoliageTool::addToSelection(foliage::Selection more) {
  if (more.empty()) {
    emit selectionChanged();
    return;
  }
  std::vector<std::pair<foliage::CellKey, uint32_t>> merged;
  merged.reserve(selection_.size() + more.size());
  std::sort(more.items.begin(), more.items.end());
  std::set_union(selection_.items.begin(), selection_.items.end(), more.items.begin(), more.items.end(),
                 std::back_inserter(merged));
  selection_.items = std::move(merged);
  emit selectionChanged();
}

void FoliageTool::end() {
  if (!stroking_) return;
  stroking_ = false;
  QCoreApplication::instance()->removeEventFilter(this);
  if (foliageToolDrawsPolygon(kind_)) return endPolygon();
  if (kind_ == FoliageToolKind::Move) return endMove();
  if (kind_ == FoliageToolKind::Select) {
    emit strokeFinished(QString("Foliage selection: %1 instance(s)").arg(selection_.size()), false);
    return;
  }
  const QString label = kind_ == FoliageToolKind::Paint ? "Paint foliage" : "Erase foliage";
  const bool pushed = scene::pushFoliageEdit(doc_, std::move(undo_), label);
  undo_ = {};
  for (const std::string& m : messages_) emit strokeFinished(label + ": " + QString::fromStdString(m), true);
  emit strokeFinished(pushed ? QString("%1: %2 placed, %3 removed in %4 dab(s)")
                                   .arg(label)
                                   .arg(stats_.placed)
                                   .arg(stats_.removed)
                                   .arg(dabs_)
                             : QString("%1: nothing changed").arg(label),
                      false);
}

void FoliageTool::endPolygon() {
  std::vector<glm::dvec2> points;
  for (const glm::dvec3& p : polygon_) points.emplace_back(p);
  polygon_.clear();
  const bool lasso = kind_ == FoliageToolKind::Lasso;
  const QString label = lasso ? "Foliage lasso" : "Fill foliage";
  const foliage::Region2 area = foliage::Region2::poly(std::move(points));
  if (area.polygon.size() < 3 || !(area.area() > 0.0)) {
    emit strokeFinished(label + ": draw a loop around an area on the ground", true);
    if (lasso) emit selectionChanged();
    return;
  }
  foliage::FoliageStore& store = doc_.foliage().store();
  if (lasso) {
    addToSelection(foliage::selectRegion(store, area, types_));
    emit strokeFinished(QString("Foliage selection: %1 instance(s)").arg(selection_.size()), false);
    return;
  }
  // A fill over a valley places millions: on a worker, into a copy
  // (foliage_work.h); a small one ends before its dialog would show.
  foliage::PaintParams p;
  p.region = area;
  p.types = types_;
  p.densityFactor = brush_.densityFactor;
  p.seed = dabSeed(brush_.seed, strokes_, 0);
  std::shared_ptr<const scene::FoliageGround> ground = ground_.shared();
  working_ = true;
  const scene::ops::FoliageOutcome out = runFoliageWork(
      dialogParent_, doc_, label, "Filling the area…",
      [ground, p, label](foliage::FoliageStore& copy, const Progress& progress) {
        scene::ops::FoliageWork work;
        foliage::PaintParams params = p;
        params.progress = &progress;
        work.result = foliage::paint(copy, ground->ground(), params);
        work.text = label;
        return work;
      },
      kShowWorkAfterMs);
  working_ = false;
  announce(out, label,
           QString("%1: %2 placed over %3 m²").arg(label).arg(out.stats.placed).arg(area.area(), 0, 'f', 0));
}

void FoliageTool::endMove() {
  const glm::dvec3 offset = moveOffset_;
  moveOffset_ = glm::dvec3(0.0);
  moveSelectionBy(offset, true);
}

bool FoliageTool::moveSelectionBy(const glm::dvec3& offset, bool snap) {
  if (offset == glm::dvec3(0.0) || selection_.empty() || !std::isfinite(glm::length(offset))) {
    emit strokeFinished("Move foliage: nothing moved", false);
    return false;
  }
  foliage::EditResult r =
      foliage::moveSelection(doc_.foliage().store(), ground_.ground().ground(), selection_, offset, snap);
  const size_t moved = r.stats.moved;
  const QString done = QString("Move foliage: %1 moved by %2 m").arg(moved).arg(glm::length(offset), 0, 'f', 2);
  record(std::move(r), "Move foliage", true, done);
  return moved > 0;
}

void FoliageTool::clearSelection() {
  if (selection_.empty()) return;
  selection_.items.clear();
  emit selectionChanged();
}

void FoliageTool::announceWarnings(const std::vector<std::string>& warnings, const QString& text) {
  for (size_t i = 0; i < warnings.size() && i < kMaxListedWarnings; ++i)
    emit strokeFinished(text + ": " + QString::fromStdString(warnings[i]), true);
  if (warnings.size() > kMaxListedWarnings)
    emit strokeFinished(QString("%1: %2 more warning(s) like these").arg(text).arg(warnings.size() - kMaxListedWarnings),
                        true);
}

void FoliageTool::record(foliage::EditResult r, const QString& text, bool keepsSelection, const QString& done) {
  announceWarnings(r.stats.messages, text);
  const QString summary =
      !done.isEmpty() ? done : QString("%1: %2 changed, %3 removed").arg(text).arg(r.stats.changed).arg(r.stats.removed);
  const bool pushed = scene::pushFoliageEdit(doc_, std::move(r.undo), text);
  emit strokeFinished(pushed ? summary : QString("%1: nothing changed").arg(text), false);
  if (!keepsSelection) selection_.items.clear();
  emit selectionChanged();
}

bool FoliageTool::deleteSelection() {
  if (selection_.empty() || stroking_) return false;
  foliage::EditResult r = foliage::deleteSelection(doc_.foliage().store(), selection_);
  const bool changed = !r.undo.empty();
  record(std::move(r), "Delete foliage", false);
  return changed;
}

bool FoliageTool::reapplySelection() {
  if (selection_.empty() || stroking_ || working_) return false;
  // Thousands of surface queries for a large selection: on a worker, into a
  // copy (foliage_work.h). The selection follows the instances (their ids
  // stay; cells may change): the worker's copy of it is taken at the end.
  std::shared_ptr<const scene::FoliageGround> ground = ground_.shared();
  auto selection = std::make_shared<foliage::Selection>(selection_);
  const uint64_t seed = brush_.seed;
  const QString text = "Reapply foliage";
  working_ = true;
  const scene::ops::FoliageOutcome out = runFoliageWork(
      dialogParent_, doc_, text, "Reapplying the type settings…",
      [ground, selection, seed, text](foliage::FoliageStore& copy, const Progress& progress) {
        scene::ops::FoliageWork work;
        work.result = foliage::reapply(copy, ground->ground(), *selection, seed, &progress);
        work.text = text;
        return work;
      },
      kShowWorkAfterMs);
  working_ = false;
  const bool changed = out.ok && !out.cancelled && (out.stats.changed > 0 || out.stats.removed > 0);
  if (changed) selection_ = *selection;
  announce(out, text, QString("%1: %2 changed, %3 removed").arg(text).arg(out.stats.changed).arg(out.stats.removed));
  emit selectionChanged();
  return changed;
}

void FoliageTool::announce(const scene::ops::FoliageOutcome& out, const QString& text, const QString& done) {
  if (!out.ok) {
    emit strokeFinished(text + ": " + QString::fromStdString(out.error), true);
    return;
  }
  announceWarnings(out.messages, text);
  const bool changed = out.stats.placed + out.stats.removed + out.stats.changed + out.stats.moved > 0;
  emit strokeFinished(out.cancelled ? text + ": cancelled; nothing changed"
                      : changed     ? done
                                    : QString("%1: nothing changed").arg(text),
                      false);
}

bool FoliageTool::eventFilter(QObject* watched, QEvent* event) {
  if (stroking_ && (event->type() == QEvent::ShortcutOverride || event->type() == QEvent::KeyPress)) {
    auto* k = static_cast<QKeyEvent*>(event);
    if (k->matches(QKeySequence::Undo) || k->matches(QKeySequence::Redo) ||
        k->keyCombination() == QKeyCombination(Qt::CTRL | Qt::Key_Y)) {
      event->accept();
      return true;
    }
  }
  return QObject::eventFilter(watched, event);
}

void FoliageTool::drawOverlay(const scene::SceneState& state, render::Overlay& overlay) const {
  const foliage::FoliageStore* store = scene::foliageStoreOf(state);
  const double tick = std::clamp(brush_.radius * 0.08, 0.3, 5.0);
  // The selection, whatever the tool (it outlives a tool change).
  if (store && !selection_.empty()) {
    const glm::vec4 cyan(0.3f, 0.9f, 1.0f, 1.0f);
    size_t drawn = 0;
    const auto& items = selection_.items;
    // Move shows the selection where the drag would put it (before the snap).
    const glm::dvec3 shift = kind_ == FoliageToolKind::Move && stroking_ ? moveOffset_ : glm::dvec3(0.0);
    for (size_t i = 0; i < items.size() && drawn < kMaxSelectedTicks;) {
      size_t j = i;
      while (j < items.size() && items[j].first == items[i].first) ++j;
      if (const foliage::Cell* cell = store->cell(items[i].first)) {
        std::vector<uint32_t> ids;
        for (size_t k = i; k < j; ++k) ids.push_back(items[k].second);
        for (const foliage::Run& r : cell->runs)
          for (const foliage::PackedInstance& p : r.items)
            if (drawn < kMaxSelectedTicks && std::binary_search(ids.begin(), ids.end(), p.id)) {
              const glm::dvec3 at = foliage::unpackPosition(p, items[i].first) + shift;
              overlay.line(at, at + glm::dvec3(0, 0, tick * 2.0), cyan);
              ++drawn;
            }
      }
      i = j;
    }
  }
  if (!active() || !hover_) return;
  const glm::dvec3 c = hover_->point;
  const double lift = std::max(0.02, brush_.radius * 0.01);
  // On a terrain the circle lies on it; on a scan, level at the hit.
  auto groundZ = [&](const glm::dvec2& xy) {
    if (hover_->terrain != scene::kNoEntity)
      if (const auto z = scene::terrainSurfaceAt(state, hover_->terrain, xy)) return *z;
    return c.z;
  };
  const bool adds = kind_ == FoliageToolKind::Paint || kind_ == FoliageToolKind::Fill;
  const glm::vec4 colour = adds                              ? glm::vec4(0.45f, 1.0f, 0.35f, 0.95f)
                           : kind_ == FoliageToolKind::Erase ? glm::vec4(1.0f, 0.45f, 0.3f, 0.95f)
                                                             : glm::vec4(0.3f, 0.9f, 1.0f, 0.95f);
  // Lasso, Fill and Move have no disc: a mark at the cursor, and the
  // polygon so far closed back to its start.
  if (foliageToolDrawsPolygon(kind_) || kind_ == FoliageToolKind::Move) {
    overlay.line(c, c + glm::dvec3(0, 0, std::max(1.0, tick * 3.0)), colour);
    const glm::dvec3 up(0.0, 0.0, 0.05);
    for (size_t i = 0; i + 1 < polygon_.size(); ++i) overlay.line(polygon_[i] + up, polygon_[i + 1] + up, colour);
    if (polygon_.size() > 2)
      overlay.line(polygon_.back() + up, polygon_.front() + up, glm::vec4(colour.r, colour.g, colour.b, 0.5f));
    return;
  }
  glm::dvec3 prev{};
  for (int i = 0; i <= kCircleSegments; ++i) {
    const double a = 2.0 * M_PI * i / kCircleSegments;
    const glm::dvec2 p = glm::dvec2(c) + brush_.radius * glm::dvec2(std::cos(a), std::sin(a));
    const glm::dvec3 w(p, groundZ(p) + lift);
    if (i) overlay.line(prev, w, colour);
    prev = w;
  }
  overlay.line(c, c + glm::dvec3(0, 0, brush_.radius * 0.15), colour);
  if (!store) return;
  // The instances a dab here would touch (of the brush's types).
  const glm::vec4 dim(colour.r, colour.g, colour.b, 0.6f);
  const foliage::Region2 disc = foliage::Region2::disc(glm::dvec2(c), brush_.radius);
  size_t drawn = 0;
  store->forEachCellIn(glm::dvec2(c) - brush_.radius, glm::dvec2(c) + brush_.radius,
                       [&](const foliage::CellKey& k, const foliage::Cell& cell) {
                         for (const foliage::Run& r : cell.runs) {
                           if (!types_.empty() && std::find(types_.begin(), types_.end(), r.type) == types_.end())
                             continue;
                           for (const foliage::PackedInstance& p : r.items) {
                             if (drawn >= kMaxTicksUnderBrush) return;
                             const glm::dvec3 at = foliage::unpackPosition(p, k);
                             if (!disc.contains(glm::dvec2(at))) continue;
                             overlay.line(at, at + glm::dvec3(0, 0, tick), dim);
                             ++drawn;
                           }
                         }
                       });
}

}  // namespace hs::app
