// Must not compile: render sits above scene.
#include "render/renderer.h"
