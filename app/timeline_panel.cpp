#include "app/timeline_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSpinBox>
#include <QSplitter>
#include <QStyle>
#include <QToolButton>
#include <QVBoxLayout>

#include "app/param_widgets.h"
#include "app/selection.h"
#include "app/stereo_preview.h"
#include "app/timeline_cut_track.h"
#include "scene/sequence_edits.h"
#include "sequencer/sequencer_operations.h"

namespace hs::app {

namespace {

QString rateText(sequencer::FrameRate r) {
  return r.den == 1 ? QString::number(r.num) : QString::number(r.fps(), 'g', 5);
}

QSpinBox* frameBox(QWidget* parent, const QString& name, const QString& tip) {
  auto* s = new QSpinBox(parent);
  s->setObjectName(name);
  s->setRange(-1000000000, 1000000000);
  s->setToolTip(tip);
  s->setKeyboardTracking(false);
  s->setButtonSymbols(QAbstractSpinBox::NoButtons);
  s->setFixedWidth(64);
  return s;
}

}  // namespace

TimelinePanel::TimelinePanel(scene::Document& doc, TimelineClock& clock, Keying& keying, Selection& selection,
                             StereoPreviewSettings& stereo, QWidget* parent)
    : QWidget(parent), doc_(doc), clock_(clock), keying_(keying), selection_(selection) {
  setObjectName("timelinePanel");
  keys_ = new KeySelection(this);
  actions_ = new TimelineActions(doc_, clock_, *keys_, this);
  window_ = new TimeWindow(this);

  auto* bar = new QHBoxLayout;
  bar->setContentsMargins(4, 2, 4, 2);
  bar->setSpacing(3);
  auto button = [this, bar](const QString& text, const QString& tip, auto fn) {
    auto* b = new QToolButton(this);
    b->setText(text);
    b->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
    b->setToolTip(tip);
    b->setAutoRaise(true);
    connect(b, &QToolButton::clicked, this, fn);
    bar->addWidget(b);
    return b;
  };
  // The style's media icons: every font has them drawn, unlike ⏮ and ⏭.
  auto media = [this](QToolButton* b, QStyle::StandardPixmap icon) {
    b->setIcon(style()->standardIcon(icon));
    b->setToolButtonStyle(Qt::ToolButtonIconOnly);
  };
  media(button("Start", "Go to the start of the loop range (Home in the timeline)", [this] { clock_.goToStart(); }),
        QStyle::SP_MediaSkipBackward);
  media(button("Previous", "Previous frame (Left)", [this] { clock_.stepFrames(-1); }), QStyle::SP_MediaSeekBackward);
  play_ = button("Play", "Play / pause at the sequence's frame rate (Space)", [this] { clock_.togglePlay(); });
  media(play_, QStyle::SP_MediaPlay);
  play_->setObjectName("timelinePlay");
  media(button("Next", "Next frame (Right)", [this] { clock_.stepFrames(1); }), QStyle::SP_MediaSeekForward);
  media(button("End", "Go to the end of the loop range (End)", [this] { clock_.goToEnd(); }), QStyle::SP_MediaSkipForward);
  frame_ = frameBox(this, "timelineFrame", "The current frame");
  bar->addWidget(frame_);
  time_ = new QLabel(this);
  time_->setMinimumWidth(64);
  bar->addWidget(time_);
  bar->addSpacing(10);
  bar->addWidget(new QLabel("Rate", this));
  rate_ = new QComboBox(this);
  rate_->setObjectName("timelineRate");
  rate_->setEditable(true);
  rate_->addItems({"23.976", "24", "25", "29.97", "30", "48", "50", "59.94", "60", "120"});
  rate_->setFixedWidth(72);
  rate_->setToolTip("Frames per second (keys stay at their times in seconds)");
  bar->addWidget(rate_);
  bar->addWidget(new QLabel("Range", this));
  first_ = frameBox(this, "timelineFirst", "First frame of the playback and export range");
  last_ = frameBox(this, "timelineLast", "Last frame of the playback and export range");
  // The range's bounds are `sequence --range`'s.
  const ParamDecl& range = sequencer::sequenceOperation().param("range");
  for (int i = 0; i < 2; ++i) {
    QSpinBox* box = i == 0 ? first_ : last_;
    box->setRange(int(componentMin(range, i)), int(componentMax(range, i)));
    tagParamWidget(box, range, i);
  }
  bar->addWidget(first_);
  bar->addWidget(last_);
  bar->addSpacing(10);
  loop_ = new QCheckBox("Loop", this);
  loop_->setObjectName("timelineLoop");
  loop_->setToolTip("Playback loops over the loop range (default: the whole range)");
  bar->addWidget(loop_);
  loopFirst_ = frameBox(this, "timelineLoopFirst", "First frame of the loop (preview only; not saved)");
  loopLast_ = frameBox(this, "timelineLoopLast", "Last frame of the loop");
  bar->addWidget(loopFirst_);
  bar->addWidget(loopLast_);
  bar->addSpacing(10);
  autoKey_ = button("● Auto Key", "Auto Key: every edit of an animatable property sets a key at the playhead "
                                  "(animated properties are always keyed when edited)",
                    [this](bool on) { clock_.setAutoKey(on); });
  autoKey_->setObjectName("timelineAutoKey");
  autoKey_->setCheckable(true);
  button("◆ Key Transform", "Key the selection's location, rotation and scale at the playhead", [this] { keyTransform(); });
  button("⤳ Follow Path", "The selected camera follows a path at constant speed (made ahead of it if it has none); "
                          "edit the path in the Camera Path panel and by dragging its points in the viewport",
         [this] { emit followPathRequested(); })
      ->setObjectName("timelineFollowPath");
  bar->addSpacing(10);
  bar->addWidget(new QLabel("Stereo", this));
  stereoMode_ = new QComboBox(this);
  stereoMode_->setObjectName("timelineStereoMode");
  for (auto m : {StereoPreviewMode::Off, StereoPreviewMode::Left, StereoPreviewMode::Right, StereoPreviewMode::SideBySide,
                 StereoPreviewMode::Anaglyph})
    stereoMode_->addItem(StereoPreviewSettings::modeName(m), int(m));
  stereoMode_->setToolTip("Viewport stereo preview through the active camera's rig (View > Stereo Preview)");
  bar->addWidget(stereoMode_);
  bar->addStretch();

  dopeSheet_ = new TimelineDopeSheet(*actions_, *window_, selection_, this);
  curveView_ = new TimelineCurveView(*actions_, *window_, this);
  // The camera-cut track over the dope sheet, on its time axis.
  auto* sheet = new QWidget(this);
  auto* sheetLayout = new QVBoxLayout(sheet);
  sheetLayout->setContentsMargins(0, 0, 0, 0);
  sheetLayout->setSpacing(0);
  cutTrack_ = new TimelineCutTrack(doc_, *window_, clock_, selection_, sheet);
  sheetLayout->addWidget(cutTrack_);
  sheetLayout->addWidget(dopeSheet_, 1);
  auto* split = new QSplitter(Qt::Horizontal, this);
  split->addWidget(sheet);
  split->addWidget(curveView_);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 2);
  // The sheet (cut track and dope sheet) never collapses to nothing.
  sheet->setMinimumWidth(TimelineDopeSheet::kNamesWidth + 120);
  split->setCollapsible(0, false);
  split->setSizes({600, 400});  // 3 : 2 from the start, as the stretch keeps it
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addLayout(bar);
  layout->addWidget(split, 1);

  connect(dopeSheet_, &TimelineDopeSheet::trackActivated, this,
          [this](scene::EntityId e, const QString& p) { curveView_->setTrack(e, p.toStdString()); });
  connect(frame_, &QSpinBox::valueChanged, this, [this](int f) { clock_.setFrame(f); });
  connect(rate_->lineEdit(), &QLineEdit::editingFinished, this, &TimelinePanel::applyRate);
  connect(rate_, &QComboBox::activated, this, &TimelinePanel::applyRate);
  connect(first_, &QSpinBox::editingFinished, this, &TimelinePanel::applyRange);
  connect(last_, &QSpinBox::editingFinished, this, &TimelinePanel::applyRange);
  connect(loop_, &QCheckBox::toggled, &clock_, &TimelineClock::setLooping);
  auto applyLoop = [this] { clock_.setLoopRange(loopFirst_->value(), loopLast_->value()); };
  connect(loopFirst_, &QSpinBox::editingFinished, this, applyLoop);
  connect(loopLast_, &QSpinBox::editingFinished, this, applyLoop);
  connect(stereoMode_, &QComboBox::activated, this,
          [this, &stereo](int i) { stereo.setMode(StereoPreviewMode(stereoMode_->itemData(i).toInt())); });
  connect(&stereo, &StereoPreviewSettings::changed, this, [this, &stereo] {
    stereoMode_->setCurrentIndex(stereoMode_->findData(int(stereo.mode())));
  });
  connect(&clock_, &TimelineClock::frameChanged, this, &TimelinePanel::refreshFields);
  connect(&clock_, &TimelineClock::loopChanged, this, &TimelinePanel::refreshFields);
  connect(&clock_, &TimelineClock::playingChanged, this, [this](bool on) {
    play_->setIcon(style()->standardIcon(on ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
    play_->setText(on ? "Pause" : "Play");
  });
  connect(&clock_, &TimelineClock::autoKeyChanged, this, [this](bool on) {
    autoKey_->setChecked(on);
    autoKey_->setStyleSheet(on ? "QToolButton { color: #ff5a4a; font-weight: bold; }" : "");
  });
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.reset) frameRange();
    if (c.sequence || c.reset) refreshFields();
  });
  loop_->setChecked(clock_.looping());
  frameRange();
  refreshFields();
}

void TimelinePanel::frameRange() {
  const sequencer::Sequence& s = doc_.state().sequence;
  const double a = sequencer::frameTime(s.startFrame, s.rate), b = sequencer::frameTime(s.endFrame, s.rate);
  const double pad = std::max((b - a) * 0.03, 0.1);
  window_->setWindow(a - pad, b + pad);
}

void TimelinePanel::refreshFields() {
  const sequencer::Sequence& s = doc_.state().sequence;
  auto show = [](QSpinBox* box, int64_t v) {
    if (box->hasFocus() && box->value() == int(v)) return;
    QSignalBlocker block(box);
    box->setValue(int(v));
  };
  show(frame_, clock_.frame());
  show(first_, s.startFrame);
  show(last_, s.endFrame);
  show(loopFirst_, clock_.loopFirst());
  show(loopLast_, clock_.loopLast());
  time_->setText(QString::asprintf("%.3f s", clock_.time()));
  if (!rate_->lineEdit()->hasFocus()) rate_->setEditText(rateText(s.rate));
}

void TimelinePanel::applyRate() {
  std::string error;
  const auto rate = sequencer::parseFrameRate(rate_->currentText().trimmed().toStdString(), error);
  if (rate) scene::ops::setFrameRate(doc_, *rate);
  refreshFields();
}

void TimelinePanel::applyRange() {
  if (!scene::ops::setFrameRange(doc_, first_->value(), last_->value())) refreshFields();
}

bool TimelinePanel::keyTransform() {
  std::vector<scene::ops::KeyToSet> keys;
  const scene::SceneState& shown = clock_.state();
  std::string error;
  for (scene::EntityId id : selection_.ids()) {
    const scene::Entity* e = shown.find(id);
    if (!e) continue;
    for (const char* path : {"transform.translation", "transform.rotation_deg", "transform.scale"}) {
      if (!keying_.keyable(id, path)) continue;
      const auto target = scene::animationTarget(path, error);
      if (auto v = scene::currentKeyValue(*e, *target)) keys.push_back({id, *target, *v});
    }
  }
  return scene::ops::setKeys(doc_, keys, clock_.time(), std::nullopt, "Key transform");
}

}  // namespace hs::app
