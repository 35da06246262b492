// Draws from several host threads at once (docs/API.md, "Threads"): each thread with its own
// renderer and framebuffers; one texture shared by every thread's draws; one renderer handed
// from thread to thread (never used by two at once); and renderers with several workers of
// their own under host threads that outnumber the cores. Every image equals the one the same
// job draws alone on one thread, byte for byte. scripts/check-tsan.sh runs this suite under
// ThreadSanitizer.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "tessera/tessera.hpp"

namespace tessera {
namespace {

constexpr uint32_t kWidth = 150, kHeight = 90;

// A job: a scene, the state it is drawn with and the framebuffer it draws into.
struct Job {
  std::string name;
  std::vector<Float4> positions;
  std::vector<float> attributes;
  uint32_t attribute_count = 4;
  PipelineState pipeline;
  uint32_t samples = 1;
  ColorFormat format = ColorFormat::kRGBA8;
  enum class Kind { kTriangles, kPoints, kLines } kind = Kind::kTriangles;
};

std::vector<Job> jobs(const std::shared_ptr<const Texture>& texture) {
  std::vector<Job> out;
  const auto soup = [](uint32_t seed, int count, float size, uint32_t attribute_count) {
    Job j;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < count; ++i) {
      const float cx = u(rng) * 2.2f - 1.1f, cy = u(rng) * 2.2f - 1.1f;
      for (int k = 0; k < 3; ++k) {
        const float w = 0.5f + u(rng);
        j.positions.push_back(
            {(cx + (u(rng) - 0.5f) * size) * w, (cy + (u(rng) - 0.5f) * size) * w, u(rng) * w, w});
        for (uint32_t a = 0; a < attribute_count; ++a)
          j.attributes.push_back(u(rng));
      }
    }
    j.attribute_count = attribute_count;
    return j;
  };
  Job j = soup(1, 3000, 0.06f, 4);
  j.name = "small gouraud triangles";
  out.push_back(j);
  j = soup(2, 400, 0.5f, 4);
  j.name = "large triangles, four samples, float colour";
  j.samples = 4;
  j.format = ColorFormat::kRGBA32F;
  out.push_back(j);
  j = soup(3, 800, 0.2f, 6);
  j.name = "textured triangles";
  j.pipeline.shader = FragmentShader::kTextured;
  j.pipeline.texture = texture;
  j.pipeline.sampler.mip_filter = MipFilter::kLinear;
  j.pipeline.roles.texcoord = 4;
  out.push_back(j);
  j = soup(4, 1500, 0.15f, 4);
  j.name = "blended triangles with a scissor";
  j.pipeline.blend[0] = BlendState::over();
  j.pipeline.depth_write = false;
  j.pipeline.scissor_test = true;
  j.pipeline.scissor = {20, 10, 100, 61};
  out.push_back(j);
  j = soup(5, 300, 0.1f, 4);
  j.name = "round points";
  j.kind = Job::Kind::kPoints;
  out.push_back(j);
  j = soup(6, 300, 0.4f, 4);
  j.name = "antialiased lines";
  j.kind = Job::Kind::kLines;
  out.push_back(j);
  return out;
}

std::shared_ptr<const Texture> texture() {
  constexpr uint32_t w = 64, h = 64;
  std::vector<uint8_t> texels(size_t{w} * h * 4);
  for (size_t i = 0; i < texels.size(); ++i)
    texels[i] = static_cast<uint8_t>((i * 31 + i / 5) % 256);
  return std::make_shared<Texture>(TextureDesc{w, h, TextureFormat::kRGBA8},
                                   std::as_bytes(std::span<const uint8_t>(texels)), true);
}

// The job drawn by `renderer` into a new framebuffer: its resolved colour as bytes and every
// sample's depth.
struct Result {
  std::vector<uint8_t> rgba8;
  std::vector<float> depth;
  friend bool operator==(const Result&, const Result&) = default;
};

Result draw(Renderer& renderer, const Job& job) {
  Framebuffer fb({kWidth, kHeight, job.samples, job.format});
  fb.clear_color({0.1f, 0.2f, 0.3f, 1.0f});
  const DrawInput input{job.positions, job.attributes, job.attribute_count, {}};
  switch (job.kind) {
    case Job::Kind::kTriangles:
      renderer.draw(fb, job.pipeline, input);
      break;
    case Job::Kind::kPoints:
      renderer.draw_points(fb, job.pipeline, {5.0f, PointShape::kRound}, input);
      break;
    case Job::Kind::kLines: {
      LineState lines;
      lines.width = 3.0f;
      lines.antialiased = true;
      const DrawInput pairs{std::span(job.positions).first(job.positions.size() / 2 * 2),
                            std::span(job.attributes).first(job.positions.size() / 2 * 2 * 4),
                            4,
                            {}};
      renderer.draw_lines(fb, job.pipeline, lines, pairs);
      break;
    }
  }
  return {fb.read_rgba8(), fb.read_sample_depth()};
}

Renderer make_renderer(Backend backend, uint32_t threads) {
  RendererOptions options;
  options.backend = backend;
  options.threads = threads;
  return Renderer(options);
}

// Each job drawn alone, one worker, on this thread.
std::vector<Result> serial(const std::vector<Job>& all, Backend backend) {
  Renderer renderer = make_renderer(backend, 1);
  std::vector<Result> out;
  for (const Job& job : all)
    out.push_back(draw(renderer, job));
  return out;
}

// Runs body(t) on `count` host threads at once and waits for them.
template <class Body>
void on_threads(uint32_t count, Body body) {
  std::vector<std::thread> threads;
  for (uint32_t t = 0; t < count; ++t)
    threads.emplace_back(body, t);
  for (std::thread& thread : threads)
    thread.join();
}

TEST(HostThreads, SeveralThreadsDrawWithTheirOwnRenderersAsOneDrawsAlone) {
  const std::vector<Job> all = jobs(texture());  // one texture in every thread's textured job
  for (Backend backend : {Backend::kFast, Backend::kReference}) {
    const std::vector<Result> expected = serial(all, backend);
    constexpr uint32_t kThreads = 4, kRounds = 2;
    // Each thread's results, in job order; threads start at different jobs, so different kinds
    // of draw run at once.
    std::vector<std::vector<Result>> got(kThreads, std::vector<Result>(all.size()));
    on_threads(kThreads, [&](uint32_t t) {
      // Two workers each: eight busy threads on this host's cores.
      Renderer renderer = make_renderer(backend, backend == Backend::kFast ? 2 : 1);
      for (uint32_t round = 0; round < kRounds; ++round) {
        for (size_t k = 0; k < all.size(); ++k) {
          const size_t j = (k + t * 2 + round) % all.size();
          got[t][j] = draw(renderer, all[j]);
        }
      }
    });
    for (uint32_t t = 0; t < kThreads; ++t) {
      for (size_t j = 0; j < all.size(); ++j) {
        EXPECT_TRUE(got[t][j] == expected[j])
            << all[j].name << ", host thread " << t << ", backend " << static_cast<int>(backend);
      }
    }
  }
}

TEST(HostThreads, OneRendererHandedFromThreadToThreadDrawsAsAlone) {
  const std::vector<Job> all = jobs(texture());
  const std::vector<Result> expected = serial(all, Backend::kFast);
  // One renderer of three workers, used by one thread at a time (the mutex), by four threads
  // that each draw every job into their own framebuffers.
  Renderer shared = make_renderer(Backend::kFast, 3);
  std::mutex turn;
  constexpr uint32_t kThreads = 4;
  std::vector<std::vector<Result>> got(kThreads, std::vector<Result>(all.size()));
  on_threads(kThreads, [&](uint32_t t) {
    for (size_t k = 0; k < all.size(); ++k) {
      const size_t j = (k + t) % all.size();
      std::lock_guard<std::mutex> lock(turn);
      got[t][j] = draw(shared, all[j]);
    }
  });
  for (uint32_t t = 0; t < kThreads; ++t) {
    for (size_t j = 0; j < all.size(); ++j)
      EXPECT_TRUE(got[t][j] == expected[j]) << all[j].name << ", host thread " << t;
  }
}

TEST(HostThreads, ThreadsReadOneFramebufferOneAfterAnotherAndDrawIntoOthers) {
  // A framebuffer drawn once, then handed between threads that read it back one at a time
  // while each also draws into its own: the reads see the one image.
  const std::vector<Job> all = jobs(texture());
  Renderer renderer = make_renderer(Backend::kFast, 2);
  Framebuffer fb({kWidth, kHeight, 1, ColorFormat::kRGBA8});
  renderer.draw(fb, all[0].pipeline, {all[0].positions, all[0].attributes, 4, {}});
  const std::vector<uint8_t> image = fb.read_rgba8();
  const std::vector<Result> expected = serial(all, Backend::kFast);
  std::mutex turn;
  constexpr uint32_t kThreads = 3;
  // One byte per thread (std::vector<bool> packs them into shared words, a race).
  std::vector<uint8_t> same_image(kThreads, 0), same_draw(kThreads, 0);
  on_threads(kThreads, [&](uint32_t t) {
    Renderer own = make_renderer(Backend::kFast, 1);
    const Result drawn = draw(own, all[t + 1]);
    same_draw[t] = drawn == expected[t + 1];
    std::lock_guard<std::mutex> lock(turn);
    same_image[t] = fb.read_rgba8() == image;
  });
  for (uint32_t t = 0; t < kThreads; ++t) {
    EXPECT_TRUE(same_image[t]) << "host thread " << t;
    EXPECT_TRUE(same_draw[t]) << "host thread " << t;
  }
}

}  // namespace
}  // namespace tessera
