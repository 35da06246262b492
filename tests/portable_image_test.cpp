// Images that are the same bytes on every machine: the shading test scene drawn with Gouraud
// colours, per-pixel Phong, a trilinear and an anisotropic texture, at one and four samples,
// by the fast engine on every SIMD target this CPU runs and by the reference, each reduced to
// a 64-bit FNV-1a digest of its colour bytes and depth bits and compared with the digest
// recorded on an x86-64 host. On 64-bit Arm (scripts/check-arm-run.sh, under qemu with NEON and
// SVE at several vector lengths) the same digests prove the same bytes as on x86.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/shading_scene.hpp"

namespace tessera {
namespace {

uint64_t fnv1a(uint64_t hash, std::span<const std::byte> bytes) {
  for (std::byte b : bytes) {
    hash ^= static_cast<uint8_t>(b);
    hash *= 0x100000001b3ull;
  }
  return hash;
}

uint64_t digest(const shading_scene::Image& image) {
  uint64_t hash = 0xcbf29ce484222325ull;
  hash = fnv1a(hash, std::as_bytes(std::span(image.rgba8)));
  hash = fnv1a(hash, std::as_bytes(std::span(image.rgba32f)));
  return fnv1a(hash, std::as_bytes(std::span(image.depth)));
}

struct Case {
  const char* name;
  PipelineState pipeline;
  ColorFormat format;
  uint32_t samples;
  uint64_t fast;       // the fast engine's digest, on every target
  uint64_t reference;  // the reference's
};

std::vector<Case> cases() {
  std::vector<Case> out;
  PipelineState gouraud;
  out.push_back({"gouraud, rgba8, 1 sample", gouraud, ColorFormat::kRGBA8, 1, 0, 0});
  out.push_back({"gouraud, rgba32f, 4 samples", gouraud, ColorFormat::kRGBA32F, 4, 0, 0});
  PipelineState phong;
  phong.shader = FragmentShader::kPhong;
  phong.phong.light_count = 2;
  phong.phong.lights[0].position = {1.5f, 2.0f, -1.0f};
  phong.phong.lights[1].kind = LightKind::kSpot;
  phong.phong.lights[1].position = {0.5f, 0.5f, 0.0f};
  phong.phong.lights[1].direction = {-0.1f, -0.2f, -1.0f};
  phong.phong.lights[1].spot_cos_cutoff = 0.97f;
  phong.phong.lights[1].spot_exponent = 3;
  phong.phong.shininess = 40;
  out.push_back({"phong, rgba8, 4 samples", phong, ColorFormat::kRGBA8, 4, 0, 0});
  PipelineState textured;
  textured.shader = FragmentShader::kTextured;
  textured.texture = shading_scene::checks();
  textured.roles.texcoord = 7;
  textured.sampler.mag_filter = textured.sampler.min_filter = Filter::kLinear;
  textured.sampler.mip_filter = MipFilter::kLinear;
  out.push_back({"trilinear, rgba8, 1 sample", textured, ColorFormat::kRGBA8, 1, 0, 0});
  textured.sampler.max_anisotropy = 4;
  textured.sampler.wrap_u = Wrap::kMirroredRepeat;
  out.push_back({"anisotropic 4, rgba32f, 1 sample", textured, ColorFormat::kRGBA32F, 1, 0, 0});
  // Recorded on an x86-64 host (AVX-512, AVX2, SSE4 and scalar alike).
  const std::array<std::array<uint64_t, 2>, 5> recorded = {{
      {0x79e3e8d3c85d2a84ull, 0x2d300468d9286a73ull},
      {0x464fa0a02216f694ull, 0x9d86ee7aa9ff4c23ull},
      {0x5c5f68f92f2f5572ull, 0x85a784db8039d37bull},
      {0xc54f38c79f7ea919ull, 0x67005a386728a781ull},
      {0x5bc746203b4d61aeull, 0xfb8e6452958b97daull},
  }};
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].fast = recorded[i][0];
    out[i].reference = recorded[i][1];
  }
  return out;
}

TEST(PortableImages, EveryTargetAndTheReferenceDrawTheBytesRecordedOnX86) {
  const shading_scene::Mesh mesh = shading_scene::test_mesh();
  for (const Case& c : cases()) {
    const uint64_t reference =
        digest(shading_scene::render(mesh, c.pipeline, c.format, c.samples, Backend::kReference));
    EXPECT_EQ(reference, c.reference)
        << c.name << ", reference: 0x" << std::hex << reference << "ull";
    for (const shading_scene::Target& t : shading_scene::fast_targets()) {
      if (t.threads != 2) continue;
      const uint64_t fast =
          digest(shading_scene::render(mesh, c.pipeline, c.format, c.samples, Backend::kFast, t));
      EXPECT_EQ(fast, c.fast) << c.name << ", target " << static_cast<int>(t.simd) << ": 0x"
                              << std::hex << fast << "ull";
    }
  }
}

}  // namespace
}  // namespace tessera
