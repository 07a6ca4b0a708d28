#pragma once
// The Terrain panel's dialogs: New Terrain (size in metres, resolution,
// height range, flat or hills), DEM import options (window, resolution,
// CRS, nodata fill, new terrain or into the selected one) and the erosion
// parameters. Each only gathers values; the panel runs the operation.
#include <map>
#include <string>

#include <QDialog>

#include "scene/terrain_jobs.h"
#include "scene/terrain_ops.h"
#include "terrain/dem_import.h"

class QAbstractSpinBox;
class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLineEdit;
class QSpinBox;

namespace hs::app {

// The fields are `terrain new`'s declared parameters (size, resolution,
// height range; scene::ops::terrainNewOperation).
class NewTerrainDialog : public QDialog {
  Q_OBJECT
 public:
  explicit NewTerrainDialog(QWidget* parent, const QString& suggestedName);
  scene::ops::NewTerrain spec() const;

 private:
  QLineEdit* name_;
  QDoubleSpinBox *sizeX_, *sizeY_, *minH_, *maxH_;
  QSpinBox *samplesX_, *samplesY_;
  QComboBox* start_;
};

struct DemImportRequest {
  terrain::DemImportOptions options;
  bool intoSelected = false;  // replace the selected terrain's heights (resampled onto its grid)
};

// The fields are DemImportOptions' declared parameters (window box,
// resolution, resampling, fill; terrain::demImportParamDecls).
class DemImportDialog : public QDialog {
  Q_OBJECT
 public:
  DemImportDialog(QWidget* parent, const QString& file, bool haveSelectedTerrain);
  DemImportRequest request() const;

 private:
  QComboBox *window_, *crs_, *fill_, *target_, *resampling_;
  QDoubleSpinBox* box_[4];
  QCheckBox* resample_;
  QSpinBox *samplesX_, *samplesY_;
  QLineEdit* customCrs_;
};

// The fields are the solver's declared parameters (thermalParamDecls,
// hydraulicParamDecls): the ones `terrain erode` offers, with its ranges.
class ErosionDialog : public QDialog {
  Q_OBJECT
 public:
  // `layers`: the terrain's material names (for the mask).
  ErosionDialog(QWidget* parent, bool hydraulic, const QStringList& layers);
  terrain::ThermalParams thermal() const;
  terrain::HydraulicParams hydraulic() const;
  scene::TerrainJobMask mask() const;

 private:
  double value(const char* key) const;

  bool hydraulic_;
  std::map<std::string, QAbstractSpinBox*> fields_;  // by parameter key
  QComboBox* mask_;
};

}  // namespace hs::app
