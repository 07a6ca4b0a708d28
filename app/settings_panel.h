#pragma once
// The Scene Settings dock: sky, lighting, exposure, grid and anti-aliasing,
// generated from scene::settingsFields(); edits go through
// scene::ops::setSettingsField (undoable, one step per gesture).
#include <map>
#include <string>
#include <vector>

#include <QWidget>

#include "scene/document.h"
#include "scene/fields.h"

namespace hs::app {

class FieldEditor;

class SettingsPanel : public QWidget {
  Q_OBJECT
 public:
  explicit SettingsPanel(scene::Document& doc, QWidget* parent = nullptr);
  FieldEditor* editorFor(const std::string& key) const;

 private:
  void refresh();

  scene::Document& doc_;
  std::vector<std::pair<const scene::SettingsField*, FieldEditor*>> rows_;
  std::map<std::string, FieldEditor*> byKey_;
};

}  // namespace hs::app
