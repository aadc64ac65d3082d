#pragma once
// Embree 3 and Embree 4 from one source tree (Debian 12 ships 3.13, Debian 13 ships 4.3). CMake
// takes Embree 4 when it is installed and 3 otherwise, and says which in SDFBENCH_EMBREE_MAJOR so
// that the headers match the library that is linked. The two differ, for what sdfbench uses, only
// in the header folder and in the single-ray queries: Embree 4 dropped RTCIntersectContext and
// takes the ray second, with optional arguments that sdfbench leaves at their defaults.
#include <string>

#if SDFBENCH_EMBREE_MAJOR == 4
#include <embree4/rtcore.h>
#elif SDFBENCH_EMBREE_MAJOR == 3
#include <embree3/rtcore.h>
#else
#error "SDFBENCH_EMBREE_MAJOR must be 3 or 4 (set by CMakeLists.txt from the Embree package it found)"
#endif
static_assert(RTC_VERSION_MAJOR == SDFBENCH_EMBREE_MAJOR, "Embree's headers are not the version CMake found");

namespace sdfbench::embree {

#if RTC_VERSION_MAJOR < 4
// Embree 3's queries take a context (Embree 4 dropped it); `coherent` marks a packet of coherent rays.
inline RTCIntersectContext context(bool coherent = false) {
  RTCIntersectContext c;
  rtcInitIntersectContext(&c);
  if (coherent) c.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  return c;
}
#endif

// The closest hit along rh.ray (rh.hit.geomID stays RTC_INVALID_GEOMETRY_ID on a miss).
inline void intersect1(RTCScene scene, RTCRayHit& rh) {
#if RTC_VERSION_MAJOR >= 4
  rtcIntersect1(scene, &rh);
#else
  RTCIntersectContext c = context();
  rtcIntersect1(scene, &c, &rh);
#endif
}

// Any hit along ray (Embree sets ray.tfar to -inf when there is one).
inline void occluded1(RTCScene scene, RTCRay& ray) {
#if RTC_VERSION_MAJOR >= 4
  rtcOccluded1(scene, &ray);
#else
  RTCIntersectContext c = context();
  rtcOccluded1(scene, &c, &ray);
#endif
}

// Packets of 8 rays (valid[i] -1: lane i traced, 0: left alone), as the single-ray queries.
inline void intersect8(const int* valid, RTCScene scene, RTCRayHit8& rh) {
#if RTC_VERSION_MAJOR >= 4
  rtcIntersect8(valid, scene, &rh);
#else
  RTCIntersectContext c = context(true);
  rtcIntersect8(valid, scene, &c, &rh);
#endif
}

inline void occluded8(const int* valid, RTCScene scene, RTCRay8& ray) {
#if RTC_VERSION_MAJOR >= 4
  rtcOccluded8(valid, scene, &ray);
#else
  RTCIntersectContext c = context(true);
  rtcOccluded8(valid, scene, &c, &ray);
#endif
}

// "3.13.5", "4.3.3": the version of the headers, which CMake matched to the linked library.
inline std::string version() {
  return std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." + std::to_string(RTC_VERSION_PATCH);
}

}  // namespace sdfbench::embree
