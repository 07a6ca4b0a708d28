// hybridscape-cli terrain import
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/terrain_cli.h"
#include "scene/terrain_jobs.h"
#include "scene/terrain_ops.h"
#include "terrain/dem_import.h"

namespace hs::cli {
namespace {

bool parseWindow(const std::string& text, terrain::DemWindow& w, std::string& error) {
  const auto colon = text.find(':');
  const std::string kind = colon == std::string::npos ? "pixels" : text.substr(0, colon);
  const std::string rest = colon == std::string::npos ? text : text.substr(colon + 1);
  if (kind == "pixels") w.units = terrain::DemWindow::Units::Pixels;
  else if (kind == "crs") w.units = terrain::DemWindow::Units::SourceCrs;
  else if (kind == "lonlat") w.units = terrain::DemWindow::Units::LonLat;
  else {
    error = "--window kind '" + kind + "' is not pixels, crs or lonlat";
    return false;
  }
  double v[4];
  size_t start = 0;
  for (int i = 0; i < 4; ++i) {
    const size_t comma = rest.find(',', start);
    if ((i < 3) != (comma != std::string::npos)) {
      error = "--window takes [pixels:|crs:|lonlat:]MINX,MINY,MAXX,MAXY";
      return false;
    }
    double a, b;
    std::string e;
    if (!terrain_cli::parsePair(rest.substr(start, (i < 3 ? comma : rest.size()) - start) + ",0", a, b, e)) {
      error = "--window: '" + rest + "' is not four numbers";
      return false;
    }
    v[i] = a;
    start = comma + 1;
  }
  if (!(v[2] > v[0] && v[3] > v[1])) {
    error = "--window: MAXX must exceed MINX and MAXY must exceed MINY";
    return false;
  }
  w.minX = v[0];
  w.minY = v[1];
  w.maxX = v[2];
  w.maxY = v[3];
  return true;
}

}  // namespace

int runTerrainImport(int argc, char** argv) {
  const char* cmd = "terrain import";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0,
                 {{"window"}, {"resolution"}, {"crs"}, {"name"}, {"into"}, {"fill"}, {"resampling"}, {"nodata"}}, args,
                 error))
    return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli terrain import <dem> <scene.hscene> [options]\n\n"
        "Imports an elevation model (GeoTIFF, DTED, SRTM .hgt, ASCII grid, anything GDAL\n"
        "reads) as a new terrain at its true ground size in metres, keeping its CRS and\n"
        "georeferenced origin, and saves the scene. Nodata is filled and reported.\n\n"
        "  --window [pixels:|crs:|lonlat:]MINX,MINY,MAXX,MAXY   import only this part\n"
        "                    (pixels: columns/rows, row 0 = the file's first row)\n"
        "  --resolution N    resample to N (or WxH) samples; default: the DEM's own\n"
        "  --crs auto|keep|local|utm|EPSG:n|WKT   target CRS (default auto: degrees,\n"
        "                    Web Mercator and feet are reprojected to a local transverse\n"
        "                    Mercator; utm: the UTM zone of the centre)\n"
        "  --resampling nearest|bilinear|cubic   (default bilinear)\n"
        "  --fill diffusion|idw   nodata filling (default diffusion)\n"
        "  --nodata V        treat V as nodata (overrides the file's value)\n"
        "  --name NAME       entity and terrain name (default: the file's base name)\n"
        "  --into NAME       replace the heights of existing terrain NAME instead: the DEM\n"
        "                    is resampled onto that terrain's grid (one undo step)\n");
    return 0;
  }
  if (args.positional.size() != 2) return usage(cmd, "expected <dem> <scene.hscene>");
  const std::string dem = args.positional[0], path = args.positional[1];
  terrain::DemImportOptions o;
  if (auto w = args.get("window"))
    if (!parseWindow(*w, o.window, error)) return usage(cmd, error);
  if (auto r = args.get("resolution"))
    if (!terrain_cli::parseSamples(*r, o.samplesX, o.samplesY, error)) return usage(cmd, error);
  if (auto c = args.get("crs")) {
    if (*c == "auto") o.crs = terrain::DemCrsMode::Auto;
    else if (*c == "keep") o.crs = terrain::DemCrsMode::KeepSource;
    else if (*c == "local") o.crs = terrain::DemCrsMode::LocalTransverseMercator;
    else if (*c == "utm") o.crs = terrain::DemCrsMode::Utm;
    else if (!c->empty()) {
      o.crs = terrain::DemCrsMode::Custom;
      o.customCrs = *c;
    } else return usage(cmd, "--crs needs a value");
  }
  if (auto r = args.get("resampling")) {
    if (*r == "nearest") o.resampling = terrain::Resampling::Nearest;
    else if (*r == "bilinear") o.resampling = terrain::Resampling::Bilinear;
    else if (*r == "cubic") o.resampling = terrain::Resampling::Cubic;
    else return usage(cmd, "--resampling takes nearest, bilinear or cubic");
  }
  if (auto f = args.get("fill")) {
    if (*f == "diffusion") o.fill = terrain::NodataFill::Diffusion;
    else if (*f == "idw") o.fill = terrain::NodataFill::InverseDistance;
    else return usage(cmd, "--fill takes diffusion or idw");
  }
  if (auto n = args.get("nodata")) {
    double v, unused;
    if (!terrain_cli::parsePair(*n + ",0", v, unused, error)) return usage(cmd, "--nodata takes a number");
    o.nodataValue = v;
  }

  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return fail(cmd, error);
  Progress progress = terminalProgress("Importing " + std::filesystem::path(dem).filename().string());
  std::string line;
  if (auto into = args.get("into")) {
    const scene::EntityId e = scene::ops::findTerrainEntity(doc.state(), *into, error);
    if (e == scene::kNoEntity) return fail(cmd, error);
    auto job = scene::TerrainJob::demInto(doc, doc.state().find(e)->terrain->terrain, dem, o);
    if (!job->valid()) return fail(cmd, job->invalidReason());
    job->run(&progress);
    const scene::TerrainJobOutcome out = job->commit(doc);
    for (const auto& w : out.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (!out.ok) return fail(cmd, out.error);
    line = out.summary;
  } else {
    terrain::DemImportResult r = terrain::importDem(dem, o, &progress);
    for (const auto& w : r.report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (!r.ok()) return fail(cmd, r.error.empty() ? dem + ": could not be imported" : r.error);
    const std::string name = args.get("name").value_or(std::filesystem::path(dem).stem().string());
    if (name.empty()) return usage(cmd, "--name must not be empty");
    if (doc.state().findByName(name) != scene::kNoEntity)
      return fail(cmd, "the scene already has an entity named '" + name + "' (choose another with --name)");
    line = terrain::summary(r.report);
    if (scene::ops::addTerrainFromHeightfield(doc, std::move(*r.heightfield), name, error) == scene::kNoEntity)
      return fail(cmd, error);
  }
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return fail(cmd, error);
  std::printf("%s\n%s\n", line.c_str(), saved.c_str());
  return 0;
}

}  // namespace hs::cli
