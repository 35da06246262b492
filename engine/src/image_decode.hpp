// Image decoding shared by the io library's loaders (image_io.cpp): a texture from a file's
// bytes in memory, as load_texture reads it from a file. Mesh files embed their textures so.
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include "tessera/texture.hpp"

namespace tessera {

// `what` names the texture in errors; `name`'s extension (.png, .jpg, ...) tells the format.
// Throws Error(kIo) naming `what` when the bytes cannot be decoded, Error(kInvalidArgument)
// when a side is above kMaxTextureSize.
Texture decode_texture(const std::string& what, const std::string& name,
                       std::span<const std::byte> bytes, bool srgb, bool mipmaps);

}  // namespace tessera
