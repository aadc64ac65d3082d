#pragma once
// The checks the codecs apply to values read from a cache file.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace sdfbench::sdf {

inline bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool positive_finite(float f) { return std::isfinite(f) && f > 0.0f; }
inline bool all_finite(const std::vector<glm::vec3>& v) { return std::all_of(v.begin(), v.end(), [](const glm::vec3& x) { return finite(x); }); }
inline uint64_t cell_product(const glm::uvec3& dims) { return uint64_t{dims.x} * dims.y * dims.z; }

}  // namespace sdfbench::sdf
