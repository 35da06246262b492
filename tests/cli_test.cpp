// tessera-render, the command-line renderer (samples/tessera_render.cpp), run as a user runs
// it: it renders the demo scene, captures and meshes to images and reports its speed; bad
// arguments and bad files end it with a non-zero exit, one line on stderr that names the
// argument or file, and no image.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tessera/io.hpp"
#include "tessera/tessera.hpp"
#include "tests/temp_dir.hpp"

namespace tessera {
namespace {

using test::read_file;
using test::TempDir;
using test::write_file;

// For the shell. (Built with append: GCC 12 warns falsely about "'" + s + "'" here.)
std::string quoted(const std::filesystem::path& path) {
  std::string s(1, '\'');
  s.append(path.string());
  s.push_back('\'');
  return s;
}

struct RunResult {
  bool exited = false;  // false: killed by a signal
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs the program `exe` with `args` (already quoted where needed), capturing stdout and
// stderr.
RunResult run_program(const char* exe, const TempDir& dir, const std::string& args) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string command = quoted(exe) + " " + args + " >" + quoted(out) + " 2>" + quoted(err);
  const int status = std::system(command.c_str());
  RunResult r;
  r.exited = status != -1 && WIFEXITED(status);
  if (r.exited) r.exit_code = WEXITSTATUS(status);
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

RunResult run_render(const TempDir& dir, const std::string& args) {
  return run_program(TESSERA_RENDER_EXE, dir, args);
}

// The image at `path`, or an empty one and a test failure when it cannot be read.
Image read_image(const std::filesystem::path& path) {
  try {
    return tessera::read_image(path);
  } catch (const Error& e) {
    ADD_FAILURE() << e.what();
    return {};
  }
}

// The lines of `text` that start with `prefix`.
std::vector<std::string> lines_starting_with(const std::string& text, const std::string& prefix) {
  std::vector<std::string> found;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) == 0) found.push_back(line);
  }
  return found;
}

// A capture of a `width` x `height` frame filled by one triangle of colour `rgba`.
void write_filled_capture(const std::filesystem::path& path, uint32_t width, uint32_t height,
                          std::array<float, 4> rgba) {
  Capture c;
  c.width = width;
  c.height = height;
  c.positions = {{-1, -1, 0, 1}, {3, -1, 0, 1}, {-1, 3, 0, 1}};
  for (int v = 0; v < 3; ++v)
    c.varyings.insert(c.varyings.end(), rgba.begin(), rgba.end());
  save_capture(path, c);
}

TEST(Cli, DemoSceneWritesAPngAndPrintsTheThroughput) {
  TempDir dir;
  const RunResult r =
      run_render(dir, "--width 96 --height 64 --samples 1 -o " + quoted(dir / "demo.png"));
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("Mtri/s"), std::string::npos) << r.out;
  const Image image = read_image(dir / "demo.png");
  EXPECT_EQ(image.width, 96);
  EXPECT_EQ(image.height, 64);
  EXPECT_EQ(image.channels, 4);
  // The scene is drawn: the centre pixel is not the clear colour (0.08, 0.09, 0.11).
  const float* centre = image.at(48, 32);
  EXPECT_GT(std::abs(centre[0] - 0.08f) + std::abs(centre[1] - 0.09f) + std::abs(centre[2] - 0.11f),
            0.05f);
}

TEST(Cli, CaptureRendersAtItsOwnSizeInItsColours) {
  TempDir dir;
  write_filled_capture(dir / "green.tri", 8, 6, {0.0f, 1.0f, 0.0f, 1.0f});
  const RunResult r =
      run_render(dir, quoted(dir / "green.tri") + " -o " + quoted(dir / "green.png"));
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const Image image = read_image(dir / "green.png");
  ASSERT_EQ(image.width, 8);
  ASSERT_EQ(image.height, 6);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 8; ++x) {
      EXPECT_EQ(image.at(x, y)[0], 0.0f) << x << "," << y;
      EXPECT_EQ(image.at(x, y)[1], 1.0f) << x << "," << y;
      EXPECT_EQ(image.at(x, y)[2], 0.0f) << x << "," << y;
    }
  }
}

TEST(Cli, BlendOptionsBlendWithTheirOpenGLFactors) {
  // A triangle of (1, 0.5, 0, 0.5) over the clear colour (0.2, 0.4, 0.6, 1), stored as bytes
  // (51, 102, 153, 255).
  TempDir dir;
  write_filled_capture(dir / "half.tri", 8, 6, {1.0f, 0.5f, 0.0f, 0.5f});
  struct Case {
    const char* blend;
    std::array<int, 3> rgb;
  };
  // over: 0.5 s + 0.5 d; add: s + d; multiply: s d; premultiplied: s + 0.5 d.
  const Case cases[] = {{"over", {153, 115, 77}},
                        {"add", {255, 230, 153}},
                        {"multiply", {51, 51, 0}},
                        {"premultiplied", {255, 179, 77}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.blend);
    const RunResult r =
        run_render(dir, quoted(dir / "half.tri") + " --clear 0.2,0.4,0.6,1 --no-depth-write" +
                            " --blend " + c.blend + " -o " + quoted(dir / "blend.png"));
    ASSERT_TRUE(r.exited);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Image image = read_image(dir / "blend.png");
    ASSERT_EQ(image.width, 8);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_EQ(std::lround(image.at(3, 2)[ch] * 255.0f), c.rgb[ch]) << ch;
  }
}

TEST(Cli, ScissorDrawsOnlyInsideTheRectangle) {
  TempDir dir;
  write_filled_capture(dir / "green.tri", 16, 12, {0.0f, 1.0f, 0.0f, 1.0f});
  const RunResult r = run_render(
      dir, quoted(dir / "green.tri") + " --scissor 3,2,5,4 -o " + quoted(dir / "cut.png"));
  ASSERT_TRUE(r.exited);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image image = read_image(dir / "cut.png");
  ASSERT_EQ(image.width, 16);
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 16; ++x) {
      const bool in = x >= 3 && x < 8 && y >= 2 && y < 6;
      EXPECT_EQ(image.at(x, y)[1] == 1.0f, in) << x << "," << y;
    }
  }
  const RunResult bad = run_render(
      dir, quoted(dir / "green.tri") + " --scissor 0,0,-4,4 -o " + quoted(dir / "bad.png"));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--scissor: width -4 is out of range"), std::string::npos) << bad.err;
}

// A TRI2 capture of one screen-filling triangle with Phong's ten varyings: an eye-space normal
// (0, 0, 1), the eye-space position of a plane at z = -2 (x, y from -2 to 6), a white base
// colour.
void write_phong_capture(const std::filesystem::path& path) {
  Capture c;
  c.width = 16;
  c.height = 16;
  c.varying_count = 10;
  const float xy[3][2] = {{-1, -1}, {3, -1}, {-1, 3}};
  for (const auto& p : xy) {
    c.positions.push_back({p[0], p[1], 0.0f, 1.0f});
    c.varyings.insert(c.varyings.end(),
                      {0, 0, 1, 2 * p[0], 2 * p[1], -2.0f, 1.0f, 1.0f, 1.0f, 1.0f});
  }
  save_capture(path, c);
}

TEST(Cli, Tri2CapturesDrawWithTheShadingAsked) {
  TempDir dir;
  write_phong_capture(dir / "phong.tri");
  const std::string in = quoted(dir / "phong.tri") + " ";
  // Per-pixel Phong with a light in front of the plane's centre: brightest under the light, the
  // same in both backends to a step.
  for (const char* backend : {"fast", "reference"}) {
    RunResult r = run_render(dir, in + "--shading phong --backend " + backend +
                                      " --light 0,0,-1 -o " + quoted(dir / "phong.png"));
    ASSERT_TRUE(r.exited && r.exit_code == 0) << r.err;
    const Image lit = read_image(dir / "phong.png");
    EXPECT_GT(lit.at(8, 8)[0], lit.at(1, 1)[0] + 0.1f) << backend;  // (0, 0) in eye space
    EXPECT_GT(lit.at(1, 1)[0], 0.1f) << backend;                    // against (-1.75, 1.75)
  }
  // Gouraud reads varyings 0..3: the normal (0, 0, 1) and x as alpha. The PNG keeps the colour
  // as drawn (straight alpha): blue 1 also where alpha is below 1.
  RunResult r = run_render(dir, in + "-o " + quoted(dir / "gouraud.png"));
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r.err;
  const Image gouraud = read_image(dir / "gouraud.png");
  EXPECT_EQ(gouraud.at(13, 5)[2], 1.0f);
  EXPECT_EQ(gouraud.at(13, 5)[3], 1.0f);
  EXPECT_EQ(gouraud.at(1, 5)[2], 1.0f);
  EXPECT_LT(gouraud.at(1, 5)[3], 1.0f);
  // Normals into an EXR, from either backend.
  for (const char* backend : {"fast", "reference"}) {
    r = run_render(dir,
                   in + "--shading normals --backend " + backend + " -o " + quoted(dir / "n.exr"));
    ASSERT_TRUE(r.exited && r.exit_code == 0) << r.err;
    EXPECT_EQ(read_image(dir / "n.exr").at(3, 3)[2], 1.0f) << backend;
    EXPECT_EQ(read_image(dir / "n.exr").at(3, 3)[0], 0.0f) << backend;
  }
  // Float outputs need a float file; lights need Phong.
  r = run_render(dir, in + "--shading depth -o " + quoted(dir / "d.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(".exr"), std::string::npos) << r.err;
  r = run_render(dir, in + "--light 1,2 --shading phong -o " + quoted(dir / "x.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--light: 1,2 is not x,y,z"), std::string::npos) << r.err;
}

TEST(Cli, MeshRendersFramedInTheImage) {
  TempDir dir;
  write_file(dir / "quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  const RunResult r = run_render(dir, quoted(dir / "quad.obj") +
                                          " --width 40 --height 30 --samples 1 --eye 0,0,5 -o " +
                                          quoted(dir / "quad.png"));
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 triangles"), std::string::npos) << r.out;
  const Image image = read_image(dir / "quad.png");
  ASSERT_EQ(image.width, 40);
  const float* centre = image.at(20, 15);
  const float* corner = image.at(0, 0);
  EXPECT_GT(centre[0], 0.3f);                 // the lit grey quad
  EXPECT_NEAR(corner[0], 0.08f, 1.0f / 255);  // the clear colour around it
}

TEST(Cli, RepeatPrintsOneSummaryLineWithTheFrameCount) {
  TempDir dir;
  const RunResult r = run_render(
      dir, "--repeat 3 --width 64 --height 48 --samples 1 -o " + quoted(dir / "repeat.png"));
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_starting_with(r.out, "frames=3 median_ms=");
  ASSERT_EQ(lines.size(), 1u) << r.out;
  double median = -1, min = -1, max = -1, mtri = -1;
  ASSERT_EQ(std::sscanf(lines[0].c_str(), "frames=3 median_ms=%lf min_ms=%lf max_ms=%lf mtri_s=%lf",
                        &median, &min, &max, &mtri),
            4)
      << lines[0];
  EXPECT_GT(min, 0.0) << lines[0];
  EXPECT_LE(min, median) << lines[0];
  EXPECT_LE(median, max) << lines[0];
  EXPECT_GT(mtri, 0.0) << lines[0];
}

TEST(Cli, TheReferenceBackendDrawsTheFastEnginesImageAndEachNamesItself) {
  // Triangles of one colour each, at distinct depths, overlapping: coverage and the depth test
  // decide every pixel, and the two backends agree on both exactly.
  TempDir dir;
  Capture c;
  c.width = 48;
  c.height = 40;
  const float tris[][6] = {{-0.9f, -0.8f, 0.7f, -0.6f, -0.2f, 0.9f},
                           {-0.5f, 0.7f, 0.8f, 0.6f, 0.1f, -0.9f},
                           {-1.0f, 0.0f, 0.3f, -0.95f, 0.9f, 0.95f},
                           {0.2f, 0.2f, 0.25f, 0.21f, 0.22f, 0.3f}};
  for (int t = 0; t < 4; ++t) {
    const float z = 0.8f - 0.15f * static_cast<float>(t);
    for (int v = 0; v < 3; ++v) {
      c.positions.push_back({tris[t][2 * v], tris[t][2 * v + 1], z, 1.0f});
      const float rgba[4] = {t == 0 ? 1.0f : 0.0f, t == 1 ? 1.0f : 0.0f, t >= 2 ? 1.0f : 0.0f,
                             1.0f};
      c.varyings.insert(c.varyings.end(), rgba, rgba + 4);
    }
  }
  save_capture(dir / "tris.tri", c);
  const RunResult fast =
      run_render(dir, quoted(dir / "tris.tri") + " -s 4 -o " + quoted(dir / "fast.png"));
  const RunResult reference = run_render(
      dir, quoted(dir / "tris.tri") + " -s 4 --backend reference -o " + quoted(dir / "ref.png"));
  ASSERT_TRUE(fast.exited && reference.exited);
  ASSERT_EQ(fast.exit_code, 0) << fast.err;
  ASSERT_EQ(reference.exit_code, 0) << reference.err;
  EXPECT_NE(fast.out.find("backend fast"), std::string::npos) << fast.out;
  EXPECT_NE(reference.out.find("backend reference"), std::string::npos) << reference.out;
  const Image a = read_image(dir / "fast.png"), b = read_image(dir / "ref.png");
  ASSERT_EQ(a.width, 48);
  ASSERT_EQ(b.width, 48);
  int drawn = 0;
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 48; ++x) {
      for (int k = 0; k < 4; ++k)
        ASSERT_EQ(a.at(x, y)[k], b.at(x, y)[k]) << x << "," << y << " channel " << k;
      drawn += a.at(x, y)[0] + a.at(x, y)[1] + a.at(x, y)[2] > 0.0f;
    }
  }
  EXPECT_GT(drawn, 48 * 40 / 2);
}

TEST(Cli, DepthOptionWritesTheDepthBufferAsAnExr) {
  TempDir dir;
  const RunResult r =
      run_render(dir, "--width 64 --height 48 --samples 1 -o " + quoted(dir / "colour.png") +
                          " --depth " + quoted(dir / "depth.exr"));
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(dir / "depth.exr").substr(0, 4), std::string("\x76\x2f\x31\x01", 4));
  const Image depth = read_image(dir / "depth.exr");
  ASSERT_EQ(depth.width, 64);
  ASSERT_EQ(depth.height, 48);
  ASSERT_EQ(depth.channels, 1);
  float nearest = 1.0f;
  for (float d : depth.pixels) {
    ASSERT_GE(d, 0.0f);
    ASSERT_LE(d, 1.0f);
    nearest = std::min(nearest, d);
  }
  EXPECT_LT(nearest, 1.0f);  // something was drawn in front of the far plane
}

TEST(Cli, HelpPrintsTheUsageAndExitsZero) {
  TempDir dir;
  const RunResult r = run_render(dir, "--help");
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--samples"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST(Cli, BlockSizeAndBinTileDrawTheSameImage) {
  TempDir dir;
  const std::string common = "--width 160 --height 96 --samples 4 --threads 2 -o ";
  const RunResult standard = run_render(dir, common + quoted(dir / "standard.png"));
  ASSERT_TRUE(standard.exited);
  ASSERT_EQ(standard.exit_code, 0) << standard.err;
  const std::string image = read_file(dir / "standard.png");
  for (const std::string options :
       {"--block-size 16", "--block-size 32", "--block-size 32 --bin-tile 128",
        "--block-size 16 --bin-tile 32", "--block-size 8"}) {
    const RunResult r = run_render(dir, options + " " + common + quoted(dir / "other.png"));
    ASSERT_TRUE(r.exited);
    EXPECT_EQ(r.exit_code, 0) << options << ": " << r.err;
    EXPECT_EQ(read_file(dir / "other.png"), image) << options;
  }
}

// --- Bad arguments and bad files ---------------------------------------------------------------

struct BadRun {
  const char* name;    // for the test's name
  std::string args;    // {dir} is replaced by the test's directory
  std::string needle;  // what the message must name
};

void PrintTo(const BadRun& b, std::ostream* os) {
  *os << b.name;
}

class CliRejects : public ::testing::TestWithParam<BadRun> {};

std::string replace_dir(const std::string& s, const TempDir& dir) {
  std::string out;
  size_t from = 0;
  for (size_t at; (at = s.find("{dir}", from)) != std::string::npos; from = at + 5) {
    out.append(s, from, at - from);
    out += dir.path().string();
  }
  out.append(s, from, std::string::npos);
  return out;
}

TEST_P(CliRejects, WithANonZeroExitOneLineOnStderrNamingTheProblemAndNoImage) {
  TempDir dir;
  write_file(dir / "cut.tri", std::string("TRI1\x08\0\0\0\x06\0\0\0\x01\0\0\0", 16) + "short");
  write_file(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  write_filled_capture(dir / "ok.tri", 8, 6, {1.0f, 0.0f, 0.0f, 1.0f});
  const BadRun& b = GetParam();
  const RunResult r = run_render(dir, replace_dir(b.args, dir) + " -o " + quoted(dir / "out.png"));
  ASSERT_TRUE(r.exited) << "killed by a signal; stderr: " << r.err;
  EXPECT_NE(r.exit_code, 0);
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  EXPECT_NE(r.err.find(b.needle), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
}

INSTANTIATE_TEST_SUITE_P(
    BadInput, CliRejects,
    ::testing::Values(BadRun{"UnknownFlag", "--sideways", "--sideways"},
                      BadRun{"SampleCountThree", "--samples 3", "--samples"},
                      BadRun{"WidthZero", "--width 0", "--width"},
                      BadRun{"HeightAboveTheLimit", "--height 16385", "--height"},
                      BadRun{"WidthNotANumber", "--width wide", "--width"},
                      BadRun{"CullSideways", "--cull sideways", "--cull"},
                      BadRun{"FovNaN", "--fov nan", "--fov"},
                      BadRun{"EyeWithTwoValues", "--eye 1,2", "--eye"},
                      BadRun{"EyeAtTheTarget", "--eye 0,0,5 --target 0,0,5", "--eye"},
                      BadRun{"UpAlongTheView", "--eye 0,0,5 --target 0,0,0 --up 0,0,1", "--up"},
                      BadRun{"ClearNaN", "--clear 0,nan,0,1", "--clear"},
                      BadRun{"FramebufferPastTheMemoryLimit",
                             "--width 16384 --height 16384 --samples 16", "16 samples"},
                      BadRun{"MissingMeshFile", "{dir}/missing.obj", "missing.obj"},
                      BadRun{"MissingCaptureFile", "{dir}/missing.tri", "missing.tri"},
                      BadRun{"TruncatedCapture", "{dir}/cut.tri", "cut.tri"},
                      BadRun{"MeshIndexOutOfRange", "{dir}/bad.obj", "bad.obj"},
                      BadRun{"SizeGivenForACapture", "{dir}/ok.tri --width 64", "--width"},
                      BadRun{"WireframeAndPoints", "--wireframe --points", "--wireframe"},
                      BadRun{"WireframeOfACapture", "{dir}/ok.tri --wireframe", "--wireframe"},
                      BadRun{"PointSizeZero", "--points --point-size 0", "--point-size"},
                      BadRun{"LineAlgorithmUnknown", "--line-algorithm wu", "--line-algorithm"},
                      BadRun{"BlockSizeTwelve", "--block-size 12", "--block-size"},
                      BadRun{"BinBudgetNaN", "--bin-budget nan", "--bin-budget"},
                      BadRun{"UnwritableDepthPath",
                             "--width 8 --height 8 --depth {dir}/no/such/depth.exr", "depth.exr"}),
    [](const ::testing::TestParamInfo<BadRun>& p) { return std::string(p.param.name); });

// A draw whose bins the budget allows but memory does not (40,000 full-screen triangles over
// 16,384 tiles of 32 pixels: 2.6 GB of references under a 65536 MiB budget, in a process
// limited to 1.5 GB of address space) ends with the engine's out-of-memory error, which names
// the budget, not with std::bad_alloc. (The sanitizers reserve more address space than that.)
TEST(Cli, ADrawPastTheMemoryThereIsIsAnOutOfMemoryErrorNamingTheBudget) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define TESSERA_TEST_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define TESSERA_TEST_SANITIZER 1
#endif
#endif
#ifdef TESSERA_TEST_SANITIZER
  GTEST_SKIP() << "the sanitizer needs more address space than the limit";
#else
  if (std::system("prlimit --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "no prlimit";
  TempDir dir;
  Capture c;
  c.width = 4096;
  c.height = 4096;
  for (int i = 0; i < 40000; ++i) {
    c.positions.insert(c.positions.end(), {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1}});
    for (int v = 0; v < 3; ++v)
      c.varyings.insert(c.varyings.end(), {1, 0, 0, 1});
  }
  save_capture(dir / "full.tri", c);
  const std::string command = "prlimit --as=1500000000 " + quoted(TESSERA_RENDER_EXE) + " " +
                              quoted(dir / "full.tri") +
                              " -s 1 --threads 1 --bin-tile 32 --bin-budget 65536 -o " +
                              quoted(dir / "full.png") + " 2>" + quoted(dir / "err.txt");
  const int status = std::system(command.c_str());
  ASSERT_TRUE(status != -1 && WIFEXITED(status)) << "killed by a signal";
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = read_file(dir / "err.txt");
  EXPECT_NE(err.find("out of memory for the bins (bin memory budget 65536 MiB); a smaller budget"),
            std::string::npos)
      << err;
  EXPECT_FALSE(std::filesystem::exists(dir / "full.png"));
#endif
}

// Pixels of an image that differ from the default clear colour (0.08, 0.09, 0.11).
int drawn_pixels(const Image& image) {
  int n = 0;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const float* p = image.at(x, y);
      n += std::abs(p[0] - 0.08f) + std::abs(p[1] - 0.09f) + std::abs(p[2] - 0.11f) > 0.02f;
    }
  }
  return n;
}

TEST(Cli, WireframeDrawsEdgesWithHiddenLinesRemoved) {
  TempDir dir;
  // A cube: seen from a corner, three faces are in front and three behind.
  write_file(dir / "cube.obj",
             "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  const std::string common = quoted(dir / "cube.obj") + " --width 96 --height 96 --samples 1 ";
  auto pixels = [&](const std::string& args, const char* name) {
    const RunResult r = run_render(dir, common + args + " -o " + quoted(dir / name));
    EXPECT_TRUE(r.exited && r.exit_code == 0) << r.err;
    return drawn_pixels(read_image(dir / name));
  };
  const int filled = pixels("", "filled.png");
  const int hidden_removed = pixels("--wireframe", "wire.png");
  const int all_edges = pixels("--wireframe --no-depth", "all.png");
  // Reversed Z pushes the hidden-surface pass the other way: the same edges stay visible.
  const int reversed = pixels("--wireframe --reversed-z", "reversed.png");
  EXPECT_NEAR(reversed, hidden_removed, hidden_removed / 50);
  EXPECT_GT(hidden_removed, 50);
  EXPECT_LT(hidden_removed, all_edges);  // the edges behind the front faces are hidden
  EXPECT_LT(all_edges, filled);
  const RunResult r = run_render(dir, common + "--wireframe -o " + quoted(dir / "w.png"));
  EXPECT_NE(r.out.find("(wireframe)"), std::string::npos) << r.out;
}

TEST(Cli, PlyPointCloudRendersAsPoints) {
  TempDir dir;
  write_file(dir / "cloud.ply",
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
             "end_header\n0 0 0 255 0 0\n1 0 0 255 0 0\n0 1 0 255 0 0\n");
  const RunResult r = run_render(dir, quoted(dir / "cloud.ply") +
                                          " --width 64 --height 64 --samples 1 --point-size 5 -o " +
                                          quoted(dir / "cloud.png"));
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(points)"), std::string::npos) << r.out;
  const Image image = read_image(dir / "cloud.png");
  int red = 0;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x)
      red += image.at(x, y)[0] == 1.0f && image.at(x, y)[1] == 0.0f;
  }
  EXPECT_EQ(red, 3 * 25);  // three 5x5 squares, apart
}

TEST(Cli, UnwritableOutputPathIsRejectedNamingIt) {
  TempDir dir;
  const RunResult r = run_render(dir, "--width 8 --height 8 -o " + quoted(dir / "no" / "such.png"));
  ASSERT_TRUE(r.exited);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  EXPECT_NE(r.err.find("such.png"), std::string::npos) << r.err;
}

// --aov writes extra render targets from the colour's pass: each holds what --shading of that
// output writes alone, IDs exactly, "none" where nothing was drawn.
TEST(Cli, AovsWriteTheVisionOutputsOfTheColoursPass) {
  TempDir dir;
  const std::string size = "--width 96 --height 64 --samples 1 ";
  const RunResult r = run_render(
      dir, size + "-o " + quoted(dir / "colour.png") + " --aov normals=" + quoted(dir / "n.exr") +
               " --aov depth=" + quoted(dir / "d.exr") + " --aov objects=" + quoted(dir / "o.exr"));
  ASSERT_TRUE(r.exited);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("o.exr"), std::string::npos) << r.out;
  const auto alone = [&](const std::string& shading, const std::string& name) {
    const RunResult one =
        run_render(dir, size + "--shading " + shading + " -o " + quoted(dir / name));
    EXPECT_EQ(one.exit_code, 0) << one.err;
    return read_image(dir / name);
  };
  const Image colour = read_image(dir / "colour.png");
  const Image colour_alone = [&] {
    run_render(dir, size + "-o " + quoted(dir / "c1.png"));
    return read_image(dir / "c1.png");
  }();
  const Image normals = read_image(dir / "n.exr"), normals_alone = alone("normals", "n1.exr");
  const Image depth = read_image(dir / "d.exr"), depth_alone = alone("depth", "d1.exr");
  const Image objects = read_image(dir / "o.exr"), objects_alone = alone("objects", "o1.exr");
  // OpenImageIO reads 32-bit unsigned channels as value / (2^32 - 1).
  const auto id_at = [](const Image& image, size_t i) {
    return static_cast<float>(std::llround(double{image.pixels[i]} * 4294967295.0));
  };
  ASSERT_EQ(normals.channels, 3u);
  ASSERT_EQ(depth.channels, 1u);
  ASSERT_EQ(objects.channels, 1u);
  ASSERT_EQ(objects.pixels.size(), size_t{96 * 64});
  size_t background = 0;
  std::vector<int> seen(8, 0);
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 96; ++x) {
      const float id = id_at(objects, size_t{y} * 96 + x);
      ASSERT_EQ(id, objects_alone.at(x, y)[0]) << x << "," << y;
      ASSERT_EQ(id, std::floor(id));
      ASSERT_GE(id, 0.0f);
      ASSERT_LT(id, 8.0f);
      seen[static_cast<size_t>(id)] = 1;
      background += id == 0;
      ASSERT_LE(std::abs(depth.at(x, y)[0] - depth_alone.at(x, y)[0]),
                2e-6f * depth_alone.at(x, y)[0])
          << x << "," << y;
      ASSERT_EQ(id == 0, depth.at(x, y)[0] == 0.0f) << x << "," << y;
      for (uint32_t c = 0; c < 3; ++c) {
        ASSERT_LE(std::abs(normals.at(x, y)[c] - normals_alone.at(x, y)[c]), 2e-6f)
            << x << "," << y;
        ASSERT_LE(std::abs(colour.at(x, y)[c] - colour_alone.at(x, y)[c]), 1.0f / 255 + 1e-6f)
            << x << "," << y;
      }
    }
  }
  EXPECT_GT(background, 0u);
  EXPECT_GE(std::count(seen.begin() + 1, seen.end(), 1), 3);  // several objects in view

  // Triangle indices: exact integers, 4294967295 where no triangle was drawn.
  const RunResult ids =
      run_render(dir, size + "-o " + quoted(dir / "c.png") + " --aov ids=" + quoted(dir / "i.exr") +
                          " --aov objects=" + quoted(dir / "o2.exr"));
  ASSERT_EQ(ids.exit_code, 0) << ids.err;
  const Image triangles = read_image(dir / "i.exr"), objects2 = read_image(dir / "o2.exr");
  ASSERT_EQ(triangles.pixels.size(), objects2.pixels.size());
  size_t drawn = 0;
  for (size_t i = 0; i < triangles.pixels.size(); ++i) {
    const float t = id_at(triangles, i);
    ASSERT_EQ(id_at(objects2, i) == 0, t == 4294967295.0f) << i;
    if (id_at(objects2, i) != 0) {
      ASSERT_LT(t, 49920.0f) << i;
    }
    drawn += id_at(objects2, i) != 0;
  }
  EXPECT_GT(drawn, 96u * 64 / 4);

  // Colour lit per vertex beside the extra targets, as without them.
  const RunResult gouraud = run_render(dir, size + "--shading gouraud -o " + quoted(dir / "g.png") +
                                                " --aov objects=" + quoted(dir / "o3.exr"));
  ASSERT_EQ(gouraud.exit_code, 0) << gouraud.err;
  run_render(dir, size + "--shading gouraud -o " + quoted(dir / "g1.png"));
  const Image lit = read_image(dir / "g.png"), lit_alone = read_image(dir / "g1.png");
  ASSERT_EQ(lit.pixels.size(), lit_alone.pixels.size());
  for (size_t i = 0; i < lit.pixels.size(); ++i)
    ASSERT_LE(std::abs(lit.pixels[i] - lit_alone.pixels[i]), 1.0f / 255 + 1e-6f) << i;
}

TEST(Cli, BadAovsAreOneLineErrorsNamingThem) {
  TempDir dir;
  const std::string out = "--width 16 --height 16 -o " + quoted(dir / "c.png") + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--aov colours=" + quoted(dir / "a.exr"), "colours"},
      {"--aov normals=" + quoted(dir / "a.png"), "a.png"},
      {"--aov normals", "kind=path"},
      {"--aov depth=" + quoted(dir / "no" / "a.exr"), "does not exist"},
      {"--aov depth=" + quoted(dir / "1.exr") + " --aov ids=" + quoted(dir / "2.exr") +
           " --aov objects=" + quoted(dir / "3.exr") + " --aov normals=" + quoted(dir / "4.exr"),
       "at most 3"},
      {"--wireframe --aov depth=" + quoted(dir / "a.exr"), "--wireframe"},
  };
  for (const auto& [args, words] : cases) {
    const RunResult r = run_render(dir, out + args);
    ASSERT_TRUE(r.exited) << args;
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << args << ": " << r.err;
  }
}

// TRI2 replay with a texture: (u, v) from varyings 0 and 1. A full-window quad whose (u, v) runs
// over [0, 1] at the texture's own size draws each texel on its pixel, with every filter.
TEST(Cli, Tri2CapturesReplayTextured) {
  TempDir dir;
  constexpr uint32_t w = 24, h = 16;
  std::vector<uint8_t> texels(w * h * 4);
  for (size_t i = 0; i < texels.size(); ++i)
    texels[i] = i % 4 == 3 ? 255 : static_cast<uint8_t>((i * 37 + i / 7) % 256);
  write_image(dir / "texture.png", w, h, 4, std::span<const uint8_t>(texels));
  Capture c;
  c.width = w;
  c.height = h;
  c.varying_count = 2;
  c.positions = {{-1, 1, 0, 1}, {1, 1, 0, 1},  {1, -1, 0, 1},
                 {-1, 1, 0, 1}, {1, -1, 0, 1}, {-1, -1, 0, 1}};
  c.varyings = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
  save_capture(dir / "uv.tri", c);
  const Image want = read_image(dir / "texture.png");
  for (const char* filter : {"nearest", "bilinear", "trilinear"}) {
    for (const char* backend : {"fast", "reference"}) {
      const RunResult r =
          run_render(dir, quoted(dir / "uv.tri") + " --shading textured --texture " +
                              quoted(dir / "texture.png") + " --filter " + filter + " --backend " +
                              backend + " -o " + quoted(dir / "out.png"));
      ASSERT_TRUE(r.exited);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(read_image(dir / "out.png").pixels, want.pixels) << filter << ", " << backend;
    }
  }
  // Clamp to border outside [0, 1]: the quad's (u, v) over [-1, 2] shows the border colour
  // around the texture.
  for (float& v : c.varyings)
    v = 3 * v - 1;
  save_capture(dir / "wide.tri", c);
  const RunResult r = run_render(dir, quoted(dir / "wide.tri") + " --shading textured --texture " +
                                          quoted(dir / "texture.png") +
                                          " --filter nearest --wrap border --border-color 0,1,0,1 "
                                          "-o " +
                                          quoted(dir / "border.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image border = read_image(dir / "border.png");
  EXPECT_EQ(border.at(0, 0)[1], 1.0f);
  EXPECT_EQ(border.at(0, 0)[0], 0.0f);
  // Pixel (12, 8): u = 12.5 / 24 * 3 - 1 = 0.5625, v = 8.5 / 16 * 3 - 1 = 0.59375: texel (13, 9).
  for (uint32_t k = 0; k < 4; ++k)
    EXPECT_EQ(border.at(12, 8)[k], want.at(13, 9)[k]) << k;

  // Errors: one line naming what was wrong.
  c.varying_count = 1;
  c.varyings.assign(6, 0.5f);
  save_capture(dir / "one.tri", c);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {quoted(dir / "uv.tri") + " --shading textured --texture " + quoted(dir / "none.png"),
       "none.png"},
      {quoted(dir / "uv.tri") + " --shading textured", "--texture"},
      {quoted(dir / "uv.tri") + " --texture " + quoted(dir / "texture.png"), "--shading textured"},
      {quoted(dir / "one.tri") + " --shading textured --texture " + quoted(dir / "texture.png"),
       "varyings 0 and 1"},
      {"--shading textured --texture " + quoted(dir / "texture.png"), "TRI2"},
      {quoted(dir / "uv.tri") + " --shading textured --filter cubic --texture " +
           quoted(dir / "texture.png"),
       "--filter"},
  };
  for (const auto& [args, words] : cases) {
    const RunResult bad = run_render(dir, args + " -o " + quoted(dir / "bad.png"));
    ASSERT_TRUE(bad.exited) << args;
    EXPECT_NE(bad.exit_code, 0) << args;
    EXPECT_EQ(bad.err.find('\n'), bad.err.size() - 1) << "not one line: " << bad.err;
    EXPECT_NE(bad.err.find(words), std::string::npos) << args << ": " << bad.err;
  }
}

// tessera-occlusion (samples/tessera_occlusion.cpp): a wall over the left half of a 64 x 48
// frame at depth 0.5; queries of two triangles each, behind the wall, in front of it, and
// behind it but reaching past its edge: one answer line each in both modes, then the summary.
// A missing capture is a one-line error naming it.
TEST(Cli, OcclusionToolAnswersOneLinePerQuery) {
  const TempDir dir;
  const auto quad = [](float x0, float x1, float z) {
    return std::vector<Float4>{{x0, 1, z, 1}, {x1, 1, z, 1},  {x1, -1, z, 1},
                               {x0, 1, z, 1}, {x1, -1, z, 1}, {x0, -1, z, 1}};
  };
  const auto capture = [](std::vector<Float4> positions) {
    Capture c;
    c.width = 64;
    c.height = 48;
    c.varyings.assign(positions.size() * 4, 1.0f);
    c.positions = std::move(positions);
    return c;
  };
  save_capture(dir / "walls.tri", capture(quad(-1, 0, 0.5f)));
  std::vector<Float4> queries = quad(-0.9f, -0.1f, 0.8f);
  for (const std::vector<Float4>& q : {quad(-0.9f, -0.1f, 0.2f), quad(-0.5f, 0.5f, 0.8f)})
    queries.insert(queries.end(), q.begin(), q.end());
  save_capture(dir / "queries.tri", capture(queries));
  for (const char* mode : {"conservative", "exact"}) {
    const RunResult r = run_program(TESSERA_OCCLUSION_EXE, dir,
                                    "--occluders " + quoted(dir / "walls.tri") + " --queries " +
                                        quoted(dir / "queries.tri") + " --group 2 --mode " + mode);
    ASSERT_TRUE(r.exited && r.exit_code == 0) << r.err;
    EXPECT_EQ(r.out.substr(0, 6), "0\n1\n1\n") << mode << ": " << r.out;
    EXPECT_EQ(lines_starting_with(r.out, "occluders: 2 triangles").size(), 1u) << r.out;
    EXPECT_NE(r.out.find("queries: 3 (" + std::string(mode) +
                         ", 2 triangles each), 2 visible, 1 "
                         "hidden"),
              std::string::npos)
        << r.out;
  }
  const RunResult bad = run_program(
      TESSERA_OCCLUSION_EXE, dir,
      "--occluders " + quoted(dir / "missing.tri") + " --queries " + quoted(dir / "queries.tri"));
  EXPECT_TRUE(bad.exited && bad.exit_code != 0);
  EXPECT_NE(bad.err.find("missing.tri"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

}  // namespace
}  // namespace tessera
