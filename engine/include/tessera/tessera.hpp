// Tessera: a tile-based, multithreaded, SIMD software rasterizer. This header includes the
// public API of the core library (the CMake target Tessera::tessera), which needs only oneTBB,
// Highway and GLM. Mesh and image files are tessera/io.hpp, in the separate Tessera::io.
#pragma once

#include "tessera/capture.hpp"
#include "tessera/error.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/mesh.hpp"
#include "tessera/occlusion.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"
#include "tessera/shading.hpp"
#include "tessera/texture.hpp"
#include "tessera/types.hpp"
#include "tessera/version.hpp"
#include "tessera/vertex.hpp"
