// Front-to-back compositing of translucent layers, shared by every
// transparency mode's resolve (oit_resolve.frag), so modes that see the
// same fragments in the same order give the same bits. Colours are straight
// (not premultiplied) linear HDR with the opacity in alpha. An opacity below
// 0 marks an additive layer (particles with additive blend, render/
// particle_source.h): it adds its colour, dimmed by the layers in front of
// it, and hides nothing behind it (transmittance 1). Half floats keep the
// sign, so the A-buffer's and K-buffer's nodes carry the mark unchanged.
#ifndef HS_OIT_COMPOSITE_GLSL
#define HS_OIT_COMPOSITE_GLSL

struct OitComposite {
  vec3 color;           // what the layers so far add
  float transmittance;  // how much of what lies behind them still shows
};

OitComposite oitBegin() { return OitComposite(vec3(0.0), 1.0); }

void oitAdd(inout OitComposite s, vec4 c) {
  if (c.a < 0.0) {
    s.color += s.transmittance * c.rgb;
    return;
  }
  s.color += s.transmittance * c.a * c.rgb;
  s.transmittance *= 1.0 - c.a;
}

#endif
