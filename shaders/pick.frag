#version 450 core
// Writes the drawn object's pick id for viewport picking: the source's
// first id (render/draw_source.h DrawCall::pickBase) plus the object index.
// INSTANCED: a fading instance is picked where it is drawn (instance_fade.glsl).
#ifdef INSTANCED
#include "instance_fade.glsl"
#endif
flat in uint vObject;
uniform uint uPickBase;
layout(location = 0) out uint outId;
void main() {
#ifdef INSTANCED
  instanceFadeDiscard();
#endif
  outId = uPickBase + vObject;
}
