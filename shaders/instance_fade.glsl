// The fade of an instanced source's instances near their cull distance
// (render/instanced_source.h): mesh.vert's INSTANCED variant gives each
// instance the share of its pixels to drop (instances.glsl instanceFade,
// flat), and every fragment shader that draws instances (mesh.frag's lit
// and transparency variants, shadow_depth.frag, pick.frag, the A-buffer's
// count and key passes, the K-buffer's depth pass) drops the same pixels
// by an ordered 8x8 Bayer dither on the pixel: a pure function of the
// instance's place and the pixel, so two renders, both eyes and every pass
// of a frame agree (the transparency passes match fragments by depth and
// key; a pixel one drops, all drop). The dropped share of a fade f is f
// within 1/128 over each 8x8 block; the shadow map's texels are dithered
// the same way, so a caster's shadow thins as it does. Picking renders one
// pixel into a 1x1 target: uDitherOffset is that pixel's place in the view.
#ifndef HS_INSTANCE_FADE_GLSL
#define HS_INSTANCE_FADE_GLSL

flat in float vInstanceFade;
uniform ivec2 uDitherOffset;

// Bayer's 8x8 ordered dither: bit reversal of the interleaved bits of
// (x ^ y, y); each of 0..63 once per 8x8 block.
float instanceDitherThreshold(ivec2 pixel) {
  uint x = uint(pixel.x) & 7u, y = uint(pixel.y) & 7u, v = x ^ y;
  uint m = ((v & 1u) << 5) | ((y & 1u) << 4) | ((v & 2u) << 2) | ((y & 2u) << 1) | ((v & 4u) >> 1) | ((y & 4u) >> 2);
  return (float(m) + 0.5) * (1.0 / 64.0);
}

void instanceFadeDiscard() {
  if (vInstanceFade > 0.0 && instanceDitherThreshold(ivec2(gl_FragCoord.xy) + uDitherOffset) < vInstanceFade) discard;
}

#endif
