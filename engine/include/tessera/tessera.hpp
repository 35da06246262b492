// Tessera: a tile-based, multithreaded, SIMD software rasterizer. This header includes the
// whole public API.
#pragma once

#include "tessera/capture.hpp"
#include "tessera/error.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/image_io.hpp"
#include "tessera/mesh.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"
#include "tessera/shading.hpp"
#include "tessera/types.hpp"
#include "tessera/vertex.hpp"
