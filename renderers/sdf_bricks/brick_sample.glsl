// Sampling a per-mesh brick field (renderers/sdf_bricks/brick_field.h), shared by the sdf-bricks kernel
// and its CPU reference (brick_cpu_sampler.h), so that the tests check the kernel's own
// arithmetic. The includer defines, before including this file:
//   uvec4 brick_record(int i)  texel i of the field records (BRICK_FIELD_TEXELS per mesh)
//   uint brick_slot(int i)     indirection entry i: a stored brick's index, or BRICK_EMPTY
//   float brick_value(int i)   atlas sample i as the texel fetch returns it (u8: UNORM in [0, 1])
//   float brick_decode(float raw, float band)  that in mesh units (identity but for u8:
//                              (2 raw - 1) band; linear, so it is applied after interpolating)
// and with BRICK_SAMPLER (--brick-fetch sampler: the atlas as a filtered 3D image):
//   float brick_filtered(uint slot, vec3 local)  the hardware's trilinear sample of stored brick
//                              `slot` at `local` (in samples, 0..7), as the texel fetch returns it
//   float brick_filter_slack(float voxel, float band)  how far that may be from the exact trilinear
//                              (filter weights of subTexelPrecisionBits, the filter's arithmetic)
//   float coarse_value(int i)  coarse sample i (exact signed distance at a brick corner)
#ifndef SDFBENCH_BRICK_SAMPLE_GLSL
#define SDFBENCH_BRICK_SAMPLE_GLSL

// Field record, BRICK_FIELD_TEXELS RGBA32UI texels per mesh (floats as bits): (lattice origin xyz,
// voxel h); (bricks per axis xyz, first indirection entry); (first coarse sample, band x h,
// quantization bound, margin: mesh bounds to lattice box); (coarse level at brick centres, 0, 0, 0).
#define BRICK_FIELD_TEXELS 4
#define BRICK_EMPTY 0xffffffffu
#define BRICK_CELLS 7u
#define BRICK_SIDE 8

struct BrickFieldInfo {
  vec3 origin;
  float voxel;
  uvec3 bricks;
  uint first_brick;
  uint first_coarse;
  float band;
  float quantization;
  float margin;
  bool coarse_at_centres;  // sdf-global: one lower bound per brick, at its centre (else brick corners)
};

struct FieldSample {
  float bound;  // a lower bound on the unsigned distance to the mesh (mesh units)
  float value;  // the trilinear field (signed) in a stored brick; elsewhere the bound
  bool stored;  // p lies in a stored brick
  uint slot;    // that brick's index in the atlas, else BRICK_EMPTY
  bool empty;   // p lies in an empty brick of the lattice: no surface in all of it
};

SHARED_FN BrickFieldInfo brick_field_info(uint mesh) {
  int base = int(mesh) * BRICK_FIELD_TEXELS;
  uvec4 r0 = brick_record(base), r1 = brick_record(base + 1), r2 = brick_record(base + 2), r3 = brick_record(base + 3);
  BrickFieldInfo f;
  f.origin = uintBitsToFloat(uvec3(r0.x, r0.y, r0.z));
  f.voxel = uintBitsToFloat(r0.w);
  f.bricks = uvec3(r1.x, r1.y, r1.z);
  f.first_brick = r1.w;
  f.first_coarse = r2.x;
  f.band = uintBitsToFloat(r2.y);
  f.quantization = uintBitsToFloat(r2.z);
  f.margin = uintBitsToFloat(r2.w);
  f.coarse_at_centres = r3.x != 0u;
  return f;
}

SHARED_FN vec3 brick_lattice_max(BrickFieldInfo f) { return f.origin + f.voxel * vec3(f.bricks * BRICK_CELLS); }

// How far a trilinear interpolation of distances can exceed the distance at p, for p at
// fractions `fr` of a cell of size h: h sqrt(sum f(1 - f)) (brick_field.h).
SHARED_FN float trilinear_slack(vec3 fr, float h) {
  vec3 spread = fr * (vec3(1.0f) - fr);
  return h * sqrt(spread.x + spread.y + spread.z);
}

SHARED_FN float trilinear(float c000, float c100, float c010, float c110, float c001, float c101, float c011, float c111,
                          vec3 fr) {
  float x00 = mix(c000, c100, fr.x), x10 = mix(c010, c110, fr.x), x01 = mix(c001, c101, fr.x), x11 = mix(c011, c111, fr.x);
  return mix(mix(x00, x10, fr.y), mix(x01, x11, fr.y), fr.z);
}

// The field at p (mesh space). Outside the lattice: the distance to the lattice box plus the
// margin less a voxel (the mesh lies inside its bounds, `margin` inside the box; a voxel less, so
// that a step from outside never lands exactly on a surface lying on the bounds). In an empty brick: the band (no point of the brick
// comes nearer), or the coarse level's bound where that is larger.
SHARED_FN FieldSample sample_field(BrickFieldInfo f, vec3 p) {
  FieldSample s;
  s.stored = false;
  s.slot = BRICK_EMPTY;
  s.empty = false;
  vec3 hi = brick_lattice_max(f);
  vec3 gap = max(max(f.origin - p, p - hi), vec3(0.0f));
  if (gap.x > 0.0f || gap.y > 0.0f || gap.z > 0.0f) {
    s.bound = length(gap) + f.margin - f.voxel;
    s.value = s.bound;
    return s;
  }
  uvec3 cells = f.bricks * BRICK_CELLS;
  vec3 g = (p - f.origin) / f.voxel;
  uvec3 c = min(uvec3(max(g, vec3(0.0f))), cells - uvec3(1u));
  vec3 fr = clamp(g - vec3(c), vec3(0.0f), vec3(1.0f));
  uvec3 b = c / BRICK_CELLS;
  uint slot = brick_slot(int(f.first_brick + b.x + f.bricks.x * (b.y + f.bricks.y * b.z)));
  if (slot == BRICK_EMPTY && f.coarse_at_centres) {
    // u(p) >= u(centre) - |p - centre| (u is 1-Lipschitz), and u >= band in all of an empty brick.
    float v = coarse_value(int(f.first_coarse + b.x + f.bricks.x * (b.y + f.bricks.y * b.z)));
    vec3 centre = f.origin + (vec3(b) + 0.5f) * (f.voxel * float(BRICK_CELLS));
    s.bound = max(f.band, v - length(p - centre) - 1e-6f * (v + length(p)));
    s.value = s.bound;
    s.empty = true;
    return s;
  }
  if (slot == BRICK_EMPTY) {
    uvec3 dims = f.bricks + uvec3(1u);
    vec3 gc = (p - f.origin) / (f.voxel * float(BRICK_CELLS));
    vec3 fc = clamp(gc - vec3(b), vec3(0.0f), vec3(1.0f));
    int i = int(f.first_coarse + b.x + dims.x * (b.y + dims.y * b.z));
    int dy = int(dims.x), dz = int(dims.x * dims.y);
    float v = trilinear(coarse_value(i), coarse_value(i + 1), coarse_value(i + dy), coarse_value(i + dy + 1),
                        coarse_value(i + dz), coarse_value(i + dz + 1), coarse_value(i + dz + dy),
                        coarse_value(i + dz + dy + 1), fc);
    s.bound = max(f.band, abs(v) - trilinear_slack(fc, f.voxel * float(BRICK_CELLS)) - 1e-6f * abs(v));
    s.value = s.bound;
    s.empty = true;
    return s;
  }
  uvec3 l = c - b * BRICK_CELLS;
#ifdef BRICK_SAMPLER
  s.value = brick_decode(brick_filtered(slot, vec3(l) + fr), f.band);
  s.bound = max(abs(s.value) - trilinear_slack(fr, f.voxel) - f.quantization - brick_filter_slack(f.voxel, f.band), 0.0f);
#else
  int i = int(slot) * (BRICK_SIDE * BRICK_SIDE * BRICK_SIDE) + int(l.x) + BRICK_SIDE * (int(l.y) + BRICK_SIDE * int(l.z));
  const int sy = BRICK_SIDE, sz = BRICK_SIDE * BRICK_SIDE;
  s.value = brick_decode(trilinear(brick_value(i), brick_value(i + 1), brick_value(i + sy), brick_value(i + sy + 1),
                                   brick_value(i + sz), brick_value(i + sz + 1), brick_value(i + sz + sy),
                                   brick_value(i + sz + sy + 1), fr),
                         f.band);
  s.bound = max(abs(s.value) - trilinear_slack(fr, f.voxel) - f.quantization, 0.0f);
#endif
  s.stored = true;
  s.slot = slot;
  return s;
}

#endif
