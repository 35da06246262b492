/* Tessera's C API: the renderer, framebuffers, pipeline state and draws of the C++ API
 * (tessera/renderer.hpp) behind opaque handles and plain structs, for C programs and for other
 * languages' foreign-function interfaces. Compiles as C11 and as C++; links against the
 * Tessera::tessera library (which is C++, so link with a C++ linker or add the C++ runtime).
 *
 * Every function that can fail returns a tessera_result and never throws or aborts: TESSERA_OK,
 * or an error code with a one-line message naming the function, the argument and the problem,
 * read with tessera_last_error_message() on the same thread. The checks are the C++ API's own
 * (the same messages); the C layer adds only those C needs: NULL handles and pointers, counts
 * too large for memory, enumeration values that do not fit the C++ type, read-back buffers that
 * are too small. A failing call changes nothing it was given, except as the C++ API documents
 * (a draw that runs out of memory leaves part of its primitives drawn) and that an output
 * handle pointer is set to NULL.
 *
 * Threads: a handle may be used from any thread, but not from two at once; a draw uses its
 * renderer and its framebuffer until it returns. Distinct renderers and framebuffers are
 * independent. The last error is per thread.
 *
 * Memory: see tessera_allocator. Guide: docs/API.md. */
#ifndef TESSERA_TESSERA_H_
#define TESSERA_TESSERA_H_

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "tessera/export.hpp"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Errors ------------------------------------------------------------------------------ */

typedef enum tessera_result {
  TESSERA_OK = 0,
  /* A parameter out of range or inconsistent with another; a NULL handle or pointer; an
   * enumeration value that names nothing; a read-back buffer too small for the image. */
  TESSERA_ERROR_INVALID_ARGUMENT = 1,
  /* Vertex data or indices that cannot be drawn: a NaN or infinite value, an index past the
   * vertices, a count that does not make whole primitives. */
  TESSERA_ERROR_INVALID_INPUT = 2,
  /* A file that cannot be read or written (no function of this header reads files yet). */
  TESSERA_ERROR_IO = 3,
  /* An allocation that failed: the allocator callback returned NULL, or the library's own. */
  TESSERA_ERROR_OUT_OF_MEMORY = 4,
  /* A valid state that the renderer's backend cannot draw (the message names the state). */
  TESSERA_ERROR_UNSUPPORTED = 5,
  /* Anything else the library did not expect; a bug to report, with the message. */
  TESSERA_ERROR_INTERNAL = 6,
  TESSERA_RESULT_MAX_ENUM = 0x7FFFFFFF
} tessera_result;

/* The result of the calling thread's last call into this API that returns a tessera_result
 * (TESSERA_OK after a success). */
TESSERA_API tessera_result tessera_last_error(void);
/* Its message: "" after a success, else one line such as "tessera_draw_triangles: position of
 * vertex 1 is not finite: (nan, 0, 0.5, 1)". Never NULL. The text belongs to the thread and
 * stays valid until its next call into this API; messages longer than 1023 bytes are cut. */
TESSERA_API const char* tessera_last_error_message(void);
/* The name of a result code, e.g. "TESSERA_ERROR_INVALID_INPUT"; "unknown" for other values. */
TESSERA_API const char* tessera_result_name(tessera_result result);

/* ---- Memory ------------------------------------------------------------------------------ */

/* Allocation callbacks for a handle, as Masked Occlusion Culling takes them. alloc returns
 * `size` bytes aligned to `alignment` (a power of two), or NULL when it cannot; free releases
 * what alloc returned. Both get `user`. Both must be set; the struct is copied at creation and
 * used until the handle is destroyed.
 *
 * What goes through them: the handle object itself, that is the C++ tessera::Renderer or
 * tessera::Framebuffer object (a pointer to its state) and the copy of these callbacks, a few
 * dozen bytes. Everything that C++ object allocates comes from the C++ runtime (operator new)
 * or oneTBB instead: its state, the framebuffer's sample planes and Hi-Z bounds, the
 * renderer's bins, setups and scratch, its oneTBB arena and worker threads, and the temporary
 * resolved image of each read-back call (freed before it returns). The large buffers are
 * shared with the engine's SIMD kernels, which allocate them cache-aligned themselves. */
typedef struct tessera_allocator {
  void* (*alloc)(size_t size, size_t alignment, void* user);
  void (*free)(void* ptr, void* user);
  void* user;
} tessera_allocator;

/* ---- Limits ------------------------------------------------------------------------------ */

#define TESSERA_MAX_VARYINGS 32            /* floats per vertex (tessera::kMaxVaryings) */
#define TESSERA_MAX_LIGHTS 8               /* Phong lights (tessera::kMaxLights) */
#define TESSERA_MAX_FRAMEBUFFER_SIZE 16384 /* pixels per side (tessera::kMaxFramebufferSize) */
#define TESSERA_MAX_COLOR_TARGETS 4        /* colour targets (tessera::kMaxColorTargets) */

/* ---- Framebuffers ------------------------------------------------------------------------ */

/* The enumerations below have the values of the C++ enumerations of the same names. */
/* Target 0 is RGBA8 or RGBA32F; extra targets take any format: R32F one float, R32UI one
 * unsigned 32-bit integer (exact IDs). */
typedef enum tessera_color_format {
  TESSERA_COLOR_RGBA8 = 0,
  TESSERA_COLOR_RGBA32F = 1,
  TESSERA_COLOR_R32F = 2,
  TESSERA_COLOR_R32UI = 3,
  TESSERA_COLOR_FORMAT_MAX_ENUM = 0x7FFFFFFF
} tessera_color_format;

typedef enum tessera_depth_format {
  TESSERA_DEPTH_FLOAT32 = 0,
  TESSERA_DEPTH_UNORM24 = 1,
  TESSERA_DEPTH_UNORM16 = 2,
  TESSERA_DEPTH_FORMAT_MAX_ENUM = 0x7FFFFFFF
} tessera_depth_format;

/* tessera::FramebufferDesc. Zero formats are RGBA8 colour and float32 depth. */
typedef struct tessera_framebuffer_desc {
  uint32_t width;                    /* 1..TESSERA_MAX_FRAMEBUFFER_SIZE */
  uint32_t height;                   /* 1..TESSERA_MAX_FRAMEBUFFER_SIZE */
  uint32_t samples;                  /* 1, 2, 4, 8 or 16 */
  tessera_color_format color_format; /* target 0 */
  tessera_depth_format depth_format;
  /* Multiple render targets: targets 1..extra_targets (0..3) of these formats; each triangle
   * draw writes every target (tessera_pipeline_state.extra_outputs says what), points, lines
   * and polygons target 0 only. */
  uint32_t extra_targets;
  tessera_color_format extra_formats[TESSERA_MAX_COLOR_TARGETS - 1];
} tessera_framebuffer_desc;

/* Colour and depth for every sample of every pixel (tessera::Framebuffer). */
typedef struct tessera_framebuffer tessera_framebuffer;

/* Creates a framebuffer cleared to colour 0 and depth 1. `allocator` may be NULL (the C++
 * runtime's allocation). On failure *out is NULL. */
TESSERA_API tessera_result tessera_framebuffer_create(const tessera_framebuffer_desc* desc,
                                                      const tessera_allocator* allocator,
                                                      tessera_framebuffer** out);
/* Destroys a framebuffer; NULL is ignored. Cannot fail. */
TESSERA_API void tessera_framebuffer_destroy(tessera_framebuffer* framebuffer);
TESSERA_API tessera_result tessera_framebuffer_get_desc(const tessera_framebuffer* framebuffer,
                                                        tessera_framebuffer_desc* out);

/* Clears every sample's colour (RGBA, 0..1 for RGBA8) or depth (0..1; a float32 buffer keeps
 * any value). */
TESSERA_API tessera_result tessera_framebuffer_clear_color(tessera_framebuffer* framebuffer,
                                                           float r, float g, float b, float a);
TESSERA_API tessera_result tessera_framebuffer_clear_depth(tessera_framebuffer* framebuffer,
                                                           float depth);

/* Read-back into caller memory, images top row first. `capacity` is the number of values
 * `dst` holds (bytes for RGBA8, floats otherwise); it must be at least the image's count, or
 * the call fails with TESSERA_ERROR_INVALID_ARGUMENT and writes nothing. Only that count is
 * written.
 *   rgba8:        width * height * 4 bytes, the resolved (box-averaged) colour;
 *   rgba32f:      width * height * 4 floats, the same (an RGBA8 buffer's divided by 255);
 *   depth:        width * height floats, sample 0's depth of each pixel, in 0..1;
 *   sample_depth: width * height * samples floats, every sample's, at
 *                 (y * width + x) * samples + s. */
TESSERA_API tessera_result tessera_framebuffer_read_rgba8(const tessera_framebuffer* framebuffer,
                                                          uint8_t* dst, size_t capacity);
TESSERA_API tessera_result tessera_framebuffer_read_rgba32f(const tessera_framebuffer* framebuffer,
                                                            float* dst, size_t capacity);
TESSERA_API tessera_result tessera_framebuffer_read_depth(const tessera_framebuffer* framebuffer,
                                                          float* dst, size_t capacity);
TESSERA_API tessera_result tessera_framebuffer_read_sample_depth(
    const tessera_framebuffer* framebuffer, float* dst, size_t capacity);
/* Colour target `target` (0..extra_targets), as tessera::Framebuffer::read_target:
 *   read_target:      width * height * 4 floats (RGBA8, RGBA32F; RGBA8 divided by 255) or
 *                     width * height (R32F), resolved;
 *   read_target_uint: width * height values of an R32UI target, sample 0's of each pixel.
 * The wrong read for the target's format, or a target that does not exist, is
 * TESSERA_ERROR_INVALID_ARGUMENT. The extra targets start cleared to 0; clear_target keeps
 * r of an R32F target, clear_target_uint clears an R32UI one. */
TESSERA_API tessera_result tessera_framebuffer_read_target(const tessera_framebuffer* framebuffer,
                                                           uint32_t target, float* dst,
                                                           size_t capacity);
TESSERA_API tessera_result tessera_framebuffer_read_target_uint(
    const tessera_framebuffer* framebuffer, uint32_t target, uint32_t* dst, size_t capacity);
TESSERA_API tessera_result tessera_framebuffer_clear_target(tessera_framebuffer* framebuffer,
                                                            uint32_t target, float r, float g,
                                                            float b, float a);
TESSERA_API tessera_result tessera_framebuffer_clear_target_uint(tessera_framebuffer* framebuffer,
                                                                 uint32_t target, uint32_t value);

/* ---- Renderers --------------------------------------------------------------------------- */

typedef enum tessera_backend {
  TESSERA_BACKEND_REFERENCE = 0, /* the scalar reference rasterizer, the oracle */
  TESSERA_BACKEND_FAST = 1,      /* the binned, tiled, multithreaded SIMD engine */
  TESSERA_BACKEND_MAX_ENUM = 0x7FFFFFFF
} tessera_backend;

/* The options of tessera::RendererOptions that an embedding sets; the others keep their C++
 * defaults. tessera_renderer_desc_init fills the defaults: 1 thread, the fast backend. */
typedef struct tessera_renderer_desc {
  uint32_t threads; /* worker threads of the renderer's arena; 1 = serial, 0 = all cores */
  tessera_backend backend;
} tessera_renderer_desc;

/* Draws into framebuffers, on threads of its own (tessera::Renderer). */
typedef struct tessera_renderer tessera_renderer;

TESSERA_API tessera_result tessera_renderer_desc_init(tessera_renderer_desc* desc);
/* Creates a renderer. `allocator` may be NULL. On failure *out is NULL. */
TESSERA_API tessera_result tessera_renderer_create(const tessera_renderer_desc* desc,
                                                   const tessera_allocator* allocator,
                                                   tessera_renderer** out);
/* Destroys a renderer; NULL is ignored. Cannot fail. */
TESSERA_API void tessera_renderer_destroy(tessera_renderer* renderer);

/* ---- Pipeline state ---------------------------------------------------------------------- */

typedef enum tessera_compare_op {
  TESSERA_COMPARE_NEVER = 0,
  TESSERA_COMPARE_LESS = 1,
  TESSERA_COMPARE_EQUAL = 2,
  TESSERA_COMPARE_LESS_EQUAL = 3,
  TESSERA_COMPARE_GREATER = 4,
  TESSERA_COMPARE_NOT_EQUAL = 5,
  TESSERA_COMPARE_GREATER_EQUAL = 6,
  TESSERA_COMPARE_ALWAYS = 7,
  TESSERA_COMPARE_OP_MAX_ENUM = 0x7FFFFFFF
} tessera_compare_op;

typedef enum tessera_cull_mode {
  TESSERA_CULL_NONE = 0,
  TESSERA_CULL_FRONT = 1,
  TESSERA_CULL_BACK = 2,
  TESSERA_CULL_MODE_MAX_ENUM = 0x7FFFFFFF
} tessera_cull_mode;

/* As seen in NDC, y up. */
typedef enum tessera_front_face {
  TESSERA_FRONT_FACE_COUNTER_CLOCKWISE = 0,
  TESSERA_FRONT_FACE_CLOCKWISE = 1,
  TESSERA_FRONT_FACE_MAX_ENUM = 0x7FFFFFFF
} tessera_front_face;

/* Clip-space depth range of the vertex data: 0 <= z <= w (Vulkan, D3D) or -w <= z <= w
 * (OpenGL). */
typedef enum tessera_clip_depth {
  TESSERA_CLIP_DEPTH_ZERO_TO_ONE = 0,
  TESSERA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE = 1,
  TESSERA_CLIP_DEPTH_MAX_ENUM = 0x7FFFFFFF
} tessera_clip_depth;

typedef enum tessera_interpolation {
  TESSERA_INTERPOLATION_PERSPECTIVE = 0,
  TESSERA_INTERPOLATION_AFFINE = 1,
  TESSERA_INTERPOLATION_MAX_ENUM = 0x7FFFFFFF
} tessera_interpolation;

/* How one varying is interpolated (tessera::VaryingMode). */
typedef enum tessera_varying_mode {
  TESSERA_VARYING_DEFAULT = 0, /* as the pipeline's interpolation says */
  TESSERA_VARYING_PERSPECTIVE = 1,
  TESSERA_VARYING_AFFINE = 2,
  TESSERA_VARYING_FLAT = 3, /* the triangle's first vertex's value */
  TESSERA_VARYING_MODE_MAX_ENUM = 0x7FFFFFFF
} tessera_varying_mode;

/* The built-in fragment shader (tessera::FragmentShader). */
typedef enum tessera_fragment_shader {
  TESSERA_SHADER_GOURAUD = 0,  /* the colour varyings, RGBA */
  TESSERA_SHADER_PHONG = 1,    /* per-pixel Phong lighting (tessera_phong_state) */
  TESSERA_SHADER_USER = 2,     /* tessera_pipeline_state.fragment_function */
  TESSERA_SHADER_TEXTURED = 3, /* tessera_pipeline_state.texture times the colour varyings */
  TESSERA_FRAGMENT_SHADER_MAX_ENUM = 0x7FFFFFFF
} tessera_fragment_shader;

/* User fragment shaders (tessera::FragmentBatch, tessera::FragmentOutput; the rules are in
 * docs/WRITING_A_SHADER.md): a batch of up to TESSERA_FRAGMENT_BATCH_STRIDE fragments in 2x2
 * quads, one array per component, TESSERA_FRAGMENT_BATCH_STRIDE values apart: varying v of
 * fragment i is varyings[v * TESSERA_FRAGMENT_BATCH_STRIDE + i]. */
#define TESSERA_FRAGMENT_BATCH_STRIDE 64

typedef struct tessera_fragment_batch {
  uint32_t count;         /* fragments, 4 per quad */
  uint32_t varying_count; /* the draw's attribute_count */
  const float* x;         /* window coordinates of the pixel centres (y down) */
  const float* y;
  const uint32_t* sample_mask;  /* samples the fragment writes; 0: a helper fragment */
  const uint32_t* primitive_id; /* the triangle's index in the draw */
  const float* varyings;
  const float* ddx; /* per quad: d varying / dx at the quad's centre (indexed as varyings) */
  const float* ddy;
} tessera_fragment_batch;

typedef struct tessera_fragment_output {
  float* color;     /* RGBA of fragment i: color[c * TESSERA_FRAGMENT_BATCH_STRIDE + i] */
  uint8_t* discard; /* nonzero drops the fragment (in every target); all zero on entry */
  /* Extra target t + 1's values, for a target whose output is TESSERA_OUTPUT_COLOR: extra[t]
   * for RGBA8 and RGBA32F (4 channels, as color) and R32F (1 channel); extra_uint[t][i] for
   * R32UI. NULL where the framebuffer has no such target or the other kind. */
  float* extra[TESSERA_MAX_COLOR_TARGETS - 1];
  uint32_t* extra_uint[TESSERA_MAX_COLOR_TARGETS - 1];
} tessera_fragment_output;

/* Called from several threads at once, for batches of different screen tiles: it must be safe
 * to call concurrently, and each fragment's outputs must depend only on its own inputs. */
typedef void (*tessera_fragment_function)(const tessera_fragment_batch* batch,
                                          const tessera_fragment_output* output, void* user_data);

/* What a colour target receives (tessera::TargetOutput). PRIMITIVE_ID and OBJECT_ID need an
 * RGBA32F, R32F or R32UI target (exact below 2^24 in the float ones, always in R32UI); an
 * R32UI target takes only them and a user shader's COLOR. */
typedef enum tessera_target_output {
  TESSERA_OUTPUT_COLOR = 0,        /* the fragment shader's colour */
  TESSERA_OUTPUT_EYE_DEPTH = 1,    /* clip-space w at the pixel */
  TESSERA_OUTPUT_NORMAL = 2,       /* the normal varyings, normalized */
  TESSERA_OUTPUT_POSITION = 3,     /* the position varyings */
  TESSERA_OUTPUT_BARYCENTRICS = 4, /* the perspective-correct vertex weights */
  TESSERA_OUTPUT_PRIMITIVE_ID = 5, /* the triangle's index in its draw */
  TESSERA_OUTPUT_OBJECT_ID = 6,    /* tessera_pipeline_state.object_id */
  TESSERA_TARGET_OUTPUT_MAX_ENUM = 0x7FFFFFFF
} tessera_target_output;

typedef enum tessera_light_kind {
  TESSERA_LIGHT_DIRECTIONAL = 0,
  TESSERA_LIGHT_POINT = 1,
  TESSERA_LIGHT_SPOT = 2,
  TESSERA_LIGHT_KIND_MAX_ENUM = 0x7FFFFFFF
} tessera_light_kind;

/* The first varying of each group the built-in shaders and outputs read
 * (tessera::VaryingRoles). */
typedef struct tessera_varying_roles {
  uint32_t color;    /* 4 varyings, RGBA */
  uint32_t normal;   /* 3 varyings */
  uint32_t position; /* 3 varyings */
  uint32_t texcoord; /* 2 varyings, (u, v): TESSERA_SHADER_TEXTURED */
} tessera_varying_roles;

/* ---- Textures (tessera::Texture, tessera::Sampler; docs/TEXTURES.md) -------------------- */

typedef enum tessera_texture_format {
  TESSERA_TEXTURE_RGBA8 = 0,
  TESSERA_TEXTURE_RGBA8_SRGB = 1, /* RGB sRGB-encoded, decoded when sampled */
  TESSERA_TEXTURE_RGBA32F = 2,
  TESSERA_TEXTURE_R8 = 3,
  TESSERA_TEXTURE_R32F = 4,
  TESSERA_TEXTURE_FORMAT_MAX_ENUM = 0x7FFFFFFF
} tessera_texture_format;

typedef enum tessera_filter {
  TESSERA_FILTER_NEAREST = 0,
  TESSERA_FILTER_LINEAR = 1,
  TESSERA_FILTER_MAX_ENUM = 0x7FFFFFFF
} tessera_filter;

typedef enum tessera_mip_filter {
  TESSERA_MIP_FILTER_NONE = 0,
  TESSERA_MIP_FILTER_NEAREST = 1,
  TESSERA_MIP_FILTER_LINEAR = 2,
  TESSERA_MIP_FILTER_MAX_ENUM = 0x7FFFFFFF
} tessera_mip_filter;

typedef enum tessera_wrap {
  TESSERA_WRAP_REPEAT = 0,
  TESSERA_WRAP_CLAMP_TO_EDGE = 1,
  TESSERA_WRAP_MIRRORED_REPEAT = 2,
  TESSERA_WRAP_CLAMP_TO_BORDER = 3,
  TESSERA_WRAP_MAX_ENUM = 0x7FFFFFFF
} tessera_wrap;

/* How a texture is sampled (tessera::Sampler); tessera_pipeline_state_init fills the C++
 * defaults (linear filters, linear mips, repeat). */
typedef struct tessera_sampler {
  tessera_filter mag_filter;
  tessera_filter min_filter;
  tessera_mip_filter mip_filter;
  tessera_wrap wrap_u;
  tessera_wrap wrap_v;
  float border_color[4]; /* TESSERA_WRAP_CLAMP_TO_BORDER */
  float lod_bias;
  float min_lod, max_lod;
  float max_anisotropy; /* 1 (off) to 16 */
} tessera_sampler;

/* A texture (tessera::Texture): the caller's texels copied (width * height texels, top row
 * first, 4 bytes per texel for RGBA8, 16 for RGBA32F, 1 for R8, 4 for R32F; `size` is their
 * byte count and must match), and the mip chain generated with `mipmaps`. Draws only read it;
 * it must outlive the draws that use it. On failure *out is NULL. */
typedef struct tessera_texture tessera_texture;
TESSERA_API tessera_result tessera_texture_create(uint32_t width, uint32_t height,
                                                  tessera_texture_format format, const void* texels,
                                                  size_t size, bool mipmaps,
                                                  const tessera_allocator* allocator,
                                                  tessera_texture** out);
/* Destroys a texture; NULL is ignored. Cannot fail. */
TESSERA_API void tessera_texture_destroy(tessera_texture* texture);

/* A Phong light (tessera::Light; its comments give the model). */
typedef struct tessera_light {
  tessera_light_kind kind;
  float position[3];  /* point and spot lights */
  float direction[3]; /* directional and spot lights: where the light travels */
  float diffuse[3];
  float specular[3];
  float c0, c1, c2; /* attenuation 1 / (c0 + c1 d + c2 d^2) */
  float spot_cos_cutoff;
  float spot_exponent;
} tessera_light;

/* Per-pixel Phong (tessera::PhongState). */
typedef struct tessera_phong_state {
  float base_color[4];
  float ka, kd, ks;
  float shininess;
  float ambient[3];
  float eye[3];
  bool two_sided;
  uint32_t light_count; /* 0..TESSERA_MAX_LIGHTS */
  tessera_light lights[TESSERA_MAX_LIGHTS];
} tessera_phong_state;

/* Blending (tessera::BlendState): a colour target's value becomes op(src * src_factor,
 * dst * dst_factor) per channel, OpenGL's and Vulkan's factors and operations. */
typedef enum tessera_blend_factor {
  TESSERA_BLEND_ZERO = 0,
  TESSERA_BLEND_ONE = 1,
  TESSERA_BLEND_SRC_COLOR = 2,
  TESSERA_BLEND_ONE_MINUS_SRC_COLOR = 3,
  TESSERA_BLEND_DST_COLOR = 4,
  TESSERA_BLEND_ONE_MINUS_DST_COLOR = 5,
  TESSERA_BLEND_SRC_ALPHA = 6,
  TESSERA_BLEND_ONE_MINUS_SRC_ALPHA = 7,
  TESSERA_BLEND_DST_ALPHA = 8,
  TESSERA_BLEND_ONE_MINUS_DST_ALPHA = 9,
  TESSERA_BLEND_CONSTANT_COLOR = 10,
  TESSERA_BLEND_ONE_MINUS_CONSTANT_COLOR = 11,
  TESSERA_BLEND_CONSTANT_ALPHA = 12,
  TESSERA_BLEND_ONE_MINUS_CONSTANT_ALPHA = 13,
  TESSERA_BLEND_SRC_ALPHA_SATURATE = 14,
  TESSERA_BLEND_FACTOR_MAX_ENUM = 0x7FFFFFFF
} tessera_blend_factor;

typedef enum tessera_blend_op {
  TESSERA_BLEND_OP_ADD = 0,
  TESSERA_BLEND_OP_SUBTRACT = 1,
  TESSERA_BLEND_OP_REVERSE_SUBTRACT = 2,
  TESSERA_BLEND_OP_MIN = 3,
  TESSERA_BLEND_OP_MAX = 4,
  TESSERA_BLEND_OP_MAX_ENUM = 0x7FFFFFFF
} tessera_blend_op;

/* write_mask bits */
#define TESSERA_WRITE_RED 1u
#define TESSERA_WRITE_GREEN 2u
#define TESSERA_WRITE_BLUE 4u
#define TESSERA_WRITE_ALPHA 8u
#define TESSERA_WRITE_ALL 15u

typedef struct tessera_blend_state {
  bool enable;
  tessera_blend_factor src_color, dst_color;
  tessera_blend_op color_op;
  tessera_blend_factor src_alpha, dst_alpha;
  tessera_blend_op alpha_op;
  uint32_t write_mask; /* TESSERA_WRITE_* bits; the channels left out keep their value */
} tessera_blend_state;

/* A rectangle of window pixels (tessera::Rect): first pixel (x, y) from the top-left, y down. */
typedef struct tessera_rect {
  int32_t x, y;
  uint32_t width, height;
} tessera_rect;

/* tessera::PipelineState: everything about a draw but its vertex data. Fill it with
 * tessera_pipeline_state_init (the C++ defaults: depth test and write on with LESS, colour
 * write on, no culling, counter-clockwise front faces, perspective-correct Gouraud colour from
 * varyings 0..3), then change what the draw needs. */
typedef struct tessera_pipeline_state {
  bool depth_test; /* off: depth is neither tested nor written */
  bool depth_write;
  tessera_compare_op depth_compare;
  bool color_write;
  tessera_cull_mode cull;
  tessera_front_face front_face;
  tessera_clip_depth clip_depth;
  tessera_interpolation interpolation;
  uint32_t samples;       /* 0: the framebuffer's; otherwise it must equal the framebuffer's */
  uint32_t subpixel_bits; /* 4..8 */
  tessera_varying_mode varying_modes[TESSERA_MAX_VARYINGS];
  tessera_fragment_shader shader; /* triangles only: points and lines use varyings 0..3 */
  tessera_target_output output;
  tessera_varying_roles roles;
  tessera_phong_state phong;
  uint32_t object_id; /* TESSERA_OUTPUT_OBJECT_ID, below 2^24 in a float target */
  /* TESSERA_SHADER_USER: the function, and the pointer passed to every call of it. */
  tessera_fragment_function fragment_function;
  void* fragment_user_data;
  /* What extra target t + 1 receives (tessera_framebuffer_desc.extra_targets). */
  tessera_target_output extra_outputs[TESSERA_MAX_COLOR_TARGETS - 1];
  /* TESSERA_SHADER_TEXTURED: the texture (read during the draw only) and its sampler. */
  const tessera_texture* texture;
  tessera_sampler sampler;
  /* Per colour target: target 0 blends; the extra targets keep the init values. */
  tessera_blend_state blend[TESSERA_MAX_COLOR_TARGETS];
  float blend_constant[4]; /* CONSTANT_COLOR and CONSTANT_ALPHA */
  /* With scissor_test, only the pixels inside `scissor` are drawn. */
  bool scissor_test;
  tessera_rect scissor;
  /* Depth bias (Direct3D's formula): constant * r + slope * max(|dz/dx|, |dz/dy|), clamped by
   * depth_bias_clamp when it is not 0. */
  float depth_bias_constant, depth_bias_slope, depth_bias_clamp;
} tessera_pipeline_state;

TESSERA_API tessera_result tessera_pipeline_state_init(tessera_pipeline_state* state);

/* ---- Draws ------------------------------------------------------------------------------- */

/* One draw's vertex data, in caller memory that the draw only reads and does not keep.
 * positions: vertex_count clip-space (x, y, z, w), 4 floats each; attributes: attribute_count
 * floats per vertex (0..TESSERA_MAX_VARYINGS), vertex-major, the varyings; indices: index_count
 * vertex numbers, or NULL with index_count 0 to take the vertices in order. A pointer may be
 * NULL only when its count is 0. */
typedef struct tessera_draw_input {
  const float* positions;
  size_t vertex_count;
  const float* attributes;
  uint32_t attribute_count;
  const uint32_t* indices;
  size_t index_count;
} tessera_draw_input;

/* A triangle list: the indices three at a time, or the vertices. */
TESSERA_API tessera_result tessera_draw_triangles(tessera_renderer* renderer,
                                                  tessera_framebuffer* framebuffer,
                                                  const tessera_pipeline_state* pipeline,
                                                  const tessera_draw_input* input);

typedef enum tessera_point_shape {
  TESSERA_POINT_SQUARE = 0, /* the pixel centres in a square of side `size` */
  TESSERA_POINT_ROUND = 1,  /* an antialiased disc of diameter `size`, blended */
  TESSERA_POINT_SHAPE_MAX_ENUM = 0x7FFFFFFF
} tessera_point_shape;

/* tessera::PointState; tessera_point_state_init fills its defaults (1 pixel, square). */
typedef struct tessera_point_state {
  float size; /* pixels, 1..1024 */
  tessera_point_shape shape;
} tessera_point_state;

TESSERA_API tessera_result tessera_point_state_init(tessera_point_state* state);
/* One point per vertex (per index when there are indices). */
TESSERA_API tessera_result tessera_draw_points(tessera_renderer* renderer,
                                               tessera_framebuffer* framebuffer,
                                               const tessera_pipeline_state* pipeline,
                                               const tessera_point_state* state,
                                               const tessera_draw_input* input);

typedef enum tessera_line_topology {
  TESSERA_LINE_LIST = 0,  /* two vertices per segment */
  TESSERA_LINE_STRIP = 1, /* a polyline */
  TESSERA_LINE_LOOP = 2,  /* a closed polyline */
  TESSERA_LINE_TOPOLOGY_MAX_ENUM = 0x7FFFFFFF
} tessera_line_topology;

/* How one-pixel lines choose their pixels (tessera::LineAlgorithm). */
typedef enum tessera_line_algorithm {
  TESSERA_LINE_DIAMOND_EXIT = 0, /* OpenGL's and D3D's rule */
  TESSERA_LINE_BRESENHAM = 1,
  TESSERA_LINE_DDA = 2,
  TESSERA_LINE_ALGORITHM_MAX_ENUM = 0x7FFFFFFF
} tessera_line_algorithm;

typedef enum tessera_line_join {
  TESSERA_LINE_JOIN_NONE = 0,
  TESSERA_LINE_JOIN_MITER = 1,
  TESSERA_LINE_JOIN_ROUND = 2,
  TESSERA_LINE_JOIN_BEVEL = 3,
  TESSERA_LINE_JOIN_MAX_ENUM = 0x7FFFFFFF
} tessera_line_join;

/* tessera::LineState (rules in docs/PRIMITIVES.md); tessera_line_state_init fills its defaults
 * (a list of one-pixel diamond-exit lines, no stipple). */
typedef struct tessera_line_state {
  tessera_line_topology topology;
  tessera_line_algorithm algorithm;
  float width; /* pixels, 1..1024 */
  tessera_line_join join;
  float miter_limit;        /* in half line widths */
  uint16_t stipple_pattern; /* glLineStipple: bit (s / factor) % 16 draws fragment s */
  uint32_t stipple_factor;  /* 1..256 */
  bool antialiased;
} tessera_line_state;

TESSERA_API tessera_result tessera_line_state_init(tessera_line_state* state);
TESSERA_API tessera_result tessera_draw_lines(tessera_renderer* renderer,
                                              tessera_framebuffer* framebuffer,
                                              const tessera_pipeline_state* pipeline,
                                              const tessera_line_state* state,
                                              const tessera_draw_input* input);

/* ---- Occlusion queries (tessera/occlusion.hpp, docs/OCCLUSION.md) ------------------------ */

typedef enum tessera_occlusion_mode {
  TESSERA_OCCLUSION_CONSERVATIVE =
      0,                       /* Hi-Z only: may see a hidden query, never hides a seen one */
  TESSERA_OCCLUSION_EXACT = 1, /* every sample, LESS_EQUAL, no writes */
  TESSERA_OCCLUSION_MODE_MAX_ENUM = 0x7FFFFFFF
} tessera_occlusion_mode;

/* tessera::OcclusionDesc: a depth-only buffer of width x height (samples 0 means 1). */
typedef struct tessera_occlusion_desc {
  uint32_t width;
  uint32_t height;
  uint32_t samples;
  tessera_depth_format depth_format;
  bool reversed_z;  /* depth cleared to 0, GREATER occluders, GREATER_EQUAL queries */
  uint32_t threads; /* the occluder draws' worker threads (0: every core) */
} tessera_occlusion_desc;

/* Occluders in depth, asked what they hide (tessera::OcclusionBuffer). The query functions may
 * run from several threads at once while no clear or draw runs on the same buffer. */
typedef struct tessera_occlusion tessera_occlusion;

/* Creates a buffer with nothing drawn. `allocator` may be NULL. On failure *out is NULL. */
TESSERA_API tessera_result tessera_occlusion_create(const tessera_occlusion_desc* desc,
                                                    const tessera_allocator* allocator,
                                                    tessera_occlusion** out);
/* Destroys a buffer; NULL is ignored. Cannot fail. */
TESSERA_API void tessera_occlusion_destroy(tessera_occlusion* occlusion);
TESSERA_API tessera_result tessera_occlusion_clear(tessera_occlusion* occlusion);
/* Draws clip-space triangles (input's positions and indices; attributes ignored) as occluders. */
TESSERA_API tessera_result tessera_occlusion_draw(tessera_occlusion* occlusion,
                                                  const tessera_draw_input* occluders);
/* *visible: whether the window rectangle [x0, x1) x [y0, y1) at nearest_depth would be seen. */
TESSERA_API tessera_result tessera_occlusion_rect_visible(const tessera_occlusion* occlusion,
                                                          float x0, float y0, float x1, float y1,
                                                          float nearest_depth,
                                                          tessera_occlusion_mode mode,
                                                          bool* visible);
/* *visible: whether the box [lo, hi] through clip_from_object (16 floats, column-major as
 * OpenGL and GLM store a matrix: projection * view * model) would be seen. */
TESSERA_API tessera_result tessera_occlusion_box_visible(const tessera_occlusion* occlusion,
                                                         const float lo[3], const float hi[3],
                                                         const float clip_from_object[16],
                                                         tessera_occlusion_mode mode,
                                                         bool* visible);
/* *visible: whether any of the clip-space triangles would be seen. */
TESSERA_API tessera_result tessera_occlusion_triangles_visible(const tessera_occlusion* occlusion,
                                                               const tessera_draw_input* triangles,
                                                               tessera_occlusion_mode mode,
                                                               bool* visible);
/* The buffer's depth (width * height floats, top row first; the first sample of each pixel). */
TESSERA_API tessera_result tessera_occlusion_read_depth(const tessera_occlusion* occlusion,
                                                        float* dst, size_t capacity);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif /* TESSERA_TESSERA_H_ */
