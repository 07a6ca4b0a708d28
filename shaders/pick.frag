#version 450 core
// Writes the drawn object's pick id for viewport picking: the source's
// first id (render/draw_source.h DrawCall::pickBase) plus the object index.
flat in uint vObject;
uniform uint uPickBase;
layout(location = 0) out uint outId;
void main() { outId = uPickBase + vObject; }
