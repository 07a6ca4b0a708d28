#pragma once
// The document's content as a value: entities, assets and settings. Edits
// replace parts of it through patches (edit.h); the renderer, the CLI and the
// file writer only read it.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/json.h"
#include "mesh/mesh_data.h"
#include "scene/entity.h"
#include "scene/foliage_data.h"
#include "scene/light_units.h"
#include "scene/material.h"
#include "scene/terrain_asset.h"
#include "sequencer/sequence.h"

namespace hs::foliage {
struct ImpostorImages;
}

namespace hs::scene {

struct ClusterAsset;  // scene/cluster_asset.h

// A coarser level of detail of a mesh asset (levels 1, 2, ...; level 0 is
// MeshAsset::data). Its own blob in the file ("mesh/<id>/lod<k>"); it has no
// textures of its own and draws with level 0's (mesh/lod_chain.h).
struct MeshLod {
  std::shared_ptr<const mesh::MeshData> data;  // immutable, shared by undo
  uint64_t contentHash = 0;                    // mesh::contentHash(*data)
  double hausdorff = 0.0;                      // metres, symmetric, against level 0
  size_t triangles = 0;                        // data->triangleCount(), kept for the description
  bool operator==(const MeshLod& o) const {
    return contentHash == o.contentHash && hausdorff == o.hausdorff && triangles == o.triangles;
  }
};

struct MeshAsset {
  AssetId id = kNoAsset;
  std::string name;
  std::string sourcePath;                       // where it was imported from
  std::shared_ptr<const mesh::MeshData> data;   // immutable once imported: shared by undo (LOD 0)
  uint64_t contentHash = 0;                     // mesh::contentHash(*data)
  // What the importer said (AssetImportReport as JSON, scene/asset_reports.h);
  // null when there is no report.
  Json importReport;
  std::vector<MeshLod> lods;                    // coarser levels after `data`, errors non-decreasing
  // Cleaning, decimation error report, per-LOD errors and times
  // (AssetProcessReport as JSON); null when the mesh was imported as read.
  Json processReport;
  // Hausdorff error per level in metres, level 0 (= 0) first: what
  // mesh::selectLod takes.
  std::vector<double> lodErrors() const;
  // The document material of each material slot (scene/material_slots.h):
  // one per mesh::Material, plus one for submeshes without a material.
  std::vector<MaterialId> materialSlots;
  // The far level the renderer baked from this mesh, an octahedral impostor
  // (foliage/impostor_images.h; blob "mesh/<id>/impostor"); null when none
  // is stored. Stale when its sourceKey is not impostorSourceKey(state,
  // *this) (scene/impostor_key.h): the renderer then bakes its own.
  std::shared_ptr<const foliage::ImpostorImages> impostor;
  uint64_t impostorHash = 0;  // impostor->contentHash() (0: none), what the description keeps
  // A huge scan as a cluster hierarchy (scene/cluster_asset.h: its index,
  // and pages read from the scene file on demand); null for an ordinary
  // mesh. With it, `data` is a coarse cut of the hierarchy (the scan's
  // bounds, picking, and what a view draws until its pages arrive).
  std::shared_ptr<const ClusterAsset> clusters;
  uint64_t clustersHash = 0;  // the cluster index blob's hash (0: none), what the description keeps
  bool operator==(const MeshAsset& o) const {
    return id == o.id && name == o.name && sourcePath == o.sourcePath &&
           contentHash == o.contentHash && importReport == o.importReport && lods == o.lods &&
           processReport == o.processReport && materialSlots == o.materialSlots && impostorHash == o.impostorHash &&
           clustersHash == o.clustersHash;
  }
};

// Anti-aliasing (docs/rendering.md "Anti-aliasing"): MSAA 4x on the scene's
// geometry, or one of two filters on the tone-mapped picture: FXAA, or SMAA
// (render/passes/smaa_passes.h: edge lines' shapes, sharper than FXAA).
enum class Antialiasing { None = 0, Fxaa = 1, Msaa4 = 2, Smaa = 3 };
// The tone map (docs/rendering.md "Post-processing"): ACES: filmic curve
// (highlights roll off); None: exposure then clamp, for reference renders
// and colour checks; AgX: Sobotka's log-encoded sigmoid (highlights
// desaturate towards white instead of skewing hue); PbrNeutral: Khronos
// PBR Neutral (base colours kept exactly up to 0.76, only highlights
// compressed).
enum class Tonemap { Aces = 0, None = 1, AgX = 2, PbrNeutral = 3 };

// A colour look-up table held by the document (docs/rendering.md
// "Post-processing", LUTs): the bytes of the file as imported, in any format
// OpenColorIO reads (.cube, .3dl, .spi3d, .csp, ...; its name's extension
// says which), so a scene grades the same on a farm node as on the machine
// that imported it. Stored in the .hscene as blob "lut/<hash>". Compared by
// name and content hash, not by the bytes.
struct LutData {
  std::string fileName;                        // "teal_orange.cube" (no folder); empty: none
  std::shared_ptr<const std::string> bytes{};  // null while a loaded description waits for its blob
  uint64_t contentHash = 0;                    // XXH3 of the bytes (core/content_hash.h)
  bool empty() const { return fileName.empty(); }
  bool operator==(const LutData& o) const { return fileName == o.fileName && contentHash == o.contentHash; }
};

// An OpenColorIO config held by the document (scene/ocio_config.h): the
// config's text and the LUT files under its search paths, so a scene
// renders through the studio's view transform on a farm node that has no
// copy of the studio's folder. Each file is a blob "ocio/<hash>" in the
// .hscene. Compared by name and content hash, not by the bytes.
struct OcioFile {
  // Relative to the bundle: "config.ocio" for the config itself, then
  // "search<i>/<path under the config's i-th search path>".
  std::string path;
  std::shared_ptr<const std::string> bytes{};  // null while a loaded description waits for its blob
  uint64_t contentHash = 0;                    // XXH3 of the bytes
};
struct OcioConfigData {
  std::string fileName;        // the config's name as imported ("studio.ocio"); empty: none
  std::vector<OcioFile> files;  // files[0] is the config ("config.ocio")
  uint64_t contentHash = 0;     // over every file's path and hash (scene/ocio_config.h)
  bool empty() const { return fileName.empty(); }
  bool loaded() const {
    for (const OcioFile& f : files)
      if (!f.bytes) return false;
    return !files.empty();
  }
  bool operator==(const OcioConfigData& o) const { return fileName == o.fileName && contentHash == o.contentHash; }
};

// The post chain from the scene's HDR colour to the output
// (docs/rendering.md "Post-processing"), in this order: exposure (manual
// or automatic), bloom,
// chromatic aberration (on the scene's light, as a lens makes it), the tone
// map (or an OpenColorIO view transform), the grade, the LUT, the vignette, grain, then FXAA. Each effect runs only
// when enabled: with all off the chain is the tone map alone, no pass or
// texture more.
// Dithering (PostSettings::dither): an ordered threshold pattern (Bayer,
// blue noise), or Floyd-Steinberg error diffusion.
enum class DitherMode { Off = 0, Bayer = 1, BlueNoise = 2, ErrorDiffusion = 3 };
struct PostSettings {
  // Automatic exposure (docs/rendering.md "Automatic exposure"): the
  // exposure metered from small renders of the shot at fixed times before
  // the frame (a luminance histogram each, core/exposure_meter.h) and
  // adapted over them, instead of settings.exposure_ev100; a pure function
  // of the time, so a frame alone equals the same frame of a sequence.
  bool autoExposure = false;
  float autoExposureMinEv100 = -2.0f;     // the range the metered exposure is clamped to
  float autoExposureMaxEv100 = 20.0f;
  float autoExposureCompensation = 0.0f;  // EV; positive: a brighter image
  float autoExposureLowPercent = 10.0f;   // the darkest pixels left out of the mean
  float autoExposureHighPercent = 90.0f;  // the brightest beyond this left out
  float autoExposureSpeedUp = 3.0f;       // per second, towards a brighter scene
  float autoExposureSpeedDown = 1.0f;     // per second, towards a darker scene
  float autoExposureProbesPerSecond = 4.0f;  // probe renders per second of film (the adaptation's step)
  // Bloom: exposed light above the threshold (soft knee), spread by a
  // downsample/upsample chain and added back.
  bool bloom = false;
  float bloomIntensity = 0.05f;  // share of the spread light added
  float bloomThreshold = 1.0f;   // exposed luminance where it starts
  float bloomRadius = 0.7f;      // 0..1: how far it spreads (the weight of the coarser levels)
  // Chromatic aberration: red and blue scaled about the image centre.
  bool chromaticAberration = false;
  float chromaticAberrationPx = 2.0f;  // fringe width at the image's corner, pixels per 1080 lines
  // Colour grade, display-linear after the tone map: white balance, lift /
  // gamma / gain per channel (ASC CDL-like: out = (gain*x + lift*(1-x))^(1/gamma)), saturation.
  bool grade = false;
  float temperature = 0.0f;  // -1 cool (blue) .. 1 warm (orange)
  float tint = 0.0f;         // -1 green .. 1 magenta
  glm::vec3 lift{0.0f};
  glm::vec3 gamma{1.0f};
  glm::vec3 gain{1.0f};
  float saturation = 1.0f;
  // Vignette: the image darkened towards its corners (cos^4-like falloff).
  bool vignette = false;
  float vignetteIntensity = 0.35f;  // darkening at the corner, 0..1
  // Film grain: luminance noise seeded by the frame number (the same
  // pattern in both eyes).
  bool grain = false;
  float grainIntensity = 0.05f;
  float grainSizePx = 1.5f;  // grain size, pixels per 1080 lines
  // A look-up table after the grade (scene/color_lut.h), applied by
  // OpenColorIO's GPU shader to the sRGB-encoded image, mixed in by intensity.
  bool lutEnabled = false;
  float lutIntensity = 1.0f;
  LutData lut{};
  // OpenColorIO's display/view transform from a stored config in the tone
  // map's place (settings.tonemap is then not used): scene-linear in,
  // display code values out, decoded to display-linear for the grade and
  // the rest of the chain. An empty display or view: the config's default.
  bool viewTransform = false;
  std::string display;
  std::string view;
  OcioConfigData ocioConfig{};
  // Stylised effects (docs/rendering.md "Stylised effects"), on the
  // display-referred image after the vignette and grain, in this order.
  // Kuwahara, anisotropic (Kyprianidis, Kang & Doellner 2009): each pixel
  // the weighted mean of eight sectors of an ellipse laid along the local
  // structure, the least varied weighing most (painted strokes).
  bool kuwahara = false;
  float kuwaharaRadiusPx = 6.0f;   // the ellipse's radius, pixels per 1080 lines
  float kuwaharaSharpness = 8.0f;  // q: how much the least varied sectors win
  // Comic: colours posterised to a few levels, halftone dots in the shadows.
  bool comic = false;
  float comicLevels = 5.0f;  // levels per channel
  float comicDotPx = 6.0f;   // halftone cell, pixels per 1080 lines
  // Outlines: Sobel edges of the luminance drawn in a colour.
  bool outlines = false;
  float outlineThreshold = 0.25f;  // gradient (luminance per pixel, Sobel-scaled) where lines start
  glm::vec3 outlineColor{0.0f};
  // CRT: barrel curvature, scanlines, an aperture-grille mask.
  bool crt = false;
  float crtCurvature = 0.08f;   // barrel distortion at the corner
  float crtScanlines = 0.5f;    // darkening between the lines, 0..1
  float crtLinesPer1080 = 270.0f;  // scanlines over the frame's height (at most one per 3 rows)
  float crtMask = 0.3f;         // the mask's strength, 0..1
  // Dithering to `ditherLevels` per channel with an ordered (Bayer 8x8) or
  // blue-noise threshold, or by diffusing each pixel's error to its
  // neighbours (Floyd-Steinberg, a compute pass).
  DitherMode dither = DitherMode::Off;
  float ditherLevels = 4.0f;
  // Weighted Voronoi stippling (Secord 2002), after the per-pixel effects
  // and before error diffusion: black dots on white paper, as many per area
  // as the image is dark, spread by Lloyd relaxation towards the centroids
  // of their darkness-weighted Voronoi cells (render/passes/stipple_passes.h).
  bool stipple = false;
  float stippleSpacingPx = 5.0f;  // distance between dots where the image is black, pixels per 1080 rows
  float stippleDotPx = 1.2f;      // a dot's radius, pixels per 1080 rows
  int stippleIterations = 8;      // Lloyd steps (0: the dots where the candidates were accepted)
  bool operator==(const PostSettings&) const = default;
};
// Shadow presets (docs/rendering.md "Shadows"): map size, cascades and PCF
// kernel together; Custom takes SceneSettings::shadowResolution etc.
enum class ShadowQuality { Low = 0, Medium = 1, High = 2, Custom = 3 };
// Fog (shaders/fog.glsl, docs/rendering.md "Fog"). DepthCue: the survey's
// depth cueing, the surface keeps f = min(1, 1/(k1 + k2·d)) of its colour
// at distance d; ExponentialHeight: density ρ(z) = density·exp(−falloff·(z −
// height)), integrated along the view ray.
enum class FogMode { None = 0, DepthCue = 1, ExponentialHeight = 2 };
// The sky behind the scene and the ambient light it gives
// (docs/rendering.md, "Sky and environment"): Gradient: the zenith/horizon/
// ground colours below and a hemisphere ambient; Analytic: Preetham's
// daylight model driven by the sun, lighting the scene through spherical
// harmonics and a prefiltered specular cube recomputed when the sun moves.
enum class SkyModel { Gradient = 0, Analytic = 1 };
// Screen-space ambient occlusion of the ambient term (docs/rendering.md).
enum class AmbientOcclusion { Off = 0, Ssao = 1, Gtao = 2 };  // docs/rendering.md, "Ambient occlusion"
enum class AoResolution { Half = 0, Full = 1 };
// Depth of field (docs/rendering.md "Depth of field"): off (no pass, no
// buffer), a gather pass on the opaque colour and depth, layers from the
// A-buffer (partial occlusion), or the lens-averaged reference.
enum class DepthOfField { Off = 0, Gather = 1, Layered = 2, Reference = 3 };
// Transparency (docs/rendering.md "Transparency"): how translucent
// surfaces (opacity under 1, no alpha cut-out) are composited.
// ABuffer: every fragment in per-pixel sorted ranges; ABufferFixed: the thesis's
// fixed 16-deep array; KBuffer: the kbufferK nearest, the rest tail-blended;
// Weighted: weighted blended OIT (McGuire & Bavoil 2013); Reference: depth
// peeling until no fragment is left (exact, slow: tests and benchmarks).
enum class Transparency { ABuffer = 0, ABufferFixed = 1, KBuffer = 2, Weighted = 3, Reference = 4 };

struct SceneSettings {
  glm::vec3 skyZenith{0.16f, 0.32f, 0.62f};    // linear RGB
  glm::vec3 skyHorizon{0.62f, 0.72f, 0.82f};
  glm::vec3 groundColor{0.22f, 0.2f, 0.18f};
  float ambientIntensity = 0.5f;
  // Camera exposure as EV100: the reference, 15.2 − log2 π ≈ 13.55
  // (light_units.h; with a 100 000 lux sun, the look of before physical
  // units). Files before format 6 held a multiplier ("exposure"), files 6-7
  // an EV100 against 15.2; both are converted on load.
  float exposureEv100 = float(kReferenceEv100);
  bool showGrid = true;
  Antialiasing antialiasing = Antialiasing::Msaa4;
  Tonemap tonemap = Tonemap::Aces;
  PostSettings post{};
  // Mesh LODs: each instance draws the coarsest level whose error, projected
  // to the screen, is at most this many pixels (0: always full resolution).
  double meshLodErrorPixels = 1.0;
  // Cluster hierarchies (huge scans, scene/cluster_asset.h) take the same
  // pixel bound; their resident pages may take at most this much memory on
  // the GPU and in the CPU's page cache (MiB); least recently used pages
  // give way, and until a page arrives its parent is drawn.
  double clusterGpuBudgetMb = 1024.0;
  double clusterCpuBudgetMb = 2048.0;
  // Shadows (docs/rendering.md "Shadows"): sun cascades and the shadows of
  // lights that cast them. Off by default so scenes made before keep their look.
  bool shadows = false;
  ShadowQuality shadowQuality = ShadowQuality::Medium;
  int shadowResolution = 2048;     // texels per side, with ShadowQuality::Custom
  int shadowCascades = 3;          // sun cascades, with Custom
  int shadowPcfRadius = 1;         // PCF kernel (2r+1)^2 taps, with Custom
  double shadowDistance = 30000.0; // metres from the camera the sun's cascades cover
  // Fog (FogMode above); off by default, and then no shader variant and no
  // buffer exist for it.
  FogMode fogMode = FogMode::None;
  glm::vec3 fogColour{0.62f, 0.7f, 0.8f};  // linear, scene units (what fully fogged pixels show)
  float fogK1 = 1.0f;                      // depth cue: constant term
  float fogK2 = 0.0005f;                   // depth cue: per metre (half the colour kept at 2 km)
  float fogDensity = 0.0005f;              // height fog: extinction per metre at the fog height
  float fogHeightFalloff = 0.02f;          // height fog: per metre above the fog height
  float fogHeight = 0.0f;                  // height fog: metres (world z) where the density is fogDensity
  // Sky and environment (settings.sky*). Gradient stays the default, so
  // files written before the analytic sky keep their look; new scenes and
  // the demo choose Analytic.
  SkyModel sky = SkyModel::Gradient;
  float skyTurbidity = 3.0f;     // Preetham's haze: 2 very clear .. 10 hazy
  float skyGroundAlbedo = 0.2f;  // the ground below the horizon (analytic sky)
  AmbientOcclusion ao = AmbientOcclusion::Off;
  float aoRadius = 1.0f;          // metres: how far an occluder counts
  float aoStrength = 1.0f;        // 0: none, 1: as measured, up to 4
  AoResolution aoResolution = AoResolution::Half;
  // Depth of field (DepthOfField above), from the viewing camera's lens
  // (focal length, f-stop, focus distance). Off by default.
  DepthOfField depthOfField = DepthOfField::Off;
  int dofLayers = 4;              // layered: K depth layers, 2..16
  int dofReferenceSamples = 64;   // reference: N pinhole renders over the lens, 64..1024
  // Transparency (Transparency above): the mode, the K-buffer's depth and
  // the most GPU memory the OIT buffers of one view may take (MiB).
  Transparency transparency = Transparency::ABuffer;
  int kbufferK = 8;
  double oitMemoryMb = 256.0;
  // Particles of emitters without replay evaluated in a compute pass
  // (render/particle_gpu_eval.h) instead of on the CPU: much faster on a
  // GPU for large emitters, within 2/255 of the CPU path (each path is
  // deterministic; frames of one film should use one). Off by default.
  bool particlesOnGpu = false;
  bool operator==(const SceneSettings&) const = default;
};

// The time a state shows (DESIGN.md, "Time and determinism"): set by
// animatedState, the one place a scene is evaluated at a time; the
// document's own state is t = 0. The renderer passes it to shaders
// (FrameBlock.time), so wind, particles and grain are functions of t too.
struct SceneTime {
  double seconds = 0.0;  // from the sequence's start
  int64_t frame = 0;     // the frame nearest `seconds` at `fps`
  double fps = 60.0;
  bool operator==(const SceneTime&) const = default;
};

struct SceneState {
  std::map<EntityId, Entity> entities;  // ordered: deterministic iteration and files
  std::vector<EntityId> roots;          // top-level entities in outliner order
  std::map<AssetId, MeshAsset> assets;
  // Terrains (scene/terrain_asset.h): small values here, tiles shared.
  std::map<TerrainId, TerrainAsset> terrains;
  // Foliage types and instances (foliage_data.h); null: none. Shared by
  // copies of the state, edited in place (FoliageCommand undoes).
  std::shared_ptr<FoliageData> foliage;
  // Materials and textures (scene/material.h), referred to by mesh assets.
  std::map<MaterialId, Material> materials;
  std::map<TextureId, TextureAsset> textures;
  SceneSettings settings;
  // The timeline: tracks per entity, frame rate, playback/export range.
  sequencer::Sequence sequence;
  // When this state is (not saved: a document is at t = 0).
  SceneTime time;

  const Entity* find(EntityId id) const;
  const MeshAsset* findAsset(AssetId id) const;
  const TerrainAsset* findTerrain(TerrainId id) const;
  const Material* findMaterial(MaterialId id) const;
  const TextureAsset* findTexture(TextureId id) const;
  // By name; kNoMaterial if none (names are unique: materials add " 2", ...).
  MaterialId findMaterialByName(const std::string& name) const;
  // Parent chain composed in double precision.
  glm::dmat4 worldMatrix(EntityId id) const;
  // Visible only if it and every ancestor is visible.
  bool effectivelyVisible(EntityId id) const;
  // True if `ancestor` is `id` or one of its ancestors.
  bool isAncestorOrSelf(EntityId ancestor, EntityId id) const;
  // Depth-first, outliner order.
  std::vector<EntityId> depthFirstOrder() const;
  // Entities with a camera, depth-first order.
  std::vector<EntityId> cameras() const;
  EntityId findByName(const std::string& name) const;
  EntityId maxEntityId() const;
  AssetId maxAssetId() const;
  TerrainId maxTerrainId() const;
  MaterialId maxMaterialId() const;
  TextureId maxTextureId() const;

  // Checks parent/children/roots consistency; empty string if sound. Used
  // by tests and after loading a file.
  std::string validate() const;
};

}  // namespace hs::scene
