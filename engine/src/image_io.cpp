// Image output through OpenImageIO; the only file that includes its headers (they are slow to
// compile), chosen format by file extension.
#include "tessera/image_io.hpp"

#include <memory>
#include <string>

#include <OpenImageIO/imageio.h>

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
  if (!out->open(path.string(), spec) || !out->write_image(type, data) || !out->close()) {
    throw Error(ErrorCode::kIo, path.string() + ": cannot write: " + out->geterror());
  }
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
  auto in = OIIO::ImageInput::open(path.string());
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

}  // namespace tessera
