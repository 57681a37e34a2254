// SPDX-License-Identifier: MIT
// Prelude that lets one source be both GLSL and C++ (Bruneton's approach, docs/style.md §7 and §8).
//
// Rules for files in shaders/shared/*.h and shaders/lib/*.glsl (they are compiled as C++ by tests/):
//  - float literals carry an `f` suffix (1.0f): in C++ `1.0` is a double and glm has no double*vec3.
//  - no swizzles other than single components (.x .y .z .w); build vectors with constructors.
//  - parameters that are written use IN/OUT/INOUT macros below.
//  - no texture or image calls: those live in the pass shaders, which pass values into lib functions.
//  - preconditions use SKY_ASSERT (a real assert in C++, nothing in GLSL).
#ifndef SKY_SHARED_PRELUDE_H
#define SKY_SHARED_PRELUDE_H

#ifdef __cplusplus
#include <cassert>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;
using ivec4 = glm::ivec4;
using uvec2 = glm::uvec2;
using uvec3 = glm::uvec3;
using uvec4 = glm::uvec4;
using mat3 = glm::mat3;
using mat4 = glm::mat4;
using uint = uint32_t;
#define IN(T) const T&
#define OUT(T) T&
#define INOUT(T) T&
#define SKY_ASSERT(x) assert(x)
#define SKY_CONST static constexpr
#else
#define IN(T) in T
#define OUT(T) out T
#define INOUT(T) inout T
#define SKY_ASSERT(x)
#define SKY_CONST const
#endif

#endif
