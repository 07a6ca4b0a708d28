#version 450 core
// Floyd-Steinberg error diffusion on the GPU (render/passes/stylised_passes.h):
// each pixel quantised to uLevels per channel, its error passed on 7/16
// right, 3/16 below-left, 5/16 below, 1/16 below-right. The scan is
// sequential by nature; here each invocation of one workgroup owns a row
// and runs along it two pixels behind the row before (a wavefront: pixel
// x of row y goes at step x + 2y, after every pixel it takes error from),
// with a barrier between steps. Rows come in bands of the workgroup's
// size; a band starts when the one before has finished. One invocation
// does one pixel at a time in a fixed order, so the result is the same on
// every run (the same as a sequential scan in float, up to the order of
// the additions into a pixel's error).
layout(local_size_x = 256) in;
layout(binding = 0) uniform sampler2D uImage;              // display-encoded
layout(binding = 0, rgba8) uniform writeonly image2D uOut;
// The error each pixel of the last two rows passes down: [row & 1][x].
layout(std430, binding = 0) coherent buffer Carry { vec4 below[]; };
uniform float uLevels;
#ifdef HS_DITHER_FORCED
// The second eye of a stereo pair: the first eye's level where it sees the
// same surface (alpha 1; shaders/dither_reproject.frag), taken instead of
// the nearest level; its error is passed on as any pixel's.
layout(binding = 1) uniform sampler2D uForced;
#endif

void main() {
  const ivec2 size = textureSize(uImage, 0);
  const int lane = int(gl_LocalInvocationID.x);
  const float steps = max(uLevels, 2.0) - 1.0;
  for (int band = 0; band * 256 < size.y; ++band) {
    const int y = band * 256 + lane;
    const bool mine = y < size.y;
    vec3 right = vec3(0.0);  // the error the pixel before passed right
    const int rows = min(256, size.y - band * 256);
    for (int t = 0; t < size.x + 2 * (rows - 1); ++t) {
      const int x = t - 2 * lane;
      vec3 e = vec3(0.0);
      bool wrote = false;
      if (mine && x >= 0 && x < size.x) {
        vec3 v = texelFetch(uImage, ivec2(x, y), 0).rgb + right;
        if (y > 0) {
          // From the row before: 3/16 of its pixel x+1's error, 5/16 of x's, 1/16 of x-1's.
          const int prev = ((y - 1) & 1) * size.x;
          if (x + 1 < size.x) v += below[prev + x + 1].rgb * (3.0 / 16.0);
          v += below[prev + x].rgb * (5.0 / 16.0);
          if (x > 0) v += below[prev + x - 1].rgb * (1.0 / 16.0);
        }
        vec3 q = clamp(floor(clamp(v, 0.0, 1.0) * steps + 0.5), 0.0, steps) / steps;
        e = v - q;
#ifdef HS_DITHER_FORCED
        const vec4 forced = texelFetch(uForced, ivec2(x, y), 0);
        if (forced.a > 0.5) {
          q = floor(forced.rgb * steps + 0.5) / steps;  // the level the 8-bit texel holds
          // Bounded: a run of taken levels that differ from this eye's
          // colour (a highlight one eye sees) cannot pile error up.
          e = clamp(v, 0.0, 1.0) - q;
        }
#endif
        right = e * (7.0 / 16.0);
        imageStore(uOut, ivec2(x, y), vec4(q, 1.0));
        wrote = true;
      }
      // Every lane reaches the barrier each step; the row after reads this
      // row's error one step later at the earliest.
      memoryBarrierBuffer();
      barrier();
      if (wrote) below[(y & 1) * size.x + x] = vec4(e, 0.0);
      memoryBarrierBuffer();
      barrier();
    }
  }
}
