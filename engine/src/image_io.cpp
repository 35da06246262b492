// Image output through OpenImageIO; the only file that includes its headers (they are slow to
// compile), chosen format by file extension.
#include "tessera/image_io.hpp"

#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "engine/src/image_decode.hpp"
#include "engine/src/texture/texture_storage.hpp"
#include "tessera/error.hpp"

namespace tessera {

namespace {

void write(const std::filesystem::path& path, uint32_t width, uint32_t height, uint32_t channels,
           size_t values, OIIO::TypeDesc type, const void* data) {
  if (width == 0 || height == 0 || channels == 0 || values != size_t{width} * height * channels) {
    throw Error(ErrorCode::kInvalidArgument, path.string() + ": image of " + std::to_string(width) +
                                                 "x" + std::to_string(height) + "x" +
                                                 std::to_string(channels) + " given " +
                                                 std::to_string(values) + " values");
  }
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) {
    throw Error(ErrorCode::kIo, path.string() + ": cannot write: " + OIIO::geterror());
  }
  OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height),
                       static_cast<int>(channels), type);
  if (channels == 1) spec.channelnames = {"Z"};
  // The pixels are stored as given: a PNG writer would otherwise divide colour by alpha.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out->open(path.string(), spec) || !out->write_image(type, data) || !out->close()) {
    throw Error(ErrorCode::kIo, path.string() + ": cannot write: " + out->geterror());
  }
}

// Reads pixels as the file stores them: a PNG reader would otherwise multiply colour by alpha.
const OIIO::ImageSpec& unassociated_alpha() {
  static const OIIO::ImageSpec config = [] {
    OIIO::ImageSpec c;
    c.attribute("oiio:UnassociatedAlpha", 1);
    return c;
  }();
  return config;
}

}  // namespace

void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const uint8_t> pixels) {
  write(path, width, height, channels, pixels.size(), OIIO::TypeDesc::UINT8, pixels.data());
}

void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const float> pixels) {
  write(path, width, height, channels, pixels.size(), OIIO::TypeDesc::FLOAT, pixels.data());
}

void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const uint32_t> pixels) {
  write(path, width, height, channels, pixels.size(), OIIO::TypeDesc::UINT32, pixels.data());
}

Image read_image(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string(), &unassociated_alpha());
  if (!in) throw Error(ErrorCode::kIo, path.string() + ": cannot read: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw Error(ErrorCode::kIo, path.string() + ": empty image");
  }
  Image image;
  image.width = static_cast<uint32_t>(spec.width);
  image.height = static_cast<uint32_t>(spec.height);
  image.channels = static_cast<uint32_t>(spec.nchannels);
  image.pixels.resize(size_t{image.width} * image.height * image.channels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    throw Error(ErrorCode::kIo, path.string() + ": cannot decode: " + in->geterror());
  }
  return image;
}

namespace {

// The texture an opened image holds; `what` names it in errors.
Texture texture_from(OIIO::ImageInput& input, const std::string& what, bool srgb, bool mipmaps) {
  OIIO::ImageInput* in = &input;
  const OIIO::ImageSpec& spec = in->spec();
  const std::filesystem::path path = what;
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw Error(ErrorCode::kIo, path.string() + ": empty image");
  }
  const auto width = static_cast<uint32_t>(spec.width);
  const auto height = static_cast<uint32_t>(spec.height);
  if (width > kMaxTextureSize || height > kMaxTextureSize) {
    throw Error(ErrorCode::kInvalidArgument,
                path.string() + ": " + std::to_string(width) + "x" + std::to_string(height) +
                    " is larger than a texture's " + std::to_string(kMaxTextureSize) +
                    " texels per side");
  }
  const auto channels = static_cast<uint32_t>(spec.nchannels);
  const bool bytes = spec.format == OIIO::TypeDesc::UINT8;
  const size_t texels = size_t{width} * height;
  // Grey, grey + alpha, RGB and RGBA (and more) as the texture's one or four channels.
  const auto expand = [&](const auto* from, auto* to, auto one) {
    for (size_t i = 0; i < texels; ++i) {
      const auto* p = from + i * channels;
      if (channels == 1) {
        to[i] = p[0];
      } else if (channels == 2) {
        to[4 * i] = to[4 * i + 1] = to[4 * i + 2] = p[0];
        to[4 * i + 3] = p[1];
      } else {
        for (uint32_t c = 0; c < 3; ++c)
          to[4 * i + c] = p[c];
        to[4 * i + 3] = channels >= 4 ? p[3] : one;
      }
    }
  };
  const uint32_t out_channels = channels == 1 ? 1 : 4;
  if (bytes) {
    std::vector<uint8_t> file(texels * channels), texture(texels * out_channels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, file.data())) {
      throw Error(ErrorCode::kIo, path.string() + ": cannot decode: " + in->geterror());
    }
    expand(file.data(), texture.data(), uint8_t{255});
    const TextureFormat format = channels == 1 ? TextureFormat::kR8
                                 : srgb        ? TextureFormat::kRGBA8Srgb
                                               : TextureFormat::kRGBA8;
    return Texture({width, height, format}, std::as_bytes(std::span<const uint8_t>(texture)),
                   mipmaps);
  }
  std::vector<float> file(texels * channels), texture(texels * out_channels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, file.data())) {
    throw Error(ErrorCode::kIo, path.string() + ": cannot decode: " + in->geterror());
  }
  expand(file.data(), texture.data(), 1.0f);
  if (srgb) {
    // The colour channels decoded as the sampler decodes sRGB texels; alpha stays linear.
    for (size_t i = 0; i < texture.size(); ++i) {
      if (out_channels == 1 || i % 4 != 3) {
        texture[i] = static_cast<float>(texture::srgb_to_linear(texture[i]));
      }
    }
  }
  const TextureFormat format = channels == 1 ? TextureFormat::kR32F : TextureFormat::kRGBA32F;
  return Texture({width, height, format}, std::as_bytes(std::span<const float>(texture)), mipmaps);
}

}  // namespace

Texture load_texture(const std::filesystem::path& path, bool srgb, bool mipmaps) {
  auto in = OIIO::ImageInput::open(path.string(), &unassociated_alpha());
  if (!in) throw Error(ErrorCode::kIo, path.string() + ": cannot read: " + OIIO::geterror());
  return texture_from(*in, path.string(), srgb, mipmaps);
}

Texture decode_texture(const std::string& what, const std::string& name,
                       std::span<const std::byte> bytes, bool srgb, bool mipmaps) {
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  OIIO::ImageSpec config = unassociated_alpha();
  OIIO::Filesystem::IOProxy* proxy = &memory;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open(name, &config, &memory);
  if (!in) throw Error(ErrorCode::kIo, what + ": cannot decode: " + OIIO::geterror());
  return texture_from(*in, what, srgb, mipmaps);
}

}  // namespace tessera
