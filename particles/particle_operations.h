#pragma once
// The particle operations the editor's Particles panel and the CLI share,
// declared once (core/params.h): `particles add PRESET SCENE [--name N]
// [--at x,y,z] [--area x0,y0,x1,y1] [--rate R] [--seed S]`. The emitter's
// own fields are emitterParamDecls() (emitter.h); `set EMITTER
// particles.FIELD` goes through them.
#include "core/params.h"
#include "particles/presets.h"

namespace hs::particles {

const OperationDecl& particlesAddOperation();

// The preset's options from values keyed by the declaration (absent: the
// preset's own defaults).
PresetOptions presetFromValues(const Json& values);

}  // namespace hs::particles
