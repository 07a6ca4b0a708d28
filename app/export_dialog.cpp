#include "app/export_dialog.h"

#include <QCheckBox>
#include <QCloseEvent>
#include <QComboBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QSpinBox>
#include <QVBoxLayout>

#include "app/param_widgets.h"
#include "app/stereo_preview.h"
#include "render/export_job_tag.h"
#include "render/stereo_views.h"
#include "scene/camera_cut_ops.h"
#include "sequencer/ffmpeg_writer.h"
#include "sequencer/image_writer.h"
#include "sequencer/output_pattern.h"

namespace hs::app {

namespace {

struct Format {
  const char* label;
  const char* extension;
  bool png16;
  bool video;
  sequencer::VideoCodec codec;
};

const Format kFormats[] = {
    {"PNG, 8-bit", ".png", false, false, sequencer::VideoCodec::H264},
    {"PNG, 16-bit", ".png", true, false, sequencer::VideoCodec::H264},
    {"JPEG", ".jpg", false, false, sequencer::VideoCodec::H264},
    {"TIFF, 8-bit", ".tif", false, false, sequencer::VideoCodec::H264},
    {"OpenEXR, linear half float", ".exr", false, false, sequencer::VideoCodec::H264},
    {"Film: MP4, H.264", ".mp4", false, true, sequencer::VideoCodec::H264},
    {"Film: MP4, H.265", ".mp4", false, true, sequencer::VideoCodec::H265},
    {"Film: MKV, H.264", ".mkv", false, true, sequencer::VideoCodec::H264},
    {"Film: MKV, H.265", ".mkv", false, true, sequencer::VideoCodec::H265},
};

QString duration(double s) {
  if (!(s >= 0.0)) return "?";
  const qint64 t = qRound64(s);
  return t < 60 ? QString("%1 s").arg(t) : QString("%1:%2:%3").arg(t / 3600).arg((t / 60) % 60, 2, 10, QChar('0')).arg(t % 60, 2, 10, QChar('0'));
}

}  // namespace

ExportDialog::ExportDialog(scene::Document& doc, StereoPreviewSettings& stereo, QWidget* parent)
    : QDialog(parent), doc_(doc), stereo_(stereo), job_(std::make_unique<ExportJob>()) {
  setObjectName("exportDialog");
  setWindowTitle("Export Frames");
  setMinimumWidth(560);
  auto* form = new QFormLayout;
  const std::vector<ParamDecl>& decls = sequencer::exportParamDecls();
  const ParamDecl& frames = paramIn(decls, "frames");
  frames_ = new QLineEdit(this);
  frames_->setToolTip("Frames to export: 0-599, 10,20-30, 0-100x10 (every 10th); " +
                      QString::fromStdString(rangeText(sequencer::frameNumberDecl())));
  form->addRow(paramLabel(frames), frames_);
  camera_ = new QComboBox(this);
  camera_->setObjectName("exportCamera");
  form->addRow("Camera", camera_);
  const ParamDecl& layout = paramIn(decls, "layout");
  layout_ = paramCombo(layout, this);
  form->addRow(paramLabel(layout), layout_);
  auto* size = new QHBoxLayout;
  const ParamDecl& eye = paramIn(decls, "size_px");
  width_ = paramIntSpin(eye, this, 0);
  height_ = paramIntSpin(eye, this, 1);
  QSettings settings;
  width_->setValue(settings.value("export/eyeWidth", 1920).toInt());
  height_->setValue(settings.value("export/eyeHeight", 1080).toInt());
  size->addWidget(width_);
  size->addWidget(new QLabel("×", this));
  size->addWidget(height_);
  size->addWidget(new QLabel("pixels per eye", this));
  size->addStretch();
  form->addRow("Size", size);
  format_ = new QComboBox(this);
  for (const Format& f : kFormats) format_->addItem(f.label);
  form->addRow("Format", format_);
  qualityLabel_ = new QLabel(this);
  quality_ = paramIntSpin(paramIn(decls, "quality"), this);
  crf_ = paramIntSpin(paramIn(decls, "crf"), this);
  auto* quality = new QHBoxLayout;
  quality->setContentsMargins(0, 0, 0, 0);
  quality->addWidget(quality_);
  quality->addWidget(crf_);
  form->addRow(qualityLabel_, quality);
  auto* out = new QHBoxLayout;
  output_ = new QLineEdit(this);
  output_->setToolTip("Frame files: %05d (or #####) is the frame number, %v / %V the eye; a film: one file");
  auto* browse = new QPushButton("Browse…", this);
  out->addWidget(output_, 1);
  out->addWidget(browse);
  form->addRow("Output", out);
  overwrite_ = new QCheckBox("Render every frame again (otherwise valid frames already there are kept: the "
                             "export resumes)", this);
  comfort_ = new QCheckBox("Check stereo comfort (nearest and farthest parallax of each frame against the budget)", this);
  form->addRow(overwrite_);
  form->addRow(comfort_);

  bar_ = new QProgressBar(this);
  bar_->setRange(0, 1000);
  bar_->setValue(0);
  status_ = new QLabel(this);
  status_->setObjectName("exportStatus");
  status_->setWordWrap(true);
  status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  export_ = new QPushButton("Export", this);
  export_->setDefault(true);
  cancel_ = new QPushButton("Cancel", this);
  close_ = new QPushButton("Close", this);
  auto* buttons = new QHBoxLayout;
  buttons->addStretch();
  buttons->addWidget(export_);
  buttons->addWidget(cancel_);
  buttons->addWidget(close_);
  auto* v = new QVBoxLayout(this);
  v->addLayout(form);
  v->addWidget(bar_);
  v->addWidget(status_);
  v->addLayout(buttons);

  connect(format_, &QComboBox::currentIndexChanged, this, &ExportDialog::onFormatChanged);
  connect(browse, &QPushButton::clicked, this, &ExportDialog::chooseOutput);
  connect(export_, &QPushButton::clicked, this, &ExportDialog::startExport);
  connect(cancel_, &QPushButton::clicked, this, [this] {
    job_->cancel();
    status_->setText("Cancelling: the frames in flight are finished and kept…");
  });
  connect(close_, &QPushButton::clicked, this, &QDialog::close);
  connect(job_.get(), &ExportJob::progress, this, &ExportDialog::onProgress);
  connect(job_.get(), &ExportJob::finished, this, &ExportDialog::onFinished);
  auto sizeChanged = [this] { stereo_.setOutputSize(width_->value(), height_->value()); };
  connect(width_, &QSpinBox::valueChanged, this, sizeChanged);
  connect(height_, &QSpinBox::valueChanged, this, sizeChanged);
  format_->setCurrentIndex(0);
  onFormatChanged();
  setRunning(false);
  resetFromDocument();
}

void ExportDialog::resetFromDocument() {
  if (job_->isRunning()) return;
  const scene::SceneState& s = doc_.state();
  frames_->setText(QString("%1-%2").arg(s.sequence.startFrame).arg(s.sequence.endFrame));
  camera_->clear();
  const scene::EntityId shot = render::shotCamera(s);
  // With camera cuts the default follows them (id 0: StereoFrameSource
  // chooses each frame's camera); a camera picked below overrides them.
  if (!s.sequence.cuts.empty())
    camera_->addItem(QString("Camera cuts (%1)").arg(s.sequence.cuts.size()), QVariant::fromValue<qulonglong>(0));
  for (scene::EntityId id : s.cameras()) {
    const scene::Entity* e = s.find(id);
    QString label = QString::fromStdString(e->name);
    if (e->camera && e->camera->stereo == scene::Camera::Stereo::Mono) label += " (mono)";
    camera_->addItem(label, QVariant::fromValue<qulonglong>(id));
    if (id == shot && s.sequence.cuts.empty()) camera_->setCurrentIndex(camera_->count() - 1);
  }
  const QString base = doc_.filePath().isEmpty() ? QDir::home().filePath("hybridscape")
                                                 : QFileInfo(doc_.filePath()).absolutePath() + "/" +
                                                       QFileInfo(doc_.filePath()).completeBaseName();
  const Format& f = kFormats[format_->currentIndex()];
  output_->setText(f.video ? base + f.extension : base + "_frames/f_%05d" + f.extension);
}

void ExportDialog::onFormatChanged() {
  const Format& f = kFormats[std::max(0, format_->currentIndex())];
  const bool jpeg = QString(f.extension) == ".jpg";
  const std::vector<ParamDecl>& decls = sequencer::exportParamDecls();
  qualityLabel_->setText(paramLabel(paramIn(decls, f.video ? "crf" : "quality")));
  quality_->setVisible(!f.video);
  crf_->setVisible(f.video);
  quality_->setEnabled(jpeg);
  // Keep the name, change the kind.
  QString path = output_->text();
  if (path.isEmpty()) return;
  const QFileInfo info(path);
  const bool wasVideo = sequencer::videoContainerFromPath(path.toStdString()).has_value();
  if (f.video && !wasVideo) {
    QString dir = info.absolutePath();
    if (dir.endsWith("_frames")) dir.chop(7);
    path = dir + f.extension;
  } else if (!f.video && wasVideo) {
    path = info.absolutePath() + "/" + info.completeBaseName() + "_frames/f_%05d" + f.extension;
  } else {
    path = info.path() + "/" + info.completeBaseName() + f.extension;
  }
  output_->setText(QDir::cleanPath(path));
}

void ExportDialog::chooseOutput() {
  const Format& f = kFormats[format_->currentIndex()];
  if (f.video) {
    const QString file = QFileDialog::getSaveFileName(this, "Export Film", output_->text(),
                                                      QString("Film (*%1)").arg(f.extension));
    if (!file.isEmpty()) output_->setText(file);
    return;
  }
  const QString dir = QFileDialog::getExistingDirectory(this, "Folder for the Frames", QFileInfo(output_->text()).path());
  if (!dir.isEmpty()) output_->setText(dir + "/f_%05d" + f.extension);
}

void ExportDialog::setRunning(bool running) {
  export_->setEnabled(!running);
  cancel_->setEnabled(running);
  for (QWidget* w : std::initializer_list<QWidget*>{frames_, camera_, layout_, width_, height_, format_, quality_,
                                                   crf_, output_, overwrite_, comfort_})
    w->setEnabled(!running);
  if (!running) onFormatChanged();
}

bool ExportDialog::startExport() {
  if (job_->isRunning()) return false;
  auto refuse = [this](const QString& why) {
    status_->setText("<span style='color:#ff8a7a'>" + why.toHtmlEscaped() + "</span>");
    return false;
  };
  ExportRequest req;
  req.scene = doc_.state();
  sequencer::ExportSettings& s = req.settings;
  std::string error;
  const auto frames = sequencer::FrameList::parse(frames_->text().toStdString(), error);
  if (!frames || frames->empty()) return refuse("Frames: " + QString::fromStdString(frames ? "no frames" : error));
  if (!sequencer::checkFrameBounds(*frames, "Frames", error)) return refuse(QString::fromStdString(error));
  s.frames = *frames;
  s.rate = req.scene.sequence.rate;
  s.layout = sequencer::layoutFromName(layout_->currentData().toString().toStdString())
                 .value_or(sequencer::StereoLayout::SideBySide);
  s.eyeWidth = width_->value();
  s.eyeHeight = height_->value();
  const Format& f = kFormats[format_->currentIndex()];
  s.output = QDir::cleanPath(output_->text().trimmed()).toStdString();
  if (f.video) {
    if (!sequencer::videoContainerFromPath(s.output)) return refuse("Output: a film must end in .mp4 or .mkv");
    if (s.layout == sequencer::StereoLayout::Separate) return refuse("A film holds one picture a frame: choose a layout other than separate");
    if (!sequencer::ffmpegAvailable()) return refuse("A film needs ffmpeg, which is not installed (apt-get install ffmpeg)");
    s.video.codec = f.codec;
    s.video.crf = crf_->value();
  } else {
    if (!sequencer::OutputPattern::parse(s.output, error)) return refuse("Output: " + QString::fromStdString(error));
    if (!sequencer::imageFormatFromPath(s.output)) return refuse("Output: use .png, .jpg, .tif or .exr");
    s.image.jpegQuality = quality_->value();
    s.image.png16 = f.png16;
  }
  s.resume = !overwrite_->isChecked();
  req.frame.camera = camera_->currentData().toULongLong();
  req.frame.displayBits16 = f.png16;
  if (comfort_->isChecked()) {
    req.frame.comfort = sequencer::ComfortOptions{};
    req.frame.comfort->budget = stereo_.budget();
    s.resume = false;  // kept frames would not be checked
  }
  if (req.frame.camera == scene::kNoEntity && req.scene.sequence.cuts.empty())
    return refuse("The scene has no camera to export through");
  if (req.frame.camera == scene::kNoEntity) {
    if (const std::string p = scene::cutsProblem(req.scene); !p.empty())
      return refuse(QString("The camera cuts cannot be rendered: %1").arg(QString::fromStdString(p)));
  }
  s.jobTag = render::exportJobTag(req.scene, req.frame.camera, s, req.frame);
  total_ = s.frames.count();
  bar_->setValue(0);
  status_->setText(QString("Starting: %1 frames…").arg(total_));
  setRunning(true);
  job_->start(std::move(req));
  return true;
}

void ExportDialog::onProgress(const sequencer::ExportProgress& p) {
  const int64_t done = p.written + p.kept;
  bar_->setValue(p.total > 0 ? int(1000 * done / p.total) : 0);
  status_->setText(QString("Frame %1 — %2 of %3 done (%4 kept from before) — %5 fps — elapsed %6 — ETA %7")
                       .arg(p.lastFrame)
                       .arg(done)
                       .arg(p.total)
                       .arg(p.kept)
                       .arg(p.framesPerSecond, 0, 'f', 2)
                       .arg(duration(p.elapsedSeconds), p.etaSeconds >= 0 ? duration(p.etaSeconds) : QString("?")));
}

void ExportDialog::onFinished() {
  setRunning(false);
  const ExportOutcome& o = job_->outcome();
  QString message;
  bool ok = false;
  if (!o.setupError.empty()) {
    message = QString::fromStdString(o.setupError);
  } else if (o.result.cancelled) {
    message = QString("Export cancelled after %1 frame(s) (%2 kept from before); export again to resume")
                  .arg(o.result.written)
                  .arg(o.result.kept);
  } else if (!o.result.ok) {
    message = "Export failed: " + QString::fromStdString(o.result.error);
    for (const std::string& n : o.result.notes) message += "\n" + QString::fromStdString(n);
  } else {
    ok = true;
    message = QString("Exported %1 frame(s), kept %2, of %3 in %4 → %5")
                  .arg(o.result.written)
                  .arg(o.result.kept)
                  .arg(o.result.total)
                  .arg(duration(o.result.seconds), output_->text());
  }
  if (!o.comfort.empty()) {
    std::vector<int64_t> bad = sequencer::framesOutsideBudget(o.comfort);
    message += QString("\nComfort: %1 of %2 frame(s) outside the budget %3 .. %4%5")
                   .arg(bad.size())
                   .arg(o.comfort.size())
                   .arg(formatParallax(stereo_.budget().nearest), formatParallax(stereo_.budget().farthest))
                   .arg(bad.empty() ? QString() : ": " + QString::fromStdString(sequencer::FrameList::fromFrames(bad).toString()));
  }
  for (const std::string& w : o.warnings) message += "\nWarning: " + QString::fromStdString(w);
  if (ok) bar_->setValue(1000);
  status_->setText(message.toHtmlEscaped().replace("\n", "<br>"));
  emit exportFinished(message, ok);
}

QString ExportDialog::statusText() const { return status_->text(); }

void ExportDialog::closeEvent(QCloseEvent* e) {
  // Closing the window does not stop a running export (it goes on; reopen
  // to watch it). Cancel stops it.
  QDialog::closeEvent(e);
}

void ExportDialog::reject() { hide(); }

}  // namespace hs::app
