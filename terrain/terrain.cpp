#include "terrain/terrain.h"

namespace hs::terrain {

Result<Terrain> Terrain::create(const HeightfieldDesc& desc, std::vector<Material> materials) {
  auto hf = Heightfield::create(desc);
  if (!hf) return Result<Terrain>::failure(hf.error());
  return fromHeightfield(hf.take(), std::move(materials));
}

Result<Terrain> Terrain::fromHeightfield(Heightfield hf, std::vector<Material> materials) {
  auto paint = PaintLayers::create(hf.samplesX(), hf.samplesY(), std::move(materials));
  if (!paint) return Result<Terrain>::failure(paint.error());
  return Terrain{std::move(hf), paint.take()};
}

}  // namespace hs::terrain
