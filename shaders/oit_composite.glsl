// Front-to-back compositing of translucent layers, shared by every
// transparency mode's resolve (oit_resolve.frag), so modes that see the
// same fragments in the same order give the same bits. Colours are straight
// (not premultiplied) linear HDR with the opacity in alpha.
#ifndef HS_OIT_COMPOSITE_GLSL
#define HS_OIT_COMPOSITE_GLSL

struct OitComposite {
  vec3 color;           // what the layers so far add
  float transmittance;  // how much of what lies behind them still shows
};

OitComposite oitBegin() { return OitComposite(vec3(0.0), 1.0); }

void oitAdd(inout OitComposite s, vec4 c) {
  s.color += s.transmittance * c.a * c.rgb;
  s.transmittance *= 1.0 - c.a;
}

#endif
