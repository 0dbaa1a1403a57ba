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

#endif  // RTDR_CORE_SHADER_SHARED_H
