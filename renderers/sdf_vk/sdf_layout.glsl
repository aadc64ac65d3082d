// How the sdf-hash / sdf-octree kernels see the SDF structures, shared by GLSL and C++.
// The large arrays live in texel buffers (lavapipe serves divergent texel fetches ~12x faster
// than divergent storage-buffer reads, docs/design.md, "lavapipe, measured"); records that mix integers and floats are
// RGBA32UI texels holding float bits, so no float conversion can touch the integers.
#ifndef SDFBENCH_SDF_LAYOUT_GLSL
#define SDFBENCH_SDF_LAYOUT_GLSL

// Uniform block: the scene hash grid and the sphere-tracing parameters.
struct SdfParams {
  vec4 hash_origin;  // xyz: min corner of the hash box, w: hash cell size
  uvec4 hash_dims;   // xyz: cells per axis, w: max sphere-tracing steps
  vec4 tracing;      // x: hit epsilon in world units (hit_epsilon x scene scale), y: 1 for --hit exact,
                     // z: --hit-footprint (exact: the hit threshold as a fraction of a pixel's footprint),
                     // w: 0 (a zero the compiler cannot see: SDF_REPEAT_* in sdf_scene_distance.glsl)
  vec4 options;      // x: --over-relax omega (1: off); sdf-bricks: y: the hit tolerance of rays leaving
                     // a hit (mesh_hit_tolerance), z: the sampler's filter slack in voxels; w: the precision of its result,
                     // a fraction of the band (brick_filter_slack)
  uvec4 atlas_bricks;       // sdf-bricks with --brick-fetch sampler: bricks per image row (x) and slice (y); zw: 0
  vec4 atlas_inverse_size;  // its 1 / image extent (xyz); w: 0
};

// A node word, the same in the hash-cell table (each cell's octree root) and the octree-node
// table: with SDF_LEAF_BIT set, the low 31 bits are the offset of the leaf's instance list
// (its length; a lower bound on the distance from the leaf's box to any listed instance's box,
// float bits, 0 without --cell-bound (sdf-bricks: how many of the listed instances' boxes meet the
// leaf's box, listed first); then the instance indices); clear, the word is the index of the node's 8
// children (octant bit 0: +x, 1: +y, 2: +z). A hash-only structure is a leaf per cell; eight
// sibling leaves with the same list are stored as their parent, a leaf.
#define SDF_LEAF_BIT 0x80000000u

// Instance record, SDF_INSTANCE_TEXELS RGBA32UI texels (floats as bits): (world AABB min,
// mesh); (world AABB max, scale); world_to_object rows 0-2; object_to_world rows 0-2 with the
// material in the first row's w (only the 3x3 part turns normals). The AABB comes first: most
// listed instances are rejected by it before their transform is read.
#define SDF_INSTANCE_TEXELS 8

// Mesh record, SDF_MESH_TEXELS RGBA32UI texels: (grid origin xyz, cell size) as float bits;
// (grid dims xyz, first grid cell); (mesh bounds min xyz as float bits, first triangle);
// (mesh bounds max xyz as float bits, 0). A grid cell is an RG32UI texel (begin, end) of list
// entries, each cell's list nearest to the cell centre first. An entry is SDF_ENTRY_TEXELS RGBA32F
// texels, the triangle's vertices inline (one fetch fewer per triangle than through an index, and
// the first texel alone decides the early stop): (a, distance from the cell centre, rounded down);
// (b, global triangle index as float bits); (c, 0). Global triangle indices (the meshes'
// triangles concatenated) index the vertex and normal tables (3 RGBA32F texels per triangle).
#define SDF_MESH_TEXELS 4
#define SDF_ENTRY_TEXELS 3
// A far cell of a scaled grid (mesh_distance_grid.h) is (v, v) with v = its bound's float bits
// | SDF_FAR_CELL: an empty range for every list walk (begin = end, negative as int), and the
// bound for the distance. List entries stay below 2^31 (texel buffers hold 2^27 texels).
#define SDF_FAR_CELL 0x80000000u

#define SDF_NONE 0xffffffffu
// The triangle of a far cell's bound (kFarCellTriangle): no triangle, stepped without the
// epsilon floor.
#define SDF_FAR_TRIANGLE 0xfffffffeu

// The deepest octree below a hash cell (--octree-depth's limit, sdf::validate): the kernels'
// descent stops there whatever the node words hold, and the pixel is counted as cut short.
// (A test defines it smaller to see that reported.)
#ifndef SDF_MAX_OCTREE_DEPTH
#define SDF_MAX_OCTREE_DEPTH 16u
#endif

// --hit exact: the most mesh-grid cells one crossing search walks (a bound on the loop; a
// segment of two hit epsilons crosses a few).
#define SDF_EXACT_MAX_CELLS 512u
// --hit thesis: rays leave a hit this many hit epsilons off the surface (kThesisOffsetEpsilons).
#define SDF_THESIS_OFFSET_EPSILONS 20.0f

#endif
