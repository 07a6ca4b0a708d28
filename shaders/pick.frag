#version 450 core
// Writes the index (1-based) of the drawn object for viewport picking.
flat in uint vObject;
layout(location = 0) out uint outId;
void main() { outId = vObject + 1u; }
