// The package test's application (scripts/check-package.sh): draws one red triangle through
// Tessera's public API, on both backends, and checks a pixel inside it and one outside; with
// Tessera::io it also writes the image as a PNG into the directory given as its argument and
// reads it back. Exits non-zero on failure.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <tessera/tessera.hpp>
#ifdef TESSERA_CONSUMER_IO
#include <tessera/io.hpp>
#endif

static_assert(TESSERA_VERSION_MAJOR >= 0 && TESSERA_VERSION_MINOR >= 0 &&
              TESSERA_VERSION_PATCH >= 0);

namespace {

constexpr uint32_t kSize = 64;

bool check(bool ok, const std::string& what) {
  if (!ok) std::fprintf(stderr, "consumer: %s\n", what.c_str());
  return ok;
}

// RGBA8 value of pixel (x, y), top row first.
const uint8_t* pixel(const std::vector<uint8_t>& rgba, uint32_t x, uint32_t y) {
  return &rgba[(static_cast<size_t>(y) * kSize + x) * 4];
}

bool draw_and_check(tessera::Backend backend, std::vector<uint8_t>& rgba) {
  tessera::Framebuffer fb({kSize, kSize, 1, tessera::ColorFormat::kRGBA8});
  fb.clear_color({0, 0, 0, 1});
  tessera::Renderer renderer({.threads = 2, .backend = backend});
  // Counter-clockwise in NDC, covering the centre of the image and not its top-left corner.
  const std::vector<tessera::Float4> positions = {
      {-0.5f, -0.5f, 0.5f, 1}, {0.5f, -0.5f, 0.5f, 1}, {0, 0.5f, 0.5f, 1}};
  const std::vector<float> colors = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  renderer.draw(fb, tessera::PipelineState{}, {positions, colors, 4, {}});
  rgba = fb.read_rgba8();
  const uint8_t* inside = pixel(rgba, kSize / 2, kSize / 2);
  const uint8_t* outside = pixel(rgba, 1, 1);
  const std::string name = backend == tessera::Backend::kFast ? "fast" : "reference";
  return check(inside[0] == 255 && inside[1] == 0 && inside[2] == 0 && inside[3] == 255,
               name + ": the triangle's centre is not red") &&
         check(outside[0] == 0 && outside[1] == 0 && outside[2] == 0,
               name + ": the corner outside the triangle is not black") &&
         check(renderer.counters().triangles_rasterized == 1,
               name + ": the renderer did not count one rasterized triangle");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<uint8_t> fast, reference;
    if (!draw_and_check(tessera::Backend::kFast, fast)) return 1;
    if (!draw_and_check(tessera::Backend::kReference, reference)) return 1;
    if (!check(fast == reference, "the fast engine's image differs from the reference's")) return 1;
    // The public error type crosses the library boundary (its type information is exported).
    try {
      tessera::Framebuffer bad({0, 0, 1, tessera::ColorFormat::kRGBA8});
      return check(false, "a 0x0 framebuffer was accepted"), 1;
    } catch (const tessera::Error& e) {
      if (!check(e.code() == tessera::ErrorCode::kInvalidArgument,
                 "a 0x0 framebuffer threw the wrong error code"))
        return 1;
    }
#ifdef TESSERA_CONSUMER_IO
    if (!check(argc == 2, "usage: consumer DIRECTORY (where to write a PNG)")) return 2;
    const std::filesystem::path png = std::filesystem::path(argv[1]) / "consumer.png";
    tessera::write_image(png, kSize, kSize, 4, std::span<const uint8_t>(fast));
    const tessera::Image image = tessera::read_image(png);
    std::filesystem::remove(png);
    if (!check(image.width == kSize && image.height == kSize && image.channels == 4 &&
                   image.at(kSize / 2, kSize / 2)[0] == 1.0f &&
                   image.at(kSize / 2, kSize / 2)[1] == 0.0f,
               "the PNG read back is not the image written"))
      return 1;
#else
    (void)argc;
    (void)argv;
#endif
    std::printf("consumer: Tessera %s drew the triangle (SIMD target %s)\n", TESSERA_VERSION_STRING,
                tessera::Renderer().simd_target());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
