// Implicit objects, traced by the shading program itself for every backend (like the floor):
// each object is sphere-traced (Hart 1996) inside its object-space bounding box. Included by
// shading.glsl; needs `frame`, `implicit_objects[]`, `implicit_nodes[]` and `has_implicits()`.
#include "implicit_sdf.glsl"

// The CSG tree of nodes [first, first + count) at object-space point p, evaluated in postfix
// order with a bounded stack (thesis Algorithm 5.3 and its intersection/subtraction). Returns
// the signed distance; `prim` is the node (relative to first) of the primitive whose surface
// decides the result there, whose uv the hit takes.
float implicit_distance(uint first, uint count, vec3 p, OUT(uint) prim) {
  float dist[IMPLICIT_STACK_SIZE];
  uint owner[IMPLICIT_STACK_SIZE];
  dist[0] = 0.0f;  // read at the end; set here too, so that no compiler sees an unset read (an empty tree)
  owner[0] = 0u;
  uint top = 0u;
  for (uint i = 0u; i < count; ++i) {
    uint kind = implicit_nodes[first + i].info.x;  // an operation reads nothing else
    if (kind < IMPLICIT_UNION) {
      GpuImplicitNode n = implicit_nodes[first + i];
      dist[top] = implicit_primitive_distance(kind, n.a, n.b, implicit_to_local(n, p));
      owner[top] = i;
      top++;
      continue;
    }
    top--;
    float b = kind == IMPLICIT_SUBTRACTION ? -dist[top] : dist[top];
    float a = dist[top - 1u];
    // union: min; intersection and subtraction (a minus b = max(a, -b)): max. Ties keep a.
    if (kind == IMPLICIT_UNION ? b < a : b > a) {
      dist[top - 1u] = b;
      owner[top - 1u] = owner[top];
    }
  }
  prim = owner[0];
  return dist[0];
}

vec3 implicit_object_point(GpuImplicitObject o, vec3 p) {
  return vec3(dot(vec3(o.to_object0), p) + o.to_object0.w, dot(vec3(o.to_object1), p) + o.to_object1.w,
              dot(vec3(o.to_object2), p) + o.to_object2.w);
}

// The ray parameter (world units) where the ray meets the object's surface in (0, tmax], or -1.
// The ray is taken into object space unnormalised, so t stays the world parameter and an
// object distance times the scale is a world step. Marching starts at the exact entry into the
// object's box and stops at its exit; a ray starting inside the shape (refraction) marches on
// the negated distance to the surface it leaves through.
//
// implicit_distance has one call site here and one in implicit_surface: the driver inlines every
// call, each a copy of the CSG interpreter and its stacks, and lavapipe's compile time grows with
// them (11 sites made a whitted kernel with implicit objects take ~20 s to compile).
float implicit_march(GpuImplicitObject o, Ray ray, float tmax) {
  vec3 origin = implicit_object_point(o, ray.origin);
  vec3 dir = vec3(dot(vec3(o.to_object0), ray.dir), dot(vec3(o.to_object1), ray.dir), dot(vec3(o.to_object2), ray.dir));
  const float tiny = 1e-30f;  // no 0 * inf = NaN for an axis-parallel ray on a slab plane
  vec3 inv = vec3(1.0f) / vec3(abs(dir.x) > tiny ? dir.x : tiny, abs(dir.y) > tiny ? dir.y : tiny,
                               abs(dir.z) > tiny ? dir.z : tiny);
  vec3 t0 = (vec3(o.bounds_min) - origin) * inv, t1 = (vec3(o.bounds_max) - origin) * inv;
  vec3 lo = min(t0, t1), hi = max(t0, t1);
  float t = max(max(lo.x, lo.y), max(lo.z, 0.0f));
  float leave = min(min(hi.x, hi.y), min(hi.z, tmax));
  if (t > leave) return -1.0f;
  float scale = o.bounds_max.w;
  float side = 1.0f;  // the sign of the first distance: -1 for a ray that starts inside
  uint prim;
  for (uint step = 0u; step < IMPLICIT_MAX_STEPS; ++step) {
    float dist = implicit_distance(o.info.x, o.info.y, origin + t * dir, prim) * scale;
    if (step == 0u && dist < 0.0f) side = -1.0f;
    dist *= side;
    if (dist < frame.tracing.w) return t;
    t += dist;
    if (t > leave) return -1.0f;
  }
  return -1.0f;
}

// At object-space point p on the surface: the normal (thesis Algorithm 3.3: the SDF's
// central-difference gradient, turned to world) and the node of the primitive that decides the
// distance there. Seven distances, from one call site (see implicit_march): k < 6 the gradient's
// +h and -h samples on axis k / 2, k = 6 the point itself.
vec3 implicit_surface(GpuImplicitObject o, vec3 p, vec3 ray_dir, OUT(uint) prim) {
  float h = o.bounds_min.w;
  vec3 g = vec3(0.0f);
  prim = 0u;
  for (uint k = 0u; k < 7u; ++k) {
    uint axis = min(k >> 1u, 2u), owner;
    float sign = (k & 1u) == 0u ? 1.0f : -1.0f;
    vec3 q = p;
    if (k < 6u) q[axis] += sign * h;
    float d = implicit_distance(o.info.x, o.info.y, q, owner);
    if (k < 6u) {
      g[axis] += sign * d;
    } else {
      prim = owner;
    }
  }
  vec3 n = vec3(dot(vec3(o.to_world0), g), dot(vec3(o.to_world1), g), dot(vec3(o.to_world2), g));
  return dot(n, n) > 0.0f ? normalize(n) : -ray_dir;  // a flat gradient (a symmetry point) faces the ray
}

// The nearest implicit surface with t in (0, tmax]: replaces `hit` (a mesh hit farther away) and
// returns true, or leaves it. Instance ids follow the meshes' (GpuImplicitObject info.w).
bool implicit_closest(Ray ray, float tmax, INOUT(Hit) hit) {
  uint best = 0xffffffffu;
  for (uint i = 0u; i < frame.limits.y; ++i) {
    float t = implicit_march(implicit_objects[i], ray, tmax);
    if (t >= 0.0f) {
      tmax = t;
      best = i;
    }
  }
  if (best == 0xffffffffu) return false;
  GpuImplicitObject o = implicit_objects[best];
  vec3 p = implicit_object_point(o, ray.origin + tmax * ray.dir);
  uint prim;
  hit.normal = implicit_surface(o, p, ray.dir, prim);
  GpuImplicitNode n = implicit_nodes[o.info.x + prim];
  hit.t = tmax;
  hit.instance = o.info.w;
  hit.prim = prim;
  hit.material = o.info.z;
  hit.uv = implicit_primitive_uv(n.info.x, n.a, n.b, implicit_to_local(n, p));
  return true;
}

bool implicit_occluded(Ray ray, float tmax) {
  for (uint i = 0u; i < frame.limits.y; ++i)
    if (implicit_march(implicit_objects[i], ray, tmax) >= 0.0f) return true;
  return false;
}
