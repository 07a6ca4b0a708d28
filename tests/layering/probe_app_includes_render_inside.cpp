// Must not compile: app/ and cli/ link hs_render and see its public
// headers only; the frame graph is the renderer's inside.
#include "render/renderer.h"
#include "render/frame_graph.h"
