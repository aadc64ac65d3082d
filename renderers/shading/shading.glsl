// The one shading program of every backend (GLSL kernels and, through cpu_shading.h, C++).
// Before including it, define: `frame` (FrameParams), `materials[]`, `lights[]` and the
// backend's two queries
//   bool closest_hit(Ray ray, float tmax, OUT(Hit) hit)   nearest surface with t in (0, tmax)
//   bool any_hit(Ray ray, float tmax)                      any surface with t in (0, tmax)
// The floor is an analytic plane handled here, identically for every backend.

uint rays_traced = 0u;  // per invocation (GLSL global) / per CpuShading object (C++ member)

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

bool trace_closest(Ray ray, float tmax, OUT(Hit) hit) {
  rays_traced++;
  bool found = closest_hit(ray, tmax, hit);
  float t;
  if (floor_hit(ray, found ? hit.t : tmax, t)) {
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

bool trace_occluded(Ray ray, float tmax) {
  rays_traced++;
  float t;
  return floor_hit(ray, tmax, t) || any_hit(ray, tmax);
}

vec3 sky_color(vec3 dir) {
  return mix(vec3(frame.sky_horizon), vec3(frame.sky_zenith), sqrt(clamp(dir.y, 0.0f, 1.0f)));
}

vec3 surface_albedo(uint material, vec2 uv) {
  GpuMaterial m = materials[material];
  float size = m.albedo.w;
  if (size > 0.0f && mod(floor(uv.x / size) + floor(uv.y / size), 2.0f) > 0.5f) return vec3(m.checker_albedo);
  return vec3(m.albedo);
}

// Lambert from every light, plus ambient; shadow rays unless in primary mode.
vec3 direct_light(vec3 p, vec3 n, vec3 albedo) {
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
    if (frame.image.z != MODE_PRIMARY && trace_occluded(Ray(p + frame.tracing.x * n, to_light), dist)) continue;
    result += albedo * vec3(light.color) * cosine;
  }
  return result;
}

// Display encoding (clamp + gamma 2.2): what the PNG holds and what images are compared on.
vec3 display_encode(vec3 c) {
  return pow(clamp(c, vec3(0.0f), vec3(1.0f)), vec3(1.0f / 2.2f));
}

vec4 shade_pixel(uvec2 pixel, OUT(PixelAov) aov) {
  Ray ray = camera_ray(pixel);
  rays_traced = 0u;
  aov.depth = 0.0f;
  aov.instance = NO_INSTANCE;
  aov.prim = NO_INSTANCE;
  aov.normal = vec3(0.0f);
  Hit hit;
  vec3 color = sky_color(ray.dir);
  if (trace_closest(ray, frame.tracing.z, hit)) {
    vec3 n = dot(hit.normal, ray.dir) > 0.0f ? -hit.normal : hit.normal;
    aov.depth = hit.t;
    aov.instance = hit.instance;
    aov.prim = hit.prim;
    aov.normal = n;
    color = direct_light(ray.origin + hit.t * ray.dir, n, surface_albedo(hit.material, hit.uv));
  }
  aov.rays = rays_traced;
  return vec4(display_encode(color), 1.0f);
}
