// Must not compile: hs_terrain does not link hs_mesh.
#include "mesh/mesh_data.h"
