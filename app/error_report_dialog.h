#pragma once
// A mesh asset's processing report (decimation error, cleaning counts, LOD
// errors, run times) in a window: shown after an import with decimation and
// reopened from the Properties panel's Mesh section. It reads the report the
// asset stores (MeshAsset::processReportJson), so a scene opened from a file
// shows the same numbers. Not modal: it can stay open beside the viewport.
#include <string>

#include <QDialog>

class QTreeWidget;

namespace hs::app {

class ErrorReportDialog : public QDialog {
  Q_OBJECT
 public:
  ErrorReportDialog(const QString& assetName, const std::string& processReportJson, QWidget* parent = nullptr);
  QTreeWidget* tree() const { return tree_; }
  const std::string& json() const { return json_; }

 private:
  QTreeWidget* tree_;
  std::string json_;
};

// Shows the report of `assetName` in a new window that deletes itself when
// closed; returns it (nullptr when the report is empty).
ErrorReportDialog* showErrorReport(QWidget* parent, const QString& assetName, const std::string& processReportJson);

}  // namespace hs::app
