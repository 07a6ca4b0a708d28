// Compiles: hs_terrain includes its own headers and core's.
#include "core/progress.h"
#include "terrain/heightfield.h"

int hsLayeringProbeOwn() { return hs::isCancelled(nullptr) ? 1 : 0; }
