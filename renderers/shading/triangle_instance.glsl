// The instance table of the triangle backends (tri-aabb, vk-rt), shared by GLSL and C++
// (vec4/uvec4/mat4 only).
#ifndef SDFBENCH_TRIANGLE_INSTANCE_GLSL
#define SDFBENCH_TRIANGLE_INSTANCE_GLSL

struct TriInstance {
  vec4 bounds_min;       // world-space AABB of the instance (thesis 6: "per-object AABB test")
  vec4 bounds_max;
  mat4 world_to_object;  // rays are intersected in the mesh's frame: meshes are shared
  mat4 object_to_world;  // rotation + uniform scale + translation; normals use its 3x3 part
  uvec4 info;            // x: first triangle in the triangle texel buffers, y: their count, z: material,
                         // w: bvh: the root of the mesh's BVH
};

#endif
