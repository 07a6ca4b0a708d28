#include "app/error_report_dialog.h"

#include <QApplication>
#include <QClipboard>
#include <QDialogButtonBox>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "scene/mesh_report_text.h"

namespace hs::app {

ErrorReportDialog::ErrorReportDialog(const QString& assetName, const Json& processReport, QWidget* parent)
    : QDialog(parent), report_(processReport) {
  setObjectName("errorReportDialog");
  setWindowTitle("Mesh Report — " + assetName);
  auto* layout = new QVBoxLayout(this);
  const std::string summary = scene::processReportSummary(processReport);
  auto* head = new QLabel(QString("<b>%1</b><br>%2").arg(assetName.toHtmlEscaped(),
                                                          QString::fromStdString(summary).toHtmlEscaped()),
                          this);
  head->setWordWrap(true);
  head->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(head);

  tree_ = new QTreeWidget(this);
  tree_->setObjectName("reportTree");
  tree_->setColumnCount(3);
  tree_->setHeaderLabels({"", "Value", "JSON field"});
  tree_->setRootIsDecorated(false);
  tree_->setSelectionMode(QAbstractItemView::ExtendedSelection);
  for (const scene::ReportSection& s : scene::processReportSections(processReport)) {
    auto* section = new QTreeWidgetItem(tree_, {QString::fromStdString(s.title)});
    QFont bold = section->font(0);
    bold.setBold(true);
    section->setFont(0, bold);
    section->setFirstColumnSpanned(true);
    for (const scene::ReportRow& r : s.rows) {
      auto* row = new QTreeWidgetItem(section, {QString::fromStdString(r.label), QString::fromStdString(r.value),
                                                QString::fromStdString(r.key)});
      row->setForeground(2, QColor(0x8f, 0x90, 0x95));
    }
    section->setExpanded(true);
  }
  tree_->header()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  tree_->header()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
  layout->addWidget(tree_, 1);

  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
  QPushButton* copy = buttons->addButton("Copy as JSON", QDialogButtonBox::ActionRole);
  connect(copy, &QPushButton::clicked, this, [this] {
    QApplication::clipboard()->setText(QString::fromStdString(writeJson(report_)));
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::close);
  layout->addWidget(buttons);
  resize(640, 620);
}

ErrorReportDialog* showErrorReport(QWidget* parent, const QString& assetName, const Json& processReport) {
  if (processReport.is_null()) return nullptr;
  auto* d = new ErrorReportDialog(assetName, processReport, parent);
  d->setAttribute(Qt::WA_DeleteOnClose);
  d->show();
  d->raise();
  return d;
}

}  // namespace hs::app
