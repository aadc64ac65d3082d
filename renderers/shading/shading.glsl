// The one shading program of every backend (GLSL kernels and, through cpu_shading.h, C++).
// Before including it, define: `frame` (FrameParams), `materials[]`, `lights[]`,
// `vec4 texel_at(uint index)` (the image-texture texel table), `bool has_textures()` and
// `uint shading_mode()` (MODE_*; both constants in the Vulkan kernels, so that code a frame
// cannot use is compiled out), the pixel's ray stack `PathEntry stack_load(uint i)` /
// `void stack_store(uint i, PathEntry e)` (whitted: STACK_SIZE entries) and the backend's two
// queries and the tolerance of its hits
//   bool closest_hit(Ray ray, float tmax, OUT(Hit) hit)   nearest surface with t in (0, tmax)
//   bool any_hit(Ray ray, float tmax)                      any surface with t in (0, tmax)
//   float mesh_hit_tolerance()   how far off the surface a closest_hit point can lie (0: exact)
// The floor is an analytic plane handled here, identically for every backend, and so are the
// implicit objects (implicit_trace.glsl: `implicit_objects[]`, `implicit_nodes[]` and
// `bool has_implicits()`, a constant in the Vulkan kernels).
// A pixel: begin_pixel, trace_ray(primary_ray), then (whitted) trace_ray(pop_ray) while its
// stack is not empty.

#include "implicit_trace.glsl"

Ray camera_ray(uvec2 pixel) {
  float sx = (float(pixel.x) + 0.5f) / float(frame.image.x) * 2.0f - 1.0f;
  float sy = 1.0f - (float(pixel.y) + 0.5f) / float(frame.image.y) * 2.0f;
  vec3 dir = normalize(vec3(frame.camera_forward) + sx * vec3(frame.camera_right) + sy * vec3(frame.camera_up));
  return Ray(vec3(frame.camera_origin), dir);
}

bool floor_hit(Ray ray, float tmax, OUT(float) t) {
  if (frame.floor.z < 0.5f || ray.dir.y == 0.0f) return false;
  t = (frame.floor.x - ray.origin.y) / ray.dir.y;
  return t > 0.0f && t < tmax;
}

// The nearest surface of the scene (meshes, implicit objects, floor); `tolerance`: how far off
// the surface the hit point can lie (offset_origin).
bool trace_closest(Ray ray, float tmax, OUT(Hit) hit, OUT(float) tolerance) {
  bool found = closest_hit(ray, tmax, hit);
  tolerance = mesh_hit_tolerance();
  if (has_implicits() && implicit_closest(ray, found ? hit.t : tmax, hit)) {
    found = true;
    tolerance = IMPLICIT_OFFSET_EPSILONS * frame.tracing.w;
  }
  float t;
  if (floor_hit(ray, found ? hit.t : tmax, t)) {
    tolerance = 0.0f;
    vec3 p = ray.origin + t * ray.dir;
    hit.t = t;
    hit.instance = FLOOR_INSTANCE;
    hit.prim = 0u;
    hit.material = uint(frame.floor.y);
    hit.normal = vec3(0.0f, 1.0f, 0.0f);
    hit.uv = vec2(p.x, p.z);
    found = true;
  }
  return found;
}

// Where a ray leaving the surface at p (n: the normal on the side it leaves by) starts: off the
// surface by the float error of computing p (relative to `magnitude`, the largest of |p|, the
// incoming ray's origin and t: the offset follows the hit, not the scene) plus the hit's
// tolerance, so that it cannot hit that surface again, and no farther. The same rule for every
// backend.
vec3 offset_origin(vec3 p, vec3 n, float magnitude, float tolerance) {
  return p + (RAY_OFFSET_RELATIVE * magnitude + tolerance) * n;
}

float max_abs_component(vec3 v) {
  return max(abs(v.x), max(abs(v.y), abs(v.z)));
}

bool trace_occluded(Ray ray, float tmax) {
  float t;
  return floor_hit(ray, tmax, t) || any_hit(ray, tmax) || (has_implicits() && implicit_occluded(ray, tmax));
}

vec3 sky_color(vec3 dir) {
  return mix(vec3(frame.sky_horizon), vec3(frame.sky_zenith), sqrt(clamp(dir.y, 0.0f, 1.0f)));
}

// Bilinear image-texture lookup repeating every `checker_albedo.w` uv units; uv (0, 0) is the
// image's bottom-left corner, texel centres sit at half-integers.
vec3 image_texel(GpuMaterial m, vec2 uv) {
  vec2 extent = vec2(float(m.image_texture.y), float(m.image_texture.z));
  vec2 st = vec2(uv.x, -uv.y) / m.checker_albedo.w * extent - 0.5f;
  vec2 base = floor(st);
  vec2 f = st - base;
  uvec2 i0 = uvec2(clamp(base - extent * floor(base / extent), vec2(0.0f), extent - 1.0f));  // wrapped
  uvec2 i1 = uvec2(i0.x + 1u == m.image_texture.y ? 0u : i0.x + 1u, i0.y + 1u == m.image_texture.z ? 0u : i0.y + 1u);
  uint row0 = m.image_texture.x + i0.y * m.image_texture.y, row1 = m.image_texture.x + i1.y * m.image_texture.y;
  vec3 top = mix(vec3(texel_at(row0 + i0.x)), vec3(texel_at(row0 + i1.x)), f.x);
  vec3 bottom = mix(vec3(texel_at(row1 + i0.x)), vec3(texel_at(row1 + i1.x)), f.x);
  return mix(top, bottom, f.y);
}

// The uv a hit's material is textured by: a glTF mesh's texture coordinates interpolated at the
// hit's barycentrics (its material's uv table, two texels per triangle of the mesh), else the
// hit's own uv (barycentrics on meshes, the floor's x and z, the implicit objects' uv).
vec2 surface_uv(Hit hit) {
  uint table = materials[hit.material].image_texture.w;
  if (!has_textures() || table == NO_UV_TABLE || hit.instance == FLOOR_INSTANCE) return hit.uv;
  vec4 a = texel_at(table + 2u * hit.prim), b = texel_at(table + 2u * hit.prim + 1u);
  return (1.0f - hit.uv.x - hit.uv.y) * vec2(a.x, a.y) + hit.uv.x * vec2(a.z, a.w) + hit.uv.y * vec2(b.x, b.y);
}

// Albedo, or the checker's second colour on odd squares; times the image texture if any.
vec3 surface_albedo(uint material, vec2 uv) {
  GpuMaterial m = materials[material];
  float size = m.albedo.w;
  bool odd = size > 0.0f && mod(floor(uv.x / size) + floor(uv.y / size), 2.0f) > 0.5f;
  vec3 albedo = odd ? vec3(m.checker_albedo) : vec3(m.albedo);
  return has_textures() && m.checker_albedo.w > 0.0f ? albedo * image_texel(m, uv) : albedo;
}

// Lambert from every light, plus ambient; shadow rays (counted in `rays`) unless in primary mode.
vec3 direct_light(vec3 p, vec3 n, float magnitude, float tolerance, vec3 albedo, INOUT(uint) rays) {
  vec3 result = albedo * frame.tracing.y;
  for (uint i = 0u; i < frame.image.w; ++i) {
    GpuLight light = lights[i];
    vec3 to_light = vec3(light.position);
    float dist = frame.tracing.z;
    if (light.position.w > 0.5f) {
      vec3 d = vec3(light.position) - p;
      dist = length(d);
      to_light = d / dist;
    }
    float cosine = dot(n, to_light);
    if (cosine <= 0.0f) continue;
    if (shading_mode() != MODE_PRIMARY) {
      rays++;
      if (trace_occluded(Ray(offset_origin(p, n, magnitude, tolerance), to_light), dist)) continue;
    }
    result += albedo * vec3(light.color) * cosine;
  }
  return result;
}

// Display encoding (clamp + gamma 2.2): what the PNG holds and what images are compared on.
vec3 display_encode(vec3 c) {
  return pow(clamp(c, vec3(0.0f), vec3(1.0f)), vec3(1.0f / 2.2f));
}

float max_component(vec3 v) {
  return max(v.x, max(v.y, v.z));
}

// Unpolarised Fresnel reflectance of a dielectric interface, from the exact Fresnel equations
// (not Schlick's approximation, so that an ior of 1 reflects nothing); eta = n_from / n_to.
float fresnel_dielectric(float cos_i, float cos_t, float eta) {
  float rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (rs * rs + rp * rp);
}

void push_ray(INOUT(PixelState) s, vec3 origin, vec3 dir, vec3 weight, float depth) {
  stack_store(s.counters.x, PathEntry(vec4(origin, depth), vec4(dir, 0.0f), vec4(weight, 0.0f)));
  s.counters.x++;
}

void begin_pixel(OUT(PixelState) s, OUT(PixelAov) aov) {
  s.color = vec4(0.0f);
  s.counters = uvec4(0u);
  aov.depth = 0.0f;
  aov.instance = NO_INSTANCE;
  aov.prim = NO_INSTANCE;
  aov.normal = vec3(0.0f);
  aov.rays = 0u;
}

PathEntry primary_ray(uvec2 pixel) {
  Ray ray = camera_ray(pixel);
  return PathEntry(vec4(ray.origin, 0.0f), vec4(ray.dir, 0.0f), vec4(1.0f));
}

// Traces one ray of the pixel and adds what it sees, weighted (scenes/README.md details it).
// primary/shadow: the primary hit's direct light. whitted (thesis 5.3): each hit adds
// (1 - reflectance - transmission) x its direct light and pushes a mirror ray (weight
// reflectance + transmission x Fresnel) and a refracted ray (Snell; weight transmission x
// (1 - Fresnel), none under total internal reflection), up to max_depth, dropping rays whose
// weight falls below ENERGY_CUTOFF. The ray enters when it comes from the normal's side. Shadow
// rays treat every surface as opaque, glass included: any_hit does not report materials.
void trace_ray(PathEntry e, INOUT(PixelState) s, INOUT(PixelAov) aov) {
  s.counters.y++;
  Ray ray = Ray(vec3(e.origin), vec3(e.dir));
  vec3 weight = vec3(e.weight);
  Hit hit;
  float tolerance;
  if (!trace_closest(ray, frame.tracing.z, hit, tolerance)) {
    s.color += vec4(weight * sky_color(ray.dir), 0.0f);
  } else {
    bool entering = dot(hit.normal, ray.dir) < 0.0f;
    vec3 n = entering ? hit.normal : -hit.normal;  // facing the ray: surfaces are two-sided
    vec3 p = ray.origin + hit.t * ray.dir;
    float magnitude = max(max(max_abs_component(p), max_abs_component(ray.origin)), hit.t);
    if (e.origin.w == 0.0f) {
      aov.depth = hit.t;
      aov.instance = hit.instance;
      aov.prim = hit.prim;
      aov.normal = n;
    }
    vec4 optics = materials[hit.material].optics;
    float local = 1.0f, reflected = 0.0f, transmitted = 0.0f;
    vec3 refracted = vec3(0.0f);
    if (shading_mode() == MODE_WHITTED) {
      local = 1.0f - optics.x - optics.y;
      reflected = optics.x;
      if (optics.y > 0.0f) {
        float eta = entering ? 1.0f / optics.z : optics.z;
        float cos_i = -dot(ray.dir, n);
        float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
        float fresnel = 1.0f;  // total internal reflection
        if (sin2_t < 1.0f) {
          float cos_t = sqrt(1.0f - sin2_t);
          fresnel = fresnel_dielectric(cos_i, cos_t, eta);
          refracted = eta * ray.dir + (eta * cos_i - cos_t) * n;
        }
        reflected += optics.y * fresnel;
        transmitted = optics.y * (1.0f - fresnel);
      }
    }
    vec3 w = weight * local;
    if (max_component(w) >= ENERGY_CUTOFF)
      s.color += vec4(w * direct_light(p, n, magnitude, tolerance, surface_albedo(hit.material, surface_uv(hit)), s.counters.y), 0.0f);
    // The limit also bounds the stack (STACK_SIZE), whatever frame.limits holds.
    if (shading_mode() == MODE_WHITTED && e.origin.w < float(min(frame.limits.x, MAX_DEPTH_LIMIT))) {
      float depth = e.origin.w + 1.0f;
      w = weight * transmitted;
      if (max_component(w) >= ENERGY_CUTOFF) push_ray(s, offset_origin(p, -n, magnitude, tolerance), refracted, w, depth);
      w = weight * reflected;
      if (max_component(w) >= ENERGY_CUTOFF) push_ray(s, offset_origin(p, n, magnitude, tolerance), reflect(ray.dir, n), w, depth);
    }
  }
}

PathEntry pop_ray(INOUT(PixelState) s) {
  s.counters.x--;
  return stack_load(s.counters.x);
}

vec4 pixel_color(PixelState s) {
  return vec4(display_encode(vec3(s.color)), 1.0f);
}
