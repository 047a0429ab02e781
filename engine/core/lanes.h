// Four values side by side, one per lane of a vector of four doubles (GCC and Clang vector
// extension: arithmetic acts lane by lane; one AVX register, or two SSE2 halves).
//
// Why: the per-pair and per-particle updates of a step are chains of dependent operations
// (quaternion products, square roots, divisions), so one item at a time keeps the floating-
// point units waiting on latency. Four independent chains in the lanes fill them. The helpers
// below repeat Eigen's operations in Eigen's order, so a lane equals the scalar code on its
// item bit for bit (beam_bond_lanes.h, contact_lanes.h, rotation_lanes.h).
#pragma once

#include <cmath>

#include <immintrin.h>

#include "engine/core/types.h"

namespace fibrenet {

inline constexpr int kLanes = 4;

typedef double Lanes __attribute__((vector_size(kLanes * sizeof(double))));

struct Vec3Lanes {
  Lanes x, y, z;
};
struct QuatLanes {
  Lanes w, x, y, z;
};

// Lanes l = 0..3 of value(l), built as whole vectors: four values stored one by one and read
// back as a vector would stall on the store forwarding.
template <class Value>
Lanes Across(const Value& value) {
  return Lanes{value(0), value(1), value(2), value(3)};
}

inline void GatherQuatLanes(const Quat* const (&q)[kLanes], QuatLanes& out) {
  out.w = Across([&](int l) { return q[l]->w(); });
  out.x = Across([&](int l) { return q[l]->x(); });
  out.y = Across([&](int l) { return q[l]->y(); });
  out.z = Across([&](int l) { return q[l]->z(); });
}

inline void GatherVec3Lanes(const Vec3 (&v)[kLanes], Vec3Lanes& out) {
  out.x = Across([&](int l) { return v[l].x(); });
  out.y = Across([&](int l) { return v[l].y(); });
  out.z = Across([&](int l) { return v[l].z(); });
}

// Whether a comparison of lanes (a vector of 0 or -1 per lane) holds in every lane.
template <class Mask>
inline bool AllLanes(const Mask& m) {
  return (m[0] & m[1] & m[2] & m[3]) != 0;
}

namespace lanes {

inline Lanes Splat(double v) { return Lanes{v, v, v, v}; }

inline Vec3Lanes Add(const Vec3Lanes& a, const Vec3Lanes& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3Lanes Sub(const Vec3Lanes& a, const Vec3Lanes& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3Lanes Scale(Lanes s, const Vec3Lanes& v) { return {s * v.x, s * v.y, s * v.z}; }
inline Vec3Lanes Negate(const Vec3Lanes& v) { return {-v.x, -v.y, -v.z}; }
// The orders of Eigen's 3-vector reductions: (x + y) + z.
inline Lanes Dot(const Vec3Lanes& a, const Vec3Lanes& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3Lanes Cross(const Vec3Lanes& a, const Vec3Lanes& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Eigen's quaternion product as its SSE2 code computes it (Geometry_SIMD.h), term for term.
inline QuatLanes Product(const QuatLanes& a, const QuatLanes& b) {
  QuatLanes r;
  r.x = (a.w * b.x + a.y * b.z) - (a.z * b.y - a.x * b.w);
  r.y = (a.w * b.y + a.y * b.w) + (a.z * b.x - a.x * b.z);
  r.z = (a.w * b.z - a.y * b.x) + (a.z * b.w + a.x * b.y);
  r.w = (a.w * b.w - a.y * b.y) - (a.z * b.z + a.x * b.x);
  return r;
}
inline QuatLanes Conjugate(const QuatLanes& q) { return {q.w, -q.x, -q.y, -q.z}; }

// The processor's vector square root: correctly rounded, as std::sqrt is, so every lane is
// std::sqrt's value; four scalar square roots would wait on each other's latency.
inline Lanes Sqrt(Lanes v) {
#if defined(__AVX__)
  return reinterpret_cast<Lanes>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(v)));
#elif defined(__SSE2__)
  const __m128d low = _mm_sqrt_pd(_mm_setr_pd(v[0], v[1]));
  const __m128d high = _mm_sqrt_pd(_mm_setr_pd(v[2], v[3]));
  return Lanes{low[0], low[1], high[0], high[1]};
#else
  return Across([&](int l) { return std::sqrt(v[l]); });
#endif
}

}  // namespace lanes

}  // namespace fibrenet
