// The few spellings that differ between C++ and GLSL, for the ports' shared headers (filters/**/<stem>_shared.h).
// Each of those includes this file, wraps its C++ side in namespace rtdr, and declares its constants as
// RTDR_SHARED_CONST and its push-constant fields with these types, so both compilers read one declaration.
#ifndef RTDR_CORE_SHADER_SHARED_H
#define RTDR_CORE_SHADER_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cstdint>
#define RTDR_SHARED_UINT std::uint32_t
#define RTDR_SHARED_INT std::int32_t
#define RTDR_SHARED_VEC2 glm::vec2
#define RTDR_SHARED_CONST inline constexpr
#else
#define RTDR_SHARED_UINT uint
#define RTDR_SHARED_INT int
#define RTDR_SHARED_VEC2 vec2
#define RTDR_SHARED_CONST const
#endif

#ifdef __cplusplus
namespace rtdr {
#endif
// The largest finite half (fp16). A store into a half record saturates there (RTDR_OUTPUT_RGBA16F_PAIR), where
// rounding would give an infinity, and an infinity times a tap weight of 0 a NaN.
RTDR_SHARED_CONST float kHalfMax = 65504.0f;
#ifdef __cplusplus
}  // namespace rtdr
#endif

#ifndef __cplusplus
// How a port reads an input plane: RTDR_INPUT_RGBA(binding, name) declares the plane and a function name(i) that
// returns its texel i as a vec4 (RTDR_INPUT_RG: vec4(x, y, 0, 1); RTDR_INPUT_UINT: uvec4(id, 0, 0, 1)), the same in
// both input builds of every shader (gpu/CMakeLists.txt compiles each one for both). A plane of pairs holds two
// texels per pixel side by side, texels 2i and 2i + 1, and name(i) returns pixel i's two as a vec4[2]:
// RTDR_INPUT_RGBA_PAIR two RGBA32F texels (32 bytes), RTDR_INPUT_RGBA16F_PAIR two of four halves each (16 bytes,
// widened exactly).
//   <stem>.spv          storage texel buffers, read with imageLoad. On lavapipe an image load gathers the texel
//                       for all lanes at once, inline, where a storage-buffer load runs lane by lane and a texelFetch
//                       calls a sampling function, which makes the shader spill its registers around every call
//                       (docs/performance.md). rg32f needs the shaderStorageImageExtendedFormats feature, which
//                       VulkanContext enables.
//   <stem>_storage.spv  (RTDR_STORAGE_INPUTS) storage buffers, read as arrays. On a GPU a 16-byte texel goes
//                       through the texture units at a fraction of the rate of plain loads (docs/performance.md), and
//                       a pixel's pair of RGBA16F texels is one 16-byte load.
// The host binds each input as the kind its shader was built for (ShaderInputs, gpu/vulkan_context.h; the
// bindings' kinds: gpu/svgf_shaders.cpp).
#ifdef RTDR_STORAGE_INPUTS
// A read-only std430 array name##_data of `element`s.
#define RTDR_INPUT_ARRAY(b, name, element) \
  layout(std430, set = 0, binding = b) readonly buffer name##_records { element name##_data[]; };
#define RTDR_INPUT_RGBA(b, name)  \
  RTDR_INPUT_ARRAY(b, name, vec4) \
  vec4 name(int i) { return name##_data[i]; }
#define RTDR_INPUT_RG(b, name)    \
  RTDR_INPUT_ARRAY(b, name, vec2) \
  vec4 name(int i) { return vec4(name##_data[i], 0.0, 1.0); }
#define RTDR_INPUT_UINT(b, name)  \
  RTDR_INPUT_ARRAY(b, name, uint) \
  uvec4 name(int i) { return uvec4(name##_data[i], 0u, 0u, 1u); }
#define RTDR_INPUT_RGBA_PAIR(b, name) \
  RTDR_INPUT_ARRAY(b, name, vec4)     \
  vec4[2] name(int i) { return vec4[2](name##_data[2 * i], name##_data[2 * i + 1]); }
#define RTDR_INPUT_RGBA16F_PAIR(b, name)                                      \
  RTDR_INPUT_ARRAY(b, name, uvec4)                                            \
  vec4[2] name(int i) {                                                       \
    const uvec4 halves = name##_data[i];                                      \
    return vec4[2](vec4(unpackHalf2x16(halves.x), unpackHalf2x16(halves.y)),  \
                   vec4(unpackHalf2x16(halves.z), unpackHalf2x16(halves.w))); \
  }
#else
// A storage texel buffer of `format`, viewed as `image` (imageBuffer or uimageBuffer), whose whole texels name(i)
// loads as `texel`s.
#define RTDR_INPUT_TEXELS(b, name, format, image, texel)                     \
  layout(set = 0, binding = b, format) uniform readonly image name##_texels; \
  texel name(int i) { return imageLoad(name##_texels, i); }
#define RTDR_INPUT_RGBA(b, name) RTDR_INPUT_TEXELS(b, name, rgba32f, imageBuffer, vec4)
#define RTDR_INPUT_RG(b, name) RTDR_INPUT_TEXELS(b, name, rg32f, imageBuffer, vec4)
#define RTDR_INPUT_UINT(b, name) RTDR_INPUT_TEXELS(b, name, r32ui, uimageBuffer, uvec4)
// A storage texel buffer of `format` holding two texels per pixel, whose pixel i name(i) loads as a vec4[2].
#define RTDR_INPUT_TEXEL_PAIRS(b, name, format)                                    \
  layout(set = 0, binding = b, format) uniform readonly imageBuffer name##_texels; \
  vec4[2] name(int i) { return vec4[2](imageLoad(name##_texels, 2 * i), imageLoad(name##_texels, 2 * i + 1)); }
#define RTDR_INPUT_RGBA_PAIR(b, name) RTDR_INPUT_TEXEL_PAIRS(b, name, rgba32f)
#define RTDR_INPUT_RGBA16F_PAIR(b, name) RTDR_INPUT_TEXEL_PAIRS(b, name, rgba16f)
#endif

// How a port writes a plane of pairs: RTDR_OUTPUT_RGBA_PAIR(binding, name) declares a write-only std430 array of
// vec4 and a function name(i, first, second) that stores pixel i's two texels, 2i and 2i + 1. RTDR_OUTPUT_RGBA16F_PAIR
// stores them as four halves each (16 bytes a pixel, one store, packHalf2x16's layout, which is rgba16f's: x in the
// low 16 bits), each component first clamped to +-kHalfMax.
// The conversion gives one of the two halves nearest v, which one the device chooses (the Vulkan spec's
// floating-point conversion rule): a relative error under 2^-10, or an absolute one under 2^-24 below the
// smallest normal half (2^-14).
// Subnormal halves: Vulkan also lets a device flush a subnormal to 0 wherever a shader converts to or from fp16,
// unless the shader asks for DenormPreserve (an optional property). The fp16 records keep them (a colour of 1e-5
// stays 1e-5) and their error bounds assume the device does too, as lavapipe does; tests/gpu_svgf_planes_test.cpp
// checks it on the device at hand, and a device that flushes should run fp32 records. Writing 0 below 2^-14
// ourselves would make every device agree, but it cost accuracy where SVGF is sensitive: the luminance weight
// [SVGF17 Eq. 5] compares dark pixels at the scale of its epsilon (1e-4), and the fp16 pipeline's colour went from
// 1.6e-3 to 1.25e-2 off the golden one on falling-light (docs/performance.md, "Packed illumination").
#define RTDR_OUTPUT_RGBA_PAIR(b, name)                                                          \
  layout(std430, set = 0, binding = b) writeonly buffer name##_records { vec4 name##_data[]; }; \
  void name(int i, vec4 first, vec4 second) {                                                   \
    name##_data[2 * i] = first;                                                                 \
    name##_data[2 * i + 1] = second;                                                            \
  }
#define RTDR_OUTPUT_RGBA16F_PAIR(b, name)                                                         \
  layout(std430, set = 0, binding = b) writeonly buffer name##_records { uvec4 name##_data[]; };  \
  void name(int i, vec4 first, vec4 second) {                                                     \
    const vec4 one = clamp(first, -kHalfMax, kHalfMax), two = clamp(second, -kHalfMax, kHalfMax); \
    name##_data[i] = uvec4(packHalf2x16(one.xy), packHalf2x16(one.zw),                            \
                           packHalf2x16(two.xy), packHalf2x16(two.zw));                           \
  }
#endif

#endif  // RTDR_CORE_SHADER_SHARED_H
