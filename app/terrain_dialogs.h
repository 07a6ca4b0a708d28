#pragma once
// The Terrain panel's dialogs: New Terrain (size in metres, resolution,
// height range, flat or hills), DEM import options (window, resolution,
// CRS, nodata fill, new terrain or into the selected one) and the erosion
// parameters. Each only gathers values; the panel runs the operation.
#include <QDialog>

#include "scene/terrain_jobs.h"
#include "scene/terrain_ops.h"
#include "terrain/dem_import.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLineEdit;
class QSpinBox;

namespace hs::app {

class NewTerrainDialog : public QDialog {
  Q_OBJECT
 public:
  explicit NewTerrainDialog(QWidget* parent, const QString& suggestedName);
  scene::ops::NewTerrain spec() const;

 private:
  QLineEdit* name_;
  QDoubleSpinBox *sizeX_, *sizeY_, *minH_, *maxH_;
  QComboBox *resolution_, *start_;
};

struct DemImportRequest {
  terrain::DemImportOptions options;
  bool intoSelected = false;  // replace the selected terrain's heights (resampled onto its grid)
};

class DemImportDialog : public QDialog {
  Q_OBJECT
 public:
  DemImportDialog(QWidget* parent, const QString& file, bool haveSelectedTerrain);
  DemImportRequest request() const;

 private:
  QComboBox *window_, *crs_, *fill_, *target_, *resampling_;
  QDoubleSpinBox* box_[4];
  QSpinBox* resolution_;
  QLineEdit* customCrs_;
};

class ErosionDialog : public QDialog {
  Q_OBJECT
 public:
  // `layers`: the terrain's material names (for the mask).
  ErosionDialog(QWidget* parent, bool hydraulic, const QStringList& layers);
  terrain::ThermalParams thermal() const;
  terrain::HydraulicParams hydraulic() const;
  scene::TerrainJobMask mask() const;

 private:
  bool hydraulic_;
  QSpinBox* iterations_;
  QDoubleSpinBox *talus_, *strength_, *rain_, *evaporation_, *capacity_, *erosion_, *deposition_, *dt_;
  QComboBox* mask_;
};

}  // namespace hs::app
