// The id stored where a pixel sees no surface, written once for C++ (core/frame.h's kInvalidId) and GLSL
// (the ports' shared headers). Embree's RTC_INVALID_GEOMETRY_ID has the same value. Plain preprocessor, so
// both compilers read it.
#ifndef RTDR_CORE_FRAME_SHARED_H
#define RTDR_CORE_FRAME_SHARED_H

#define RTDR_INVALID_ID 0xFFFFFFFFu

#endif  // RTDR_CORE_FRAME_SHARED_H
