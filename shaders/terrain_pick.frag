#version 450 core
// The terrain in the viewport's id pass: holes and the area past the last
// sample are not there, so they cannot be picked (terrain.frag's rules).
in vec3 vEyePos;
in vec2 vSample;
in vec2 vLocal;
uniform ivec2 uSamples;
uniform bool uHasHoles;
uniform usampler2D uHoles;
uniform uint uPickId;
layout(location = 0) out uint outId;
void main() {
  const vec2 last = vec2(uSamples - 1);
  if (any(lessThan(vSample, vec2(-1e-3))) || any(greaterThan(vSample, last + 1e-3))) discard;
  if (uHasHoles) {
    ivec2 c = clamp(ivec2(floor(vSample)), ivec2(0), uSamples - 2);
    if (texelFetch(uHoles, c, 0).r + texelFetch(uHoles, c + ivec2(1, 0), 0).r +
        texelFetch(uHoles, c + ivec2(0, 1), 0).r + texelFetch(uHoles, c + ivec2(1, 1), 0).r > 0u)
      discard;
  }
  outId = uPickId;
}
