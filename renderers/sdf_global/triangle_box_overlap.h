#pragma once
// Whether a triangle meets an axis-aligned box: the separating-axis test of Akenine-Möller
// ("Fast 3D triangle-box overlap testing", 2001): the box's three axes, the triangle's normal and
// the nine cross products of edges. Used where a list must hold every triangle that crosses a cell
// (cell_triangle_refs.h); a box overlap alone lists a long diagonal triangle in every cell of its box.
#include <glm/glm.hpp>

namespace sdfbench::sdf {

// True when triangle (a, b, c) and the box centred at `centre` with half extents `half` share a
// point (touching counts).
bool triangle_meets_box(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& centre,
                        const glm::vec3& half);

}  // namespace sdfbench::sdf
