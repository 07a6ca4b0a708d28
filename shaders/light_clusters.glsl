// The clustered light list (render/passes/light_culling.h is the C++ side;
// the constants must match it). Each view's frustum is cut into froxels:
// LIGHT_TILES_X x LIGHT_TILES_Y screen tiles times LIGHT_SLICES depth
// slices (slice 0 from the eye to LIGHT_SLICE_NEAR metres, then
// exponential slices to LIGHT_SLICE_FAR, the last one reaching to
// infinity). shaders/light_culling.comp writes, per cluster, how many
// lights reach it (binding 7) and their indices into the light buffer
// (binding 9, LIGHT_CLUSTER_CAP slots per cluster, in ascending order so
// the sum is the brute-force loop's); binding 10 counts clusters that had
// more lights than the cap. Each view's grid is bound as a range of the
// frame's buffers.
#ifndef HS_LIGHT_CLUSTERS_GLSL
#define HS_LIGHT_CLUSTERS_GLSL

#define LIGHT_TILES_X 16
#define LIGHT_TILES_Y 9
#define LIGHT_SLICES 24
#define LIGHT_CLUSTER_CAP 128
#define LIGHT_SLICE_NEAR 0.5
#define LIGHT_SLICE_FAR 3000.0
#define LIGHT_CLUSTERS (LIGHT_TILES_X * LIGHT_TILES_Y * LIGHT_SLICES)

// Depth slice of a view-space distance d (metres in front of the eye).
// A distance that is not a number or infinite (a fragment whose inputs
// were extrapolated far off its triangle: a sliver covering a sample under
// MSAA interpolates at the pixel centre) still gets a slice of the grid:
// int() of an infinite or NaN float is undefined (x86 gives INT_MIN), and an
// index off the grid reads a count from anywhere, which made the light loop
// run for minutes on a CPU rasteriser.
int lightSliceOf(float d) {
  if (!(d >= LIGHT_SLICE_NEAR)) return 0;  // NaN too
  const float scale = float(LIGHT_SLICES - 2) / log(LIGHT_SLICE_FAR / LIGHT_SLICE_NEAR);
  return min(1 + int(floor(log(min(d, LIGHT_SLICE_FAR) / LIGHT_SLICE_NEAR) * scale)), LIGHT_SLICES - 1);
}

// The near distance of slice k (k = LIGHT_SLICES: infinity).
float lightSliceStart(int k) {
  if (k <= 0) return 0.0;
  if (k >= LIGHT_SLICES) return 1e30;
  return LIGHT_SLICE_NEAR * pow(LIGHT_SLICE_FAR / LIGHT_SLICE_NEAR, float(k - 1) / float(LIGHT_SLICES - 2));
}

int lightClusterIndex(ivec2 tile, int slice) {
  return (slice * LIGHT_TILES_Y + tile.y) * LIGHT_TILES_X + tile.x;
}

#endif
