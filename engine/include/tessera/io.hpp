// Tessera::io, the file input and output beside the core library: meshes through Assimp and
// images through OpenImageIO. Link the CMake target Tessera::io (pkg-config: tessera-io), which
// brings Tessera::tessera with it.
#pragma once

#include "tessera/image_io.hpp"
#include "tessera/mesh_io.hpp"
