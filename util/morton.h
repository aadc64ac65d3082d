#pragma once
// Morton (Z-order) codes: sorting by them puts points that are close in space close in the list.
#include <cstdint>

#include <glm/glm.hpp>

namespace sdfbench {

// 10 bits of x spread to every third bit.
inline uint32_t spread_morton_bits(uint32_t x) {
  x = (x | (x << 16)) & 0x030000ffu;
  x = (x | (x << 8)) & 0x0300f00fu;
  x = (x | (x << 4)) & 0x030c30c3u;
  return (x | (x << 2)) & 0x09249249u;
}

// The code of p on a 1024^3 grid over the box [lo, hi] (p outside is clamped to it).
inline uint32_t morton_code(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-30f));
  const glm::uvec3 cell(glm::clamp((p - lo) / extent, 0.0f, 1.0f) * 1023.0f);
  return (spread_morton_bits(cell.x) << 2) | (spread_morton_bits(cell.y) << 1) | spread_morton_bits(cell.z);
}

}  // namespace sdfbench
