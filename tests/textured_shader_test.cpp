// The built-in textured shader (FragmentShader::kTextured): the texel at the texture
// coordinates, its level of detail from each 2x2 quad's derivatives, times the colour varyings.
// The fast engine (float sampler) against the reference (the double sampler, the oracle) on
// every SIMD target and thread count, for every filter and wrap mode; and every bad state an
// error naming it. Texture files are input_texture_test.cpp's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/shading_scene.hpp"

namespace tessera {
namespace {

using shading_scene::kClear;
using shading_scene::kHeight;
using shading_scene::kWidth;
using shading_scene::Mesh;
using shading_scene::Target;
using shading_scene::test_mesh;

// The scene's eye-space position x and y (varyings 7 and 8) as (u, v): about three repeats of
// the texture across the near sheet, minified on the far ones.
PipelineState textured(const Sampler& sampler) {
  PipelineState p;
  p.shader = FragmentShader::kTextured;
  p.texture = shading_scene::checks();
  p.sampler = sampler;
  p.roles.texcoord = 7;
  return p;
}

using shading_scene::Image;

Image render(const PipelineState& pipeline, ColorFormat format, uint32_t samples, Backend backend,
             Target target = {SimdTarget::kAuto, 1}) {
  return shading_scene::render(test_mesh(), pipeline, format, samples, backend, target);
}

struct Case {
  std::string name;
  Sampler sampler;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  const auto add = [&](const std::string& name, Filter filter, MipFilter mip, Wrap wrap) {
    Sampler s;
    s.mag_filter = s.min_filter = filter;
    s.mip_filter = mip;
    s.wrap_u = s.wrap_v = wrap;
    s.border_color = {0.25f, 0.5f, 1.0f, 1.0f};
    out.push_back({name, s});
  };
  add("nearest, no mips, repeat", Filter::kNearest, MipFilter::kNone, Wrap::kRepeat);
  add("bilinear, no mips, repeat", Filter::kLinear, MipFilter::kNone, Wrap::kRepeat);
  add("bilinear, nearest mip, mirrored", Filter::kLinear, MipFilter::kNearest,
      Wrap::kMirroredRepeat);
  add("trilinear, repeat", Filter::kLinear, MipFilter::kLinear, Wrap::kRepeat);
  add("trilinear, clamp to edge", Filter::kLinear, MipFilter::kLinear, Wrap::kClampToEdge);
  add("trilinear, clamp to border", Filter::kLinear, MipFilter::kLinear, Wrap::kClampToBorder);
  add("nearest, nearest mip, clamp to border", Filter::kNearest, MipFilter::kNearest,
      Wrap::kClampToBorder);
  Sampler biased = out[3].sampler;
  biased.lod_bias = 1.5f;
  biased.max_lod = 3.0f;
  out.push_back({"trilinear, LOD bias 1.5, max LOD 3", biased});
  Sampler anisotropic = out[3].sampler;
  anisotropic.max_anisotropy = 8;
  out.push_back({"trilinear, anisotropic 8, repeat", anisotropic});
  anisotropic = out[5].sampler;
  anisotropic.max_anisotropy = 16;
  out.push_back({"trilinear, anisotropic 16, clamp to border", anisotropic});
  return out;
}

// Every filter and wrap mode: every SIMD target and thread count gives the same bytes; against
// the reference, RGBA8 within one step where a linear filter blends (nearest texels or levels
// may differ only where float and double fall on the two sides of a texel edge or a level
// switch: counted, and under 0.5% of the covered pixels), RGBA32F within 1e-4.
TEST(TexturedShader, MatchesTheReferenceOnEveryTargetAndThreadCount) {
  const std::vector<Target> targets = shading_scene::fast_targets();
  ASSERT_FALSE(targets.empty());
  for (const Case& c : cases()) {
    const PipelineState p = textured(c.sampler);
    const bool nearest =
        c.sampler.min_filter == Filter::kNearest || c.sampler.mip_filter == MipFilter::kNearest;
    for (uint32_t samples : {1u, 4u}) {
      const std::string where = c.name + ", " + std::to_string(samples) + " samples";
      const Image want = render(p, ColorFormat::kRGBA8, samples, Backend::kReference);
      const Image got = render(p, ColorFormat::kRGBA8, samples, Backend::kFast, targets[0]);
      for (const Target& t : targets) {
        ASSERT_EQ(render(p, ColorFormat::kRGBA8, samples, Backend::kFast, t).rgba8, got.rgba8)
            << where << ", target " << int(t.simd) << ", " << t.threads << " threads";
      }
      size_t covered = 0, off = 0;
      for (size_t i = 0; i < want.rgba8.size(); i += 4) {
        ASSERT_EQ(want.rgba8[i + 3] == 0, got.rgba8[i + 3] == 0) << where << ": pixel " << i / 4;
        covered += want.rgba8[i + 3] != 0;
        int worst = 0;
        for (size_t k = 0; k < 4; ++k)
          worst = std::max(worst, std::abs(int{want.rgba8[i + k]} - got.rgba8[i + k]));
        if (!nearest) {
          ASSERT_LE(worst, 1) << where << ": pixel " << i / 4;
        }
        off += worst > 1;
      }
      EXPECT_GT(covered, size_t{kWidth * kHeight / 2}) << where;
      EXPECT_LE(off * 200, covered) << where << ": " << off << " pixels differ by more than 1";
      std::printf("%s: %zu of %zu pixels differ by more than one step\n", where.c_str(), off,
                  covered);
      if (samples == 1 && !nearest) {
        const Image want32 = render(p, ColorFormat::kRGBA32F, 1, Backend::kReference);
        const Image got32 = render(p, ColorFormat::kRGBA32F, 1, Backend::kFast);
        for (size_t i = 0; i < want32.rgba32f.size(); ++i) {
          ASSERT_EQ(want32.rgba32f[i] == kClear, got32.rgba32f[i] == kClear) << where << ": " << i;
          ASSERT_LE(std::abs(want32.rgba32f[i] - got32.rgba32f[i]), 1e-4f) << where << ": " << i;
        }
      }
    }
  }
}

// The fast engine draws a textured triangle in its raster kernels' lanes (Shader::kTextured)
// where the sampler's lanes take the texture (the test's 64x32 RGBA8 one), and through the quad
// back end otherwise (several colour targets, other formats). Both form the same values,
// derivatives and samples: the lanes give the bytes of a user shader that samples the texture
// and scales it by the colour varyings, on every target, in RGBA8 and RGBA32F, at one and four
// samples.
TEST(TexturedShader, TheLanePathGivesTheQuadBackEndsBytes) {
  const std::vector<Target> targets = shading_scene::fast_targets();
  for (const Case& c : cases()) {
    const PipelineState lanes = textured(c.sampler);
    PipelineState quads = lanes;
    quads.shader = FragmentShader::kUser;
    const std::shared_ptr<const Texture> texture = lanes.texture;
    const Sampler sampler = c.sampler;
    quads.fragment_function = [texture, sampler](const FragmentBatch& b,
                                                 const FragmentOutput& out) {
      constexpr uint32_t kStride = kFragmentBatchStride;
      alignas(64) float texel[4 * kStride];
      sample(*texture, sampler, b, 7, 8, texel);
      for (uint32_t k = 0; k < 4; ++k) {
        for (uint32_t i = 0; i < b.count; ++i)
          out.color[k * kStride + i] = texel[k * kStride + i] * b.varyings[k * kStride + i];
      }
    };
    for (const Target& t : targets) {
      for (uint32_t samples : {1u, 4u}) {
        const std::string where = c.name + ", " + std::to_string(samples) + " samples, target " +
                                  std::to_string(int(t.simd)) + ", " + std::to_string(t.threads) +
                                  " threads";
        const Image want = render(quads, ColorFormat::kRGBA8, samples, Backend::kFast, t);
        EXPECT_EQ(render(lanes, ColorFormat::kRGBA8, samples, Backend::kFast, t).rgba8, want.rgba8)
            << where;
      }
      const Image want32 = render(quads, ColorFormat::kRGBA32F, 1, Backend::kFast, t);
      EXPECT_EQ(render(lanes, ColorFormat::kRGBA32F, 1, Backend::kFast, t).rgba32f, want32.rgba32f)
          << c.name << ", RGBA32F";
    }
  }
}

// The colour varyings scale the texel; without four of them the texel is drawn as it is.
TEST(TexturedShader, TheColourVaryingsScaleTheTexel) {
  Sampler s;
  s.mip_filter = MipFilter::kNone;
  PipelineState white = textured(s);
  white.roles.color = 10;  // past the draw's 10 varyings: no colour
  const PipelineState coloured = textured(s);
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    const Image plain = render(white, ColorFormat::kRGBA32F, 1, backend);
    const Image scaled = render(coloured, ColorFormat::kRGBA32F, 1, backend);
    const Image colour = render(PipelineState{}, ColorFormat::kRGBA32F, 1, backend);
    size_t checked = 0;
    for (size_t i = 0; i < plain.rgba32f.size(); ++i) {
      if (plain.rgba32f[i] == kClear) continue;
      ASSERT_NEAR(scaled.rgba32f[i], plain.rgba32f[i] * colour.rgba32f[i], 2e-6f) << i;
      ++checked;
    }
    EXPECT_GT(checked, size_t{kWidth * kHeight});
  }
}

// A full-window quad whose (u, v) runs over [0, 1] at the texture's own size draws each texel
// on its pixel, exactly, with the nearest and the linear filter alike (every pixel centre is a
// texel centre), through MSAA too.
TEST(TexturedShader, ATextureMappedOneToOneDrawsItsTexels) {
  constexpr uint32_t w = 24, h = 16;
  std::vector<uint8_t> texels(w * h * 4);
  for (size_t i = 0; i < texels.size(); ++i)
    texels[i] = static_cast<uint8_t>((i * 37 + i / 7) % 256);
  const auto texture =
      std::make_shared<Texture>(TextureDesc{w, h, TextureFormat::kRGBA8},
                                std::as_bytes(std::span<const uint8_t>(texels)), false);
  const std::vector<Float4> positions = {{-1, 1, 0.5f, 1}, {1, 1, 0.5f, 1},  {1, -1, 0.5f, 1},
                                         {-1, 1, 0.5f, 1}, {1, -1, 0.5f, 1}, {-1, -1, 0.5f, 1}};
  const std::vector<float> uv = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
  for (Filter filter : {Filter::kNearest, Filter::kLinear}) {
    for (uint32_t samples : {1u, 4u}) {
      for (Backend backend : {Backend::kReference, Backend::kFast}) {
        PipelineState p;
        p.shader = FragmentShader::kTextured;
        p.texture = texture;
        p.roles.texcoord = 0;
        p.sampler.mag_filter = p.sampler.min_filter = filter;
        RendererOptions options;
        options.backend = backend;
        options.threads = 2;
        Renderer renderer(options);
        Framebuffer fb({w, h, samples, ColorFormat::kRGBA8});
        renderer.draw(fb, p, {positions, uv, 2, {}});
        EXPECT_EQ(fb.read_rgba8(), texels)
            << int(filter) << ", " << samples << " samples, backend " << int(backend);
      }
    }
  }
}

// The demo scene's tiled ground through draw_scene, per vertex and per pixel: both backends
// within one step, the tiles visible (the ground is not one flat colour).
TEST(TexturedShader, TheDemoScenesTexturedGroundDrawsAlikeOnBothBackends) {
  const Scene scene = make_demo_scene();
  ASSERT_NE(scene.objects[0].texture, nullptr);
  for (SceneShading shading : {SceneShading::kPerVertex, SceneShading::kPerPixel}) {
    std::vector<uint8_t> image[2];
    for (Backend backend : {Backend::kReference, Backend::kFast}) {
      RendererOptions options;
      options.backend = backend;
      options.threads = 2;
      Renderer renderer(options);
      Framebuffer fb({160, 100, 1, ColorFormat::kRGBA8});
      draw_scene(renderer, fb, PipelineState{}, scene, shading);
      image[backend == Backend::kFast ? 1 : 0] = fb.read_rgba8();
    }
    size_t differ = 0;
    for (size_t i = 0; i < image[0].size(); ++i)
      differ += std::abs(int{image[0][i]} - image[1][i]) > 1;
    EXPECT_EQ(differ, 0u) << int(shading);
    // The bottom row is ground: its tiles' joints make it vary.
    const auto [lo, hi] = std::minmax_element(image[1].end() - 160 * 4, image[1].end());
    EXPECT_GT(*hi - *lo, 40) << int(shading);
  }
  // A textured object without texture coordinates is an error, and nothing is drawn.
  Scene bad = scene;
  bad.objects[0].mesh.texcoords.clear();
  Renderer renderer;
  Framebuffer fb({160, 100, 1, ColorFormat::kRGBA8});
  try {
    draw_scene(renderer, fb, PipelineState{}, bad);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scene object 0 has a texture but 0 texture coordinates"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(fb.read_depth(), std::vector<float>(160 * 100, 1.0f));
}

template <typename F>
void expect_error(F&& f, const std::string& words) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one naming " << words;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(TexturedShader, BadStatesAreErrorsThatDrawNothing) {
  const Mesh mesh = test_mesh();
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    RendererOptions options;
    options.backend = backend;
    Renderer renderer(options);
    Framebuffer fb({kWidth, kHeight, 1, ColorFormat::kRGBA8});
    const auto draw_error = [&](const PipelineState& p, const std::string& words) {
      expect_error([&] { renderer.draw(fb, p, mesh.input()); }, words);
      EXPECT_EQ(fb.read_depth(), std::vector<float>(kWidth * kHeight, 1.0f)) << words;
    };
    PipelineState p = textured(Sampler{});
    p.texture = nullptr;
    draw_error(p, "needs a texture");
    p = textured(Sampler{});
    p.roles.texcoord = 9;  // 9..10 of 10 varyings
    draw_error(p, "roles.texcoord");
    p = textured(Sampler{});
    p.sampler.wrap_v = static_cast<Wrap>(7);
    draw_error(p, "sampler.wrap_v");
    p = textured(Sampler{});
    p.sampler.mip_filter = static_cast<MipFilter>(5);
    draw_error(p, "sampler.mip_filter");
    p = textured(Sampler{});
    p.sampler.min_lod = 4;
    p.sampler.max_lod = 2;
    draw_error(p, "min_lod");
    p = textured(Sampler{});
    p.sampler.lod_bias = std::nanf("");
    draw_error(p, "lod_bias");
    for (float bad : {0.5f, 17.0f, std::nanf("")}) {
      p = textured(Sampler{});
      p.sampler.max_anisotropy = bad;
      draw_error(p, "max_anisotropy");
    }
    p = textured(Sampler{});
    p.sampler.border_color[2] = INFINITY;
    draw_error(p, "border_color");
    p = textured(Sampler{});
    p.shader = static_cast<FragmentShader>(9);
    draw_error(p, "shader");
  }
}

}  // namespace
}  // namespace tessera
