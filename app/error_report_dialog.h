#pragma once
// A mesh asset's processing report (decimation error, cleaning counts, LOD
// errors, run times) in a window: shown after an import with decimation and
// reopened from the Properties panel's Mesh section. It reads the report the
// asset stores (MeshAsset::processReport), so a scene opened from a file
// shows the same numbers. Not modal: it can stay open beside the viewport.
#include <QDialog>

#include "core/json.h"

class QTreeWidget;

namespace hs::app {

class ErrorReportDialog : public QDialog {
  Q_OBJECT
 public:
  ErrorReportDialog(const QString& assetName, const Json& processReport, QWidget* parent = nullptr);
  QTreeWidget* tree() const { return tree_; }
  const Json& report() const { return report_; }

 private:
  QTreeWidget* tree_;
  Json report_;
};

// Shows the report of `assetName` in a new window that deletes itself when
// closed; returns it (nullptr when there is no report).
ErrorReportDialog* showErrorReport(QWidget* parent, const QString& assetName, const Json& processReport);

}  // namespace hs::app
