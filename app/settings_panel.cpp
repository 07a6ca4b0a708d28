#include "app/settings_panel.h"

#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QLayout>
#include <QScrollArea>
#include <QVBoxLayout>

#include "app/background_job.h"
#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "app/prompts.h"
#include "app/status_bar.h"
#include "app/timeline_clock.h"
#include "app/timeline_keying.h"
#include "scene/color_lut.h"
#include "scene/ocio_config.h"
#include "scene/object_tracks.h"
#include "scene/operations.h"

namespace hs::app {

bool SettingsPanel::inPostPanel(const std::string& key) { return key == "tonemap" || key.rfind("post.", 0) == 0; }

SettingsPanel::SettingsPanel(scene::Document& doc, QWidget* parent, SettingsSection section)
    : QWidget(parent), doc_(doc) {
  const bool post = section == SettingsSection::Post;
  setObjectName(post ? "postPanel" : "settingsPanel");
  auto* content = new QWidget;
  auto* form = new QFormLayout(content);
  form->setContentsMargins(8, 8, 8, 8);
  form->setLabelAlignment(Qt::AlignRight | Qt::AlignVCenter);
  form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  form->setVerticalSpacing(4);
  auto addHeading = [&](const char* title, const char* name, const char* tip) {
    auto* heading = new QLabel(title, content);
    heading->setObjectName(name);
    heading->setStyleSheet("QLabel { font-weight: bold; margin-top: 8px; }");
    heading->setToolTip(tip);
    form->addRow(heading);
  };
  if (post) {
    auto* intro = new QLabel(
        "The chain after the scene's light, in order: exposure (manual in Scene Settings, automatic here), bloom, "
        "chromatic aberration, the tone map, the grade, the LUT, the vignette, grain, anti-aliasing (Scene Settings), then the "
        "stylised effects. Each runs only when enabled. View > Post Before/After compares.",
        content);
    intro->setObjectName("postIntro");
    intro->setWordWrap(true);
    intro->setStyleSheet("QLabel { color: #a9aaae; }");
    form->addRow(intro);
  }
  for (const auto& f : scene::settingsFields()) {
    if (inPostPanel(f.key) != post) continue;
    // Depth of field and transparency: blocks of their own (their fields
    // follow in the declarations, scene/fields.cpp).
    if (f.key == "depth_of_field")
      addHeading("Depth of field", "dofHeading",
                 "The camera's lens (focal length, f-stop, focus distance in Properties); "
                 "View > Pick Focus Distance sets the focus from a click in the viewport");
    if (f.key == "post.bloom.enabled")
      addHeading("Effects", "postHeading",
                 "In the chain's order; the tone map above runs between chromatic aberration and the grade");
    if (f.key == "post.kuwahara.enabled")
      addHeading("Stylised effects", "stylisedHeading",
                 "After the chain and anti-aliasing, on the display image, in this order: Kuwahara, comic (with "
                 "its outlines) or outlines, CRT, ordered dithering, stippling, error diffusion");
    if (f.key == "transparency")
      addHeading("Transparency", "oitHeading",
                 "How translucent materials (opacity under 1) are composited; View > Depth Complexity "
                 "shows translucent fragments per pixel");
    FieldEditor* ed = createFieldEditor(specOf(f, "settings." + f.key), content);
    const scene::SettingsField* field = &f;
    ed->setOnEdited([this, field](const scene::FieldValue& value, int component, const QString& mergeKey) {
      scene::FieldValue v = value;
      if (component >= 0) {
        glm::dvec3 current = std::get<glm::dvec3>(field->get(shown().settings));
        current[component] = std::get<glm::dvec3>(value)[component];
        v = current;
      }
      // With keying on every edit has a merge key, so a key it sets joins its step.
      const QString key = mergeKey.isEmpty() && keying_ ? QString("settings-%1").arg(++editCounter_) : mergeKey;
      scene::ops::setSettingsField(doc_, *field, v, key);
      // An animated field keeps the edit as a key at this frame; with Auto Key, any field.
      if (keying_) keying_->afterEdit({scene::settingsTarget()}, {std::string(scene::kSettingsTrackPrefix) + field->key}, key);
    });
    auto* label = new QLabel(QString::fromStdString(f.label), content);
    label->setStyleSheet("QLabel { color: #a9aaae; }");
    QWidget* row = editorRow(content, ed);
    form->addRow(label, row);
    rows_.emplace_back(field, ed);
    byKey_[f.key] = ed;
    rowOf_[f.key] = row;
    if (f.key == "post.lut.intensity") addLutRow(content, form);
    if (f.key == "post.view_transform.enabled") addOcioRow(content, form);
    if (f.key == "oit_memory_mb") {  // the last transparency field: what the last frame used
      oitStats_ = new QLabel(content);
      oitStats_->setObjectName("oitStats");
      oitStats_->setWordWrap(true);
      oitStats_->setStyleSheet("QLabel { color: #a9aaae; }");
      auto* statsLabel = new QLabel("Last frame", content);
      statsLabel->setStyleSheet("QLabel { color: #a9aaae; }");
      form->addRow(statsLabel, oitStats_);
      showTransparencyStats(render::OitStats{});
    }
  }
  putInScrollArea(this, content);
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.settings || c.reset) refresh();
  });
  refresh();
}

void SettingsPanel::addLutRow(QWidget* content, QFormLayout* form) {
  // The stored LUT (post.lut) with Import LUT... and Remove: a file, not a
  // value, so not a field editor (scene/color_lut.h).
  auto* row = new QWidget(content);
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  lutName_ = new QLabel(row);
  lutName_->setObjectName("lutName");
  auto* import = new QPushButton("Import LUT...", row);
  import->setObjectName("lutImport");
  import->setToolTip(QString::fromStdString(scene::lutImportOperation().description));
  lutRemove_ = new QPushButton("Remove", row);
  lutRemove_->setObjectName("lutRemove");
  lutRemove_->setToolTip(QString::fromStdString(scene::lutClearOperation().description));
  layout->addWidget(lutName_, 1);
  layout->addWidget(import);
  layout->addWidget(lutRemove_);
  connect(import, &QPushButton::clicked, this, [this] {
    if (!prompts_) return;
    QString filter = "LUT files (";
    for (const std::string& e : scene::lutFileExtensions()) filter += QString(" *.%1").arg(QString::fromStdString(e));
    filter += ");;All files (*)";
    const QString path = prompts_().askOpenFile(this, "Import LUT", QString(), filter);
    if (!path.isEmpty()) importLut(path);
  });
  connect(lutRemove_, &QPushButton::clicked, this, [this] { scene::ops::setLut(doc_, {}); });
  auto* label = new QLabel("LUT file", content);
  label->setStyleSheet("QLabel { color: #a9aaae; }");
  form->addRow(label, row);
}

void SettingsPanel::addOcioRow(QWidget* content, QFormLayout* form) {
  // The stored OpenColorIO config (post.ocio_config) with Import OCIO
  // config... and Remove; its displays and views fill the Display and View
  // boxes below (refreshOcioChoices).
  auto* row = new QWidget(content);
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  ocioName_ = new QLabel(row);
  ocioName_->setObjectName("ocioName");
  auto* import = new QPushButton("Import OCIO config...", row);
  import->setObjectName("ocioImport");
  import->setToolTip(QString::fromStdString(scene::ocioImportOperation().description));
  ocioRemove_ = new QPushButton("Remove", row);
  ocioRemove_->setObjectName("ocioRemove");
  ocioRemove_->setToolTip(QString::fromStdString(scene::ocioClearOperation().description));
  layout->addWidget(ocioName_, 1);
  layout->addWidget(import);
  layout->addWidget(ocioRemove_);
  connect(import, &QPushButton::clicked, this, [this] {
    if (!prompts_) return;
    const QString path =
        prompts_().askOpenFile(this, "Import OpenColorIO config", QString(), "OpenColorIO configs (*.ocio);;All files (*)");
    if (!path.isEmpty()) importOcioConfig(path);
  });
  connect(ocioRemove_, &QPushButton::clicked, this, [this] { scene::ops::setOcioConfig(doc_, {}); });
  auto* label = new QLabel("OCIO config", content);
  label->setStyleSheet("QLabel { color: #a9aaae; }");
  form->addRow(label, row);
}

bool SettingsPanel::importOcioConfig(const QString& path) {
  // A config's search paths can hold hundreds of MB of LUTs: read on a
  // worker, with progress and Cancel.
  auto error = std::make_shared<std::string>();
  auto read = std::make_shared<std::optional<scene::OcioConfigData>>();
  {
    BackgroundJob job(this, "Import OpenColorIO config", QString("Reading %1…").arg(QFileInfo(path).fileName()), true);
    job.start([read, error, file = path.toStdString()](const Progress& p) {
      *read = scene::readOcioConfig(file, *error, &p);
    });
    job.waitForFinished();
    if (job.cancelRequested()) return false;  // the user's choice: no message
  }
  const std::optional<scene::OcioConfigData>& config = *read;
  if (!config) {
    if (prompts_) prompts_().showError(this, "Import OpenColorIO config", QString::fromStdString(*error));
    return false;
  }
  scene::ops::setOcioConfig(doc_, *config);
  return true;
}

void SettingsPanel::refreshOcioChoices() {
  FieldEditor* display = editorFor("post.view_transform.display");
  FieldEditor* view = editorFor("post.view_transform.view");
  if (!display || !view) return;
  const scene::PostSettings& post = shown().settings.post;
  std::vector<std::pair<std::string, std::string>> displays, views;
  if (!post.ocioConfig.empty() && post.ocioConfig.loaded()) {
    const scene::OcioConfigSummary s = scene::ocioSummary(post.ocioConfig);
    const std::string chosen = post.display.empty() ? s.defaultDisplay : post.display;
    if (s.error.empty()) displays.push_back({"", "Default (" + s.defaultDisplay + ")"});
    for (const scene::OcioDisplay& d : s.displays) {
      displays.push_back({d.name, d.name});
      if (d.name != chosen) continue;
      views.push_back({"", "Default (" + d.defaultView + ")"});
      for (const std::string& v : d.views) views.push_back({v, v});
    }
  }
  display->setChoices(displays);
  view->setChoices(views);
}

bool SettingsPanel::importLut(const QString& path) {
  // A LUT may be hundreds of MB of text: read and checked on a worker.
  auto error = std::make_shared<std::string>();
  auto read = std::make_shared<std::optional<scene::LutData>>();
  {
    BackgroundJob job(this, "Import LUT", QString("Reading %1…").arg(QFileInfo(path).fileName()), true);
    job.start([read, error, file = path.toStdString()](const Progress&) { *read = scene::readLutFile(file, *error); });
    job.waitForFinished();
    if (job.cancelRequested()) return false;
  }
  const std::optional<scene::LutData>& lut = *read;
  if (!lut) {
    if (prompts_) prompts_().showError(this, "Import LUT", QString::fromStdString(*error));
    return false;
  }
  scene::ops::setLut(doc_, *lut);
  return true;
}

FieldEditor* SettingsPanel::editorFor(const std::string& key) const {
  auto it = byKey_.find(key);
  return it == byKey_.end() ? nullptr : it->second;
}

void SettingsPanel::enableKeying(Keying& keying, TimelineClock& clock) {
  keying_ = &keying;
  clock_ = &clock;
  for (const auto& [key, row] : rowOf_) {
    const std::string path = std::string(scene::kSettingsTrackPrefix) + key;
    std::string error;
    if (!scene::animationTarget(path, error)) continue;  // choices and on/off lists: not animatable
    auto* button = new KeyButton(
        keying, [] { return std::vector<uint64_t>{scene::settingsTarget()}; }, clock, path, row);
    row->layout()->addWidget(button);
    keyButtons_[key] = button;
  }
  connect(&clock, &TimelineClock::stateChanged, this, &SettingsPanel::refresh);
  refresh();
}

void SettingsPanel::showTransparencyStats(const render::OitStats& stats) {
  if (oitStats_) oitStats_->setText(oitSummary(stats));
}

KeyButton* SettingsPanel::keyButtonFor(const std::string& key) const {
  auto it = keyButtons_.find(key);
  return it == keyButtons_.end() ? nullptr : it->second;
}

const scene::SceneState& SettingsPanel::shown() const { return clock_ ? clock_->state() : doc_.state(); }

void SettingsPanel::refresh() {
  for (const auto& [field, editor] : rows_) editor->setValue(field->get(shown().settings));
  if (lutName_) {
    const scene::LutData& lut = doc_.state().settings.post.lut;
    lutName_->setText(lut.empty() ? QString("none")
                                  : QString("%1 (%2)").arg(QString::fromStdString(lut.fileName),
                                                           formatBytes(lut.bytes ? lut.bytes->size() : 0)));
    lutRemove_->setEnabled(!lut.empty());
  }
  if (ocioName_) {
    const scene::OcioConfigData& config = doc_.state().settings.post.ocioConfig;
    size_t bytes = 0;
    for (const scene::OcioFile& f : config.files) bytes += f.bytes ? f.bytes->size() : 0;
    ocioName_->setText(config.empty() ? QString("none")
                                      : QString("%1 (%2 files, %3)")
                                            .arg(QString::fromStdString(config.fileName))
                                            .arg(config.files.size())
                                            .arg(formatBytes(bytes)));
    ocioRemove_->setEnabled(!config.empty());
    refreshOcioChoices();
  }
}

}  // namespace hs::app
