// A 32-bit integer hash, Wellons' lowbias32: the same bits on the GPU as in
// the CPU code that mirrors a shader (particles/rng.h, the tests' twins),
// so patterns drawn from it match exactly. One definition for every shader.
uint lowbias32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
