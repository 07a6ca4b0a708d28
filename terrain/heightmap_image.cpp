#include "terrain/heightmap_image.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/image_io.h"
#include "terrain/dem_export.h"
#include "terrain/raw_sidecar.h"

namespace hs::terrain {
namespace {

std::string lowerExt(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

bool parseDouble(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end && *end == '\0' && std::isfinite(out);
}

void putMetadata(image_io::Spec& spec, const Heightfield& hf, const HeightRange* range) {
  auto put = [&](const char* name, std::string value) { spec.text.emplace_back(name, std::move(value)); };
  if (range) {
    put("hs:height_min", num(double(range->min)));
    put("hs:height_max", num(double(range->max)));
  }
  put("hs:spacing_x", num(hf.spacing().x));
  put("hs:spacing_y", num(hf.spacing().y));
  put("hs:origin_x", num(hf.origin().x));
  put("hs:origin_y", num(hf.origin().y));
  put("hs:origin_z", num(hf.origin().z));
  if (hf.geo().valid()) put("hs:crs_wkt", hf.geo().crsWkt);
  put("ImageDescription", "Hybridscape heightmap; row 0 = north; see hs:* for range and georeferencing");
}

Status writeImage(const std::string& path, const image_io::Spec& spec, image_io::PixelType type, const void* data) {
  if (std::string why; !image_io::writeFile(path, spec, type, data, why)) return Status::failure(path + ": " + why);
  return {};
}

std::vector<uint16_t> quantise(const std::vector<float>& h, HeightRange r, size_t& clamped) {
  std::vector<uint16_t> q(h.size());
  const double span = double(r.max) - double(r.min);
  clamped = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    double t = span > 0.0 ? (double(h[i]) - double(r.min)) / span : 0.0;
    if (t < 0.0 || t > 1.0) ++clamped;
    t = std::clamp(t, 0.0, 1.0);
    q[i] = uint16_t(std::lround(t * 65535.0));
  }
  return q;
}

// Builds a heightfield from north-first rows and optional georeferencing.
Result<Heightfield> build(const std::string& path, std::vector<float> northFirst, int w, int h, glm::dvec2 spacing,
                          glm::dvec3 origin, const std::string& wkt) {
  if (w < 2 || h < 2)
    return Result<Heightfield>::failure(path + ": is " + std::to_string(w) + " x " + std::to_string(h) +
                                        "; a terrain needs at least 2 x 2 samples");
  if (w > kMaxSamples || h > kMaxSamples)
    return Result<Heightfield>::failure(path + ": is " + std::to_string(w) + " x " + std::to_string(h) +
                                        "; a terrain has at most 8193 samples per side (import it as a DEM to resample)");
  HeightfieldDesc d;
  d.samplesX = w;
  d.samplesY = h;
  d.sizeMetres = spacing * glm::dvec2(w - 1, h - 1);
  d.origin = origin;
  d.geo.crsWkt = wkt;
  auto hf = Heightfield::create(d);
  if (!hf) return Result<Heightfield>::failure(path + ": " + hf.error());
  Heightfield f = hf.take();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = northFirst[size_t(h - 1 - y) * size_t(w) + size_t(x)];
      f.heights().set(x, y, std::isfinite(v) ? v : 0.0f);
    }
  f.updateAllBounds();
  return f;
}

}  // namespace

std::optional<HeightmapFormat> heightmapFormatFor(const std::string& path) {
  const std::string e = lowerExt(path);
  if (e == ".png") return HeightmapFormat::Png16;
  if (e == ".exr") return HeightmapFormat::Exr32;
  if (e == ".tif" || e == ".tiff") return HeightmapFormat::GeoTiff;
  if (e == ".r16" || e == ".raw") return HeightmapFormat::RawR16;
  return std::nullopt;
}

namespace detail {
std::vector<float> heightsNorthFirst(const Heightfield& hf) {
  const int w = hf.samplesX(), h = hf.samplesY();
  std::vector<float> out(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out[size_t(h - 1 - y) * size_t(w) + size_t(x)] = hf.at(x, y);
  return out;
}
}  // namespace detail

Result<HeightExportReport> exportHeightmap(const Heightfield& hf, const std::string& path,
                                           const HeightExportOptions& opt) {
  using R = Result<HeightExportReport>;
  const auto fmt = heightmapFormatFor(path);
  if (!fmt) return R::failure(path + ": unknown heightmap format (use .png, .exr, .tif or .r16)");
  if (hf.samplesX() < 2) return R::failure(path + ": the terrain is empty");
  HeightExportReport rep;
  rep.file = path;
  rep.width = hf.samplesX();
  rep.height = hf.samplesY();
  HeightRange range = opt.range ? *opt.range : hf.range();
  if (!std::isfinite(range.min) || !std::isfinite(range.max) || range.max < range.min)
    return R::failure(path + ": the height range " + num(double(range.min)) + ".." + num(double(range.max)) +
                      " is not valid");
  const std::vector<float> heights = detail::heightsNorthFirst(hf);
  const int w = hf.samplesX(), h = hf.samplesY();
  switch (*fmt) {
    case HeightmapFormat::GeoTiff: {
      Status s = exportGeoTiff(hf, path, opt.holesAsNodata);
      if (!s) return R::failure(s.error);
      return rep;
    }
    case HeightmapFormat::Exr32: {
      image_io::Spec spec = image_io::Spec::of(w, h, 1, image_io::PixelType::Float);
      spec.channelNames = {"Y"};
      spec.text.emplace_back("compression", "zip");
      putMetadata(spec, hf, nullptr);
      Status s = writeImage(path, spec, image_io::PixelType::Float, heights.data());
      if (!s) return R::failure(s.error);
      return rep;
    }
    case HeightmapFormat::Png16: {
      rep.range = range;
      rep.quantisationStep = (double(range.max) - double(range.min)) / 65535.0;
      const auto q = quantise(heights, range, rep.clampedSamples);
      image_io::Spec spec = image_io::Spec::of(w, h, 1, image_io::PixelType::UInt16);
      spec.text.emplace_back("oiio:ColorSpace", "Linear");
      putMetadata(spec, hf, &range);
      Status s = writeImage(path, spec, image_io::PixelType::UInt16, q.data());
      if (!s) return R::failure(s.error);
      return rep;
    }
    case HeightmapFormat::RawR16: {
      rep.range = range;
      rep.quantisationStep = (double(range.max) - double(range.min)) / 65535.0;
      const auto q = quantise(heights, range, rep.clampedSamples);
      const std::string tmp = path + ".part";
      {
        std::ofstream f(tmp, std::ios::binary);
        if (!f) return R::failure(path + ": cannot create the file");
        f.write(reinterpret_cast<const char*>(q.data()), std::streamsize(q.size() * 2));  // little endian host
        if (!f) return R::failure(path + ": write failed (disk full?)");
      }
      std::error_code ec;
      std::filesystem::rename(tmp, path, ec);
      if (ec) return R::failure(path + ": cannot move the finished file into place (" + ec.message() + ")");
      RawSidecar side;
      side.width = w;
      side.height = h;
      side.heightMin = double(range.min);
      side.heightMax = double(range.max);
      side.spacing = hf.spacing();
      side.origin = hf.origin();
      if (hf.geo().valid()) side.crsWkt = hf.geo().crsWkt;
      rep.sidecar = path + ".json";
      std::string error;
      if (!writeRawSidecar(rep.sidecar, side, error)) return R::failure(error);
      return rep;
    }
  }
  return R::failure(path + ": unsupported format");
}

Result<Heightfield> importHeightmap(const std::string& path, const HeightmapImportOptions& opt,
                                    std::vector<std::string>* warnings) {
  using R = Result<Heightfield>;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return R::failure(path + ": no such file");
  const std::string ext = lowerExt(path);
  auto warn = [&](const std::string& m) {
    if (warnings) warnings->push_back(path + ": " + m);
  };
  if (ext == ".r16" || ext == ".raw") {
    const std::string side = path + ".json";
    int w = 0, h = 0;
    HeightRange range{0.0f, 1.0f};
    glm::dvec2 spacing{1.0};
    glm::dvec3 origin{0.0};
    std::string wkt;
    const auto bytes = std::filesystem::file_size(path, ec);
    if (ec) return R::failure(path + ": cannot read the file size");
    if (std::filesystem::exists(side)) {
      // A sidecar that is there but damaged is an error, not "no sidecar":
      // guessing the size would read the heights wrongly.
      std::string error;
      const std::optional<RawSidecar> s = readRawSidecar(side, error);
      if (!s) return R::failure(error);
      w = s->width;
      h = s->height;
      range = {float(s->heightMin), float(s->heightMax)};
      spacing = s->spacing;
      origin = s->origin;
      wkt = s->crsWkt;
    } else {
      // No sidecar: square files only (like Unreal), range from the options.
      const double n = std::sqrt(double(bytes) / 2.0);
      w = h = int(std::lround(n));
      if (size_t(w) * size_t(h) * 2 != bytes)
        return R::failure(path + ": no sidecar (" + side + ") and the size (" + std::to_string(bytes) +
                          " bytes) is not a square 16-bit raw");
      warn("no sidecar; assuming " + std::to_string(w) + " x " + std::to_string(h));
    }
    if (opt.range) range = *opt.range;
    if (opt.sizeMetres && w > 1 && h > 1) spacing = *opt.sizeMetres / glm::dvec2(w - 1, h - 1);
    if (w < 2 || h < 2 || w > kMaxSamples || h > kMaxSamples)
      return R::failure(path + ": size " + std::to_string(w) + " x " + std::to_string(h) + " is outside 2..8193");
    if (size_t(w) * size_t(h) * 2 != bytes)
      return R::failure(path + ": holds " + std::to_string(bytes) + " bytes, the sidecar says " + std::to_string(w) +
                        " x " + std::to_string(h) + " x 2 = " + std::to_string(size_t(w) * size_t(h) * 2));
    std::vector<uint16_t> q(size_t(w) * size_t(h));
    std::ifstream f(path, std::ios::binary);
    if (!f.read(reinterpret_cast<char*>(q.data()), std::streamsize(bytes)))
      return R::failure(path + ": read failed");
    std::vector<float> v(q.size());
    const double span = double(range.max) - double(range.min);
    for (size_t i = 0; i < q.size(); ++i) v[i] = float(double(range.min) + span * double(q[i]) / 65535.0);
    return build(path, std::move(v), w, h, spacing, origin, wkt);
  }

  std::string why;
  auto in = image_io::open(path, why);
  if (!in) return R::failure(path + ": not an image OpenImageIO can read (" + why + ")");
  const image_io::Spec& spec = in->spec();
  const int w = spec.width, h = spec.height;
  if (w < 2 || h < 2 || w > kMaxSamples || h > kMaxSamples)
    return R::failure(path + ": is " + std::to_string(w) + " x " + std::to_string(h) +
                      "; a heightmap image needs 2..8193 samples per side");
  std::vector<float> v(size_t(w) * size_t(h));
  // Channel 0 only, as float: integer formats come back normalised to 0..1.
  // A decoder may complain and still return true: libjpeg fills a JPEG cut
  // short with grey and only warns, so anything it said refuses the file.
  if (std::string complaint; !in->read(1, image_io::PixelType::Float, v.data(), complaint))
    return R::failure(path + ": cannot read the pixels; the file is damaged or truncated (" + complaint + ")");
  auto attr = [&](const char* name, double& out) { return parseDouble(spec.attribute(name), out); };
  double mn = 0, mx = 0, sx = 1, sy = 1, ox = 0, oy = 0, oz = 0;
  const bool hasRange = attr("hs:height_min", mn) && attr("hs:height_max", mx);
  const bool hasSpacing = attr("hs:spacing_x", sx) && attr("hs:spacing_y", sy);
  attr("hs:origin_x", ox);
  attr("hs:origin_y", oy);
  attr("hs:origin_z", oz);
  const bool isFloat = spec.format == image_io::PixelType::Float || spec.format == image_io::PixelType::Half ||
                       spec.format == image_io::PixelType::Double;
  if (!isFloat) {
    HeightRange r{float(mn), float(mx)};
    if (opt.range) r = *opt.range;
    else if (!hasRange) {
      r = {0.0f, 1.0f};
      warn("no height range recorded; heights are 0..1 (give the range to scale them)");
    }
    // Re-quantise to the exact 16-bit code before scaling, so the round
    // trip lands on the same value the exporter meant.
    const double span = double(r.max) - double(r.min);
    const double levels = spec.format == image_io::PixelType::UInt8 ? 255.0 : 65535.0;
    for (float& x : v) x = float(double(r.min) + span * std::round(double(x) * levels) / levels);
  }
  glm::dvec2 spacing{sx, sy};
  if (opt.sizeMetres) spacing = *opt.sizeMetres / glm::dvec2(w - 1, h - 1);
  else if (!hasSpacing) warn("no spacing recorded; 1 m per sample");
  return build(path, std::move(v), w, h, spacing, {ox, oy, oz}, spec.attribute("hs:crs_wkt"));
}

Result<std::string> exportPaintLayerImage(const PaintLayers& paint, int layer, const std::string& path, int bits) {
  using R = Result<std::string>;
  if (layer < 0 || layer >= paint.layerCount()) return R::failure(path + ": no paint layer " + std::to_string(layer));
  const int w = paint.samplesX(), h = paint.samplesY();
  const bool isExr = lowerExt(path) == ".exr";
  std::vector<float> v(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) v[size_t(h - 1 - y) * size_t(w) + size_t(x)] = paint.weight(layer, x, y);
  const image_io::PixelType type =
      isExr ? image_io::PixelType::Float : bits == 16 ? image_io::PixelType::UInt16 : image_io::PixelType::UInt8;
  image_io::Spec spec = image_io::Spec::of(w, h, 1, type);
  spec.text.emplace_back("oiio:ColorSpace", "Linear");
  spec.text.emplace_back("ImageDescription",
                         "Hybridscape paint weights, layer '" + paint.material(layer).name + "'; row 0 = north");
  Status s = writeImage(path, spec, image_io::PixelType::Float, v.data());
  if (!s) return R::failure(s.error);
  return path;
}

Result<std::string> exportSplatMap(const PaintLayers& paint, int first, const std::string& path) {
  using R = Result<std::string>;
  if (first < 0 || first >= paint.layerCount()) return R::failure(path + ": no paint layer " + std::to_string(first));
  const int w = paint.samplesX(), h = paint.samplesY();
  std::vector<uint8_t> v(size_t(w) * size_t(h) * 4, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c)
        if (first + c < paint.layerCount())
          v[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4 + size_t(c)] = weightByte(paint.raw(first + c, x, y));
  image_io::Spec spec = image_io::Spec::of(w, h, 4, image_io::PixelType::UInt8);
  spec.text.emplace_back("oiio:ColorSpace", "Linear");
  spec.ints.emplace_back("oiio:UnassociatedAlpha", 1);
  Status s = writeImage(path, spec, image_io::PixelType::UInt8, v.data());
  if (!s) return R::failure(s.error);
  return path;
}

}  // namespace hs::terrain
