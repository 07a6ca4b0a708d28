#version 450 core
// The A-buffer's per-pixel ranges (abuffer.glsl): an exclusive prefix sum,
// in row-major order, of the nodes each pixel keeps (the fixed array's
// layers for every pixel of abuffer_fixed). Two dispatches of one
// invocation per row: ABUFFER_SCAN_ROW_SUMS sums each row into the cursor
// buffer (free until the key pass, which finds it cleared), then each row
// adds the sums of the rows before it and writes its pixels' starts. Rows
// are few (1080 at 1080p), so the rows-before loop costs less than a
// work-efficient scan's extra dispatches; a pure function of the counts.
layout(local_size_x = 64) in;
#include "abuffer.glsl"
layout(std430, binding = 16) coherent buffer ABufferCursor { uint abufferCursor[]; };
uniform ivec2 uSize;

void main() {
  const int y = int(gl_GlobalInvocationID.x);
  if (y >= uSize.y) return;
  uint sum = 0u;
#ifdef ABUFFER_SCAN_ROW_SUMS
  for (int x = 0; x < uSize.x; ++x) sum += abufferRangeLength(ivec2(x, y));
  abufferCursor[y] = sum;
#else
  for (int r = 0; r < y; ++r) sum += abufferCursor[r];
  const uint row = uint(y) * uint(uSize.x);
  for (int x = 0; x < uSize.x; ++x) {
    abufferStarts[row + uint(x)] = sum;
    sum += abufferRangeLength(ivec2(x, y));
  }
  if (y == uSize.y - 1) abufferStarts[row + uint(uSize.x)] = sum;
#endif
}
