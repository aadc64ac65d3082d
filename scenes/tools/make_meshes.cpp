// make_meshes: regenerate the four thesis meshes (bunny, teapot, monkey,
// sphere) as plain triangle OBJ files, deterministically.
//
//   make_meshes --sources DIR --out scenes/meshes [--only NAME]...
//   make_meshes --check FILE.obj...
//
// DIR is the directory printed by scenes/tools/fetch_mesh_sources.sh (unpacked
// npm packages bunny@1.0.1, teapot@1.0.0, @gsimone/suzanne@0.0.12 plus the
// Draco-decoded suzanne-decoded.gltf).  The sphere needs no sources.
// See scenes/meshes/PROVENANCE.md for what is done to each mesh and why.
//
// Every output mesh is: triangles only, welded (no two vertices share a
// position), free of zero-area triangles, consistently wound (CCW seen from
// outside), y-up, with its bounding box centred at the origin and its largest
// bounding-box extent equal to 2.  Target triangle counts are exact.
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// ---------------------------------------------------------------------------
// Basic mesh type and helpers
// ---------------------------------------------------------------------------
struct Mesh {
  std::vector<float> pos;       // xyz per vertex
  std::vector<uint32_t> idx;    // 3 per triangle
  size_t vertex_count() const { return pos.size() / 3; }
  size_t tri_count() const { return idx.size() / 3; }
};

[[noreturn]] void fail(const std::string& msg) { throw std::runtime_error(msg); }

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  if (!f) fail("cannot open " + p.string());
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct V3 {
  double x, y, z;
};
V3 sub(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double len(V3 a) { return std::sqrt(dot(a, a)); }
V3 vert(const Mesh& m, uint32_t i) { return {m.pos[3 * i], m.pos[3 * i + 1], m.pos[3 * i + 2]}; }

struct Box {
  V3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  double max_extent() const { return std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}); }
};
Box bbox(const Mesh& m) {
  Box b;
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    V3 p = vert(m, uint32_t(i));
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
  }
  return b;
}

// Drop unreferenced vertices; vertices are renumbered in order of first use.
void compact(Mesh& m) {
  std::vector<uint32_t> remap(m.vertex_count(), UINT32_MAX);
  std::vector<float> np;
  for (auto& i : m.idx) {
    if (remap[i] == UINT32_MAX) {
      remap[i] = uint32_t(np.size() / 3);
      np.insert(np.end(), m.pos.begin() + 3 * i, m.pos.begin() + 3 * i + 3);
    }
    i = remap[i];
  }
  m.pos = std::move(np);
}

// Weld vertices with bit-identical positions (meshopt_generateVertexRemap on
// the position stream only), then compact.
void weld_exact(Mesh& m) {
  std::vector<unsigned int> remap(m.vertex_count());
  size_t unique = meshopt_generateVertexRemap(remap.data(), m.idx.data(), m.idx.size(), m.pos.data(),
                                              m.vertex_count(), sizeof(float) * 3);
  std::vector<float> np(unique * 3);
  meshopt_remapVertexBuffer(np.data(), m.pos.data(), m.vertex_count(), sizeof(float) * 3, remap.data());
  std::vector<uint32_t> ni(m.idx.size());
  meshopt_remapIndexBuffer(ni.data(), m.idx.data(), m.idx.size(), remap.data());
  m.pos = std::move(np);
  m.idx = std::move(ni);
  compact(m);
}

// Weld vertices closer than eps (union-find over all pairs; fine for a few
// thousand vertices).  Each class takes the position of its lowest-numbered
// member, so the result is deterministic.  Returns the smallest distance
// between two vertices that were NOT welded (to show eps is well separated).
double weld_tolerance(Mesh& m, double eps) {
  const size_t n = m.vertex_count();
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  std::function<uint32_t(uint32_t)> find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if (len(sub(vert(m, uint32_t(i)), vert(m, uint32_t(j)))) < eps) {
        uint32_t a = find(uint32_t(i)), b = find(uint32_t(j));
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
  double min_sep = 1e300;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if (find(uint32_t(i)) != find(uint32_t(j)))
        min_sep = std::min(min_sep, len(sub(vert(m, uint32_t(i)), vert(m, uint32_t(j)))));
  for (auto& i : m.idx) i = find(i);
  compact(m);
  return min_sep;
}

double tri_area(const Mesh& m, size_t t) {
  V3 a = vert(m, m.idx[3 * t]), b = vert(m, m.idx[3 * t + 1]), c = vert(m, m.idx[3 * t + 2]);
  return 0.5 * len(cross(sub(b, a), sub(c, a)));
}

// ---------------------------------------------------------------------------
// Topology statistics (used for the log and by --check)
// ---------------------------------------------------------------------------
struct Stats {
  size_t tris = 0, verts = 0, unused_verts = 0, dup_positions = 0, degenerate = 0, repeated_index = 0;
  size_t boundary_edges = 0, nonmanifold_edges = 0, nonmanifold_vertices = 0, misoriented_edges = 0, components = 0;
  double min_area = 0, signed_volume = 0;
  Box box;
};

Stats stats(const Mesh& m) {
  Stats s;
  s.tris = m.tri_count();
  s.verts = m.vertex_count();
  s.box = bbox(m);
  {
    std::vector<bool> used(s.verts, false);
    for (auto i : m.idx) used[i] = true;
    s.unused_verts = size_t(std::count(used.begin(), used.end(), false));
    std::vector<std::array<float, 3>> p(s.verts);
    for (size_t i = 0; i < s.verts; ++i) p[i] = {m.pos[3 * i], m.pos[3 * i + 1], m.pos[3 * i + 2]};
    std::sort(p.begin(), p.end());
    s.dup_positions = size_t(std::unique(p.begin(), p.end()) - p.begin());
    s.dup_positions = s.verts - s.dup_positions;
  }
  const double ext = s.box.max_extent();
  s.min_area = 1e300;
  std::map<std::pair<uint32_t, uint32_t>, std::array<int, 2>> edges;  // (min,max) -> {forward, backward}
  std::vector<uint32_t> comp(s.verts);
  std::iota(comp.begin(), comp.end(), 0u);
  std::function<uint32_t(uint32_t)> find = [&](uint32_t x) {
    while (comp[x] != x) x = comp[x] = comp[comp[x]];
    return x;
  };
  for (size_t t = 0; t < s.tris; ++t) {
    uint32_t v[3] = {m.idx[3 * t], m.idx[3 * t + 1], m.idx[3 * t + 2]};
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) ++s.repeated_index;
    double a = tri_area(m, t);
    s.min_area = std::min(s.min_area, a);
    if (a <= 1e-12 * ext * ext) ++s.degenerate;
    V3 p0 = vert(m, v[0]), p1 = vert(m, v[1]), p2 = vert(m, v[2]);
    s.signed_volume += dot(p0, cross(p1, p2)) / 6.0;
    for (int k = 0; k < 3; ++k) {
      uint32_t a0 = v[k], b0 = v[(k + 1) % 3];
      auto& e = edges[{std::min(a0, b0), std::max(a0, b0)}];
      ++e[a0 < b0 ? 0 : 1];
      uint32_t ra = find(a0), rb = find(b0);
      if (ra != rb) comp[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  for (auto& [k, e] : edges) {
    int total = e[0] + e[1];
    if (total == 1) ++s.boundary_edges;
    if (total > 2) ++s.nonmanifold_edges;
    if (total == 2 && e[0] != 1) ++s.misoriented_edges;
  }
  std::vector<bool> used(s.verts, false);
  for (auto i : m.idx) used[i] = true;
  for (size_t i = 0; i < s.verts; ++i)
    if (used[i] && find(uint32_t(i)) == i) ++s.components;
  // Non-manifold vertices: the triangles around the vertex form more than one
  // edge-connected fan (e.g. two surfaces touching at a single point).
  {
    std::vector<std::vector<uint32_t>> vt(s.verts);
    for (size_t t = 0; t < s.tris; ++t)
      for (int k = 0; k < 3; ++k) vt[m.idx[3 * t + k]].push_back(uint32_t(t));
    for (size_t v = 0; v < s.verts; ++v) {
      const auto& ts = vt[v];
      std::vector<size_t> par(ts.size());
      std::iota(par.begin(), par.end(), size_t(0));
      std::function<size_t(size_t)> f = [&](size_t x) {
        while (par[x] != x) x = par[x] = par[par[x]];
        return x;
      };
      std::map<uint32_t, size_t> by_other;  // neighbour vertex -> first triangle (index into ts)
      for (size_t i = 0; i < ts.size(); ++i)
        for (int k = 0; k < 3; ++k) {
          uint32_t o = m.idx[3 * ts[i] + k];
          if (o == v) continue;
          auto [it, fresh] = by_other.emplace(o, i);
          if (!fresh) par[f(i)] = f(it->second);
        }
      size_t fans = 0;
      for (size_t i = 0; i < ts.size(); ++i) fans += f(i) == i;
      if (fans > 1) ++s.nonmanifold_vertices;
    }
  }
  if (s.tris == 0) s.min_area = 0;
  return s;
}

void print_stats(const std::string& name, const Stats& s) {
  std::printf(
      "%-8s tris %5zu  verts %5zu  boundary_edges %4zu  nonmanifold_edges %zu  nonmanifold_vertices %zu  "
      "misoriented_edges %zu  components %zu  dup_positions %zu  degenerate %zu  repeated_index %zu  "
      "unused_verts %zu\n"
      "         bbox [%.6f %.6f %.6f] .. [%.6f %.6f %.6f]  min_area %.3g  signed_volume %.6f\n",
      name.c_str(), s.tris, s.verts, s.boundary_edges, s.nonmanifold_edges, s.nonmanifold_vertices,
      s.misoriented_edges, s.components,
      s.dup_positions, s.degenerate, s.repeated_index, s.unused_verts, s.box.lo.x, s.box.lo.y, s.box.lo.z,
      s.box.hi.x, s.box.hi.y, s.box.hi.z, s.min_area, s.signed_volume);
}

// ---------------------------------------------------------------------------
// Output
// ---------------------------------------------------------------------------
void normalize(Mesh& m) {
  Box b = bbox(m);
  const double cx = 0.5 * (b.lo.x + b.hi.x), cy = 0.5 * (b.lo.y + b.hi.y), cz = 0.5 * (b.lo.z + b.hi.z);
  const double s = 2.0 / b.max_extent();
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    m.pos[3 * i + 0] = float((m.pos[3 * i + 0] - cx) * s);
    m.pos[3 * i + 1] = float((m.pos[3 * i + 1] - cy) * s);
    m.pos[3 * i + 2] = float((m.pos[3 * i + 2] - cz) * s);
  }
}

// Shortest decimal that round-trips to the same float, fixed notation.
std::string fmt(float v) {
  if (v == 0.0f) v = 0.0f;  // no "-0"
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
  if (r.ec != std::errc()) fail("to_chars failed");
  return std::string(buf, r.ptr);
}

void write_obj(const fs::path& path, const Mesh& m, const std::string& name, const std::vector<std::string>& notes) {
  std::string out;
  out += "# sdfbench mesh: " + name + "\n";
  out += "# triangles: " + std::to_string(m.tri_count()) + "\n";
  out += "# vertices: " + std::to_string(m.vertex_count()) + "\n";
  for (auto& n : notes) out += "# " + n + "\n";
  out += "# generated by scenes/tools/make_meshes.cpp; see scenes/meshes/PROVENANCE.md\n";
  out += "# y-up, CCW winding seen from outside, bbox centred at origin, largest extent 2\n";
  for (size_t i = 0; i < m.vertex_count(); ++i)
    out += "v " + fmt(m.pos[3 * i]) + " " + fmt(m.pos[3 * i + 1]) + " " + fmt(m.pos[3 * i + 2]) + "\n";
  for (size_t t = 0; t < m.tri_count(); ++t)
    out += "f " + std::to_string(m.idx[3 * t] + 1) + " " + std::to_string(m.idx[3 * t + 1] + 1) + " " +
           std::to_string(m.idx[3 * t + 2] + 1) + "\n";
  std::ofstream f(path, std::ios::binary);
  if (!f) fail("cannot write " + path.string());
  f << out;
  if (!f) fail("write failed: " + path.string());
}

Mesh read_obj(const fs::path& path) {
  Mesh m;
  std::istringstream in(read_text(path));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      double x, y, z;
      if (!(ls >> x >> y >> z)) fail("bad v line in " + path.string());
      m.pos.insert(m.pos.end(), {float(x), float(y), float(z)});
    } else if (tag == "f") {
      std::vector<long> f;
      std::string tok;
      while (ls >> tok) f.push_back(std::stol(tok.substr(0, tok.find('/'))));
      if (f.size() != 3) fail("non-triangle face in " + path.string());
      for (long i : f) {
        if (i < 1) fail("bad index in " + path.string());
        m.idx.push_back(uint32_t(i - 1));
      }
    } else if (!tag.empty() && tag[0] != '#') {
      fail("unexpected line '" + line + "' in " + path.string());
    }
  }
  for (auto i : m.idx)
    if (i >= m.vertex_count()) fail("index out of range in " + path.string());
  return m;
}

// ---------------------------------------------------------------------------
// Source parsing
// ---------------------------------------------------------------------------

// The npm packages are CommonJS files of the form
//   exports.positions=[[x,y,z],...]\n exports.cells=[[a,b,c],...]
// Extract the bracketed array after "exports.NAME=" and parse it as JSON.
json js_export_array(const std::string& js, const std::string& name) {
  const std::string key = "exports." + name + "=";
  size_t p = js.find(key);
  if (p == std::string::npos) fail("no '" + key + "' in source");
  p = js.find('[', p);
  int depth = 0;
  size_t e = p;
  for (; e < js.size(); ++e) {
    if (js[e] == '[') ++depth;
    if (js[e] == ']' && --depth == 0) break;
  }
  if (depth != 0) fail("unterminated array for " + name);
  return json::parse(js.begin() + std::ptrdiff_t(p), js.begin() + std::ptrdiff_t(e + 1));
}

Mesh load_js_mesh(const fs::path& file) {
  const std::string js = read_text(file);
  json P = js_export_array(js, "positions"), C = js_export_array(js, "cells");
  Mesh m;
  for (auto& p : P) {
    if (p.size() != 3) fail("position is not 3D in " + file.string());
    for (auto& c : p) m.pos.push_back(c.get<float>());
  }
  for (auto& c : C) {
    if (c.size() != 3) fail("cell is not a triangle in " + file.string());
    for (auto& i : c) {
      auto v = i.get<long>();
      if (v < 0 || size_t(v) >= m.vertex_count()) fail("cell index out of range in " + file.string());
      m.idx.push_back(uint32_t(v));
    }
  }
  return m;
}

std::vector<uint8_t> base64_decode(const std::string& s) {
  auto val = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+' || c == '-') return 62;
    if (c == '/' || c == '_') return 63;
    return -1;
  };
  std::vector<uint8_t> out;
  uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    if (c == '=') break;
    int v = val(c);
    if (v < 0) continue;  // whitespace
    acc = (acc << 6) | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(uint8_t((acc >> bits) & 0xFF));
    }
  }
  return out;
}

// Minimal glTF 2.0 reader: .gltf (external .bin or base64 data: URI) or .glb.
// Reads POSITION (FLOAT VEC3) and indices (UNSIGNED_BYTE/SHORT/INT, or none)
// of every triangle primitive of the first mesh whose name matches (or the
// first mesh), honouring byteOffset/byteStride.  Node transforms are not
// applied (an error is raised if the node carries one).
Mesh load_gltf(const fs::path& file, const std::string& mesh_name) {
  std::string raw = read_text(file);
  json g;
  std::vector<uint8_t> glb_bin;
  if (raw.size() >= 12 && raw.compare(0, 4, "glTF") == 0) {
    auto u32 = [&](size_t o) {
      uint32_t v;
      std::memcpy(&v, raw.data() + o, 4);
      return v;
    };
    size_t off = 12;
    while (off + 8 <= raw.size()) {
      uint32_t clen = u32(off), ctype = u32(off + 4);
      if (ctype == 0x4E4F534Au) g = json::parse(raw.substr(off + 8, clen));
      if (ctype == 0x004E4942u) glb_bin.assign(raw.begin() + std::ptrdiff_t(off + 8), raw.begin() + std::ptrdiff_t(off + 8 + clen));
      off += 8 + clen;
    }
  } else {
    g = json::parse(raw);
  }
  for (auto& e : g.value("extensionsRequired", json::array()))
    fail(file.string() + " requires glTF extension " + e.get<std::string>() +
         " (for the Draco-compressed Suzanne run decode_draco_gltf.js first)");

  std::vector<std::vector<uint8_t>> buffers;
  for (auto& b : g.at("buffers")) {
    if (!b.contains("uri")) {
      buffers.push_back(glb_bin);
      continue;
    }
    std::string uri = b.at("uri").get<std::string>();
    if (uri.rfind("data:", 0) == 0) {
      size_t comma = uri.find(',');
      if (comma == std::string::npos || uri.substr(0, comma).find(";base64") == std::string::npos)
        fail("unsupported data URI in " + file.string());
      buffers.push_back(base64_decode(uri.substr(comma + 1)));
    } else {
      std::string bin = read_text(file.parent_path() / uri);
      buffers.emplace_back(bin.begin(), bin.end());
    }
    if (buffers.back().size() < b.at("byteLength").get<size_t>()) fail("buffer too short in " + file.string());
  }

  auto component_size = [](int ct) -> size_t {
    switch (ct) {
      case 5120: case 5121: return 1;
      case 5122: case 5123: return 2;
      case 5125: case 5126: return 4;
    }
    fail("unknown componentType " + std::to_string(ct));
  };
  auto type_count = [](const std::string& t) -> size_t {
    if (t == "SCALAR") return 1;
    if (t == "VEC2") return 2;
    if (t == "VEC3") return 3;
    if (t == "VEC4") return 4;
    fail("unsupported accessor type " + t);
  };
  // Returns a pointer to element i (component 0) of an accessor.
  struct View {
    const uint8_t* base;
    size_t stride, count;
    int ct;
    size_t ncomp;
  };
  auto accessor = [&](size_t ai) -> View {
    const json& a = g.at("accessors").at(ai);
    if (a.contains("sparse")) fail("sparse accessors not supported");
    if (!a.contains("bufferView")) fail("accessor without bufferView");
    const json& bv = g.at("bufferViews").at(a.at("bufferView").get<size_t>());
    const auto& buf = buffers.at(bv.at("buffer").get<size_t>());
    int ct = a.at("componentType").get<int>();
    size_t nc = type_count(a.at("type").get<std::string>());
    size_t esize = component_size(ct) * nc;
    size_t stride = bv.value("byteStride", size_t(0));
    if (stride == 0) stride = esize;
    size_t off = bv.value("byteOffset", size_t(0)) + a.value("byteOffset", size_t(0));
    size_t count = a.at("count").get<size_t>();
    if (count > 0 && off + stride * (count - 1) + esize > bv.value("byteOffset", size_t(0)) + bv.at("byteLength").get<size_t>())
      fail("accessor exceeds its bufferView");
    if (off + (count ? stride * (count - 1) + esize : 0) > buf.size()) fail("accessor exceeds buffer");
    return {buf.data() + off, stride, count, ct, nc};
  };

  const json& meshes = g.at("meshes");
  size_t mi = 0;
  for (size_t i = 0; i < meshes.size(); ++i)
    if (meshes[i].value("name", "") == mesh_name) {
      mi = i;
      break;
    }
  for (auto& n : g.value("nodes", json::array()))
    if (n.value("mesh", -1) == int(mi) && (n.contains("matrix") || n.contains("translation") || n.contains("rotation") || n.contains("scale")))
      fail("node transforms on the mesh node are not supported");

  Mesh m;
  for (auto& prim : meshes[mi].at("primitives")) {
    if (prim.value("mode", 4) != 4) fail("non-triangle primitive");
    View pv = accessor(prim.at("attributes").at("POSITION").get<size_t>());
    if (pv.ct != 5126 || pv.ncomp != 3) fail("POSITION must be FLOAT VEC3");
    if (prim.contains("extensions")) fail("primitive extensions not supported");
    const uint32_t base = uint32_t(m.vertex_count());
    for (size_t i = 0; i < pv.count; ++i) {
      float p[3];
      std::memcpy(p, pv.base + i * pv.stride, 12);
      m.pos.insert(m.pos.end(), p, p + 3);
    }
    if (prim.contains("indices")) {
      View iv = accessor(prim.at("indices").get<size_t>());
      if (iv.ncomp != 1) fail("indices must be SCALAR");
      for (size_t i = 0; i < iv.count; ++i) {
        const uint8_t* q = iv.base + i * iv.stride;
        uint32_t v;
        if (iv.ct == 5121) v = *q;
        else if (iv.ct == 5123) { uint16_t s; std::memcpy(&s, q, 2); v = s; }
        else if (iv.ct == 5125) std::memcpy(&v, q, 4);
        else fail("indices componentType must be 5121/5123/5125");
        if (v >= pv.count) fail("index out of range");
        m.idx.push_back(base + v);
      }
    } else {
      for (size_t i = 0; i < pv.count; ++i) m.idx.push_back(base + uint32_t(i));
    }
  }
  if (m.idx.size() % 3) fail("index count not a multiple of 3");
  return m;
}

// ---------------------------------------------------------------------------
// Simplification to an exact triangle count
// ---------------------------------------------------------------------------
// meshopt_simplify stops at or below target_index_count (it collapses edges
// in batches), so the requested target is scanned upward from the desired
// count until the result is exactly `target_tris` triangles.  On a mesh with
// open borders, collapsing a border edge removes one triangle and an interior
// edge two, so the reachable counts can skip the target; the scan is then
// repeated with meshopt_SimplifyLockBorder (only interior collapses, which
// keeps the parity of the triangle count).  Fully deterministic.
Mesh simplify_exact(const Mesh& in, size_t target_tris, std::string& log) {
  const float target_error = 1.0f;  // relative to mesh extent: effectively unlimited
  std::vector<uint32_t> out(in.idx.size());
  for (unsigned options : {0u, unsigned(meshopt_SimplifyLockBorder)}) {
    size_t tried = 0;
    for (size_t t = target_tris * 3; t <= in.idx.size(); t += 3) {
      ++tried;
      float err = 0;
      size_t n = meshopt_simplify(out.data(), in.idx.data(), in.idx.size(), in.pos.data(), in.vertex_count(),
                                  sizeof(float) * 3, t, target_error, options, &err);
      if (n / 3 > target_tris) break;  // overshot: next strategy
      if (n / 3 != target_tris) continue;
      Mesh m{in.pos, std::vector<uint32_t>(out.begin(), out.begin() + std::ptrdiff_t(n))};
      compact(m);
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "meshopt_simplify(target_index_count=%zu, target_error=%.1f, options=%s) -> %zu triangles, "
                    "relative error %.3g (meshoptimizer %d.%d)",
                    t, double(target_error), options ? "meshopt_SimplifyLockBorder" : "0", n / 3, double(err),
                    MESHOPTIMIZER_VERSION / 1000, MESHOPTIMIZER_VERSION % 1000 / 10);
      log = buf;
      return m;
    }
  }
  fail("could not reach exactly " + std::to_string(target_tris) + " triangles with meshopt_simplify");
}

// Edge flips restricted to (numerically) coplanar triangle pairs, accepted
// when they increase the smaller of the two triangles' minimum angles (a
// planar Delaunay-style improvement).  They change neither the triangle count
// nor the surface, and remove the zero-area triangles that simplifying a
// midpoint-subdivided mesh leaves behind (an edge midpoint that ends up in a
// triangle with both endpoints of its edge).  Deterministic: edges are
// visited in sorted order, passes repeat until nothing changes.
size_t flip_coplanar(Mesh& m) {
  const double ext = bbox(m).max_extent();
  auto min_angle = [&](uint32_t a, uint32_t b, uint32_t c) {
    V3 p[3] = {vert(m, a), vert(m, b), vert(m, c)};
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
      V3 e1 = sub(p[(k + 1) % 3], p[k]), e2 = sub(p[(k + 2) % 3], p[k]);
      double l = len(e1) * len(e2);
      best = std::min(best, l > 0 ? std::atan2(len(cross(e1, e2)), dot(e1, e2)) : 0.0);
    }
    return best;
  };
  auto normal = [&](uint32_t a, uint32_t b, uint32_t c) {
    return cross(sub(vert(m, b), vert(m, a)), sub(vert(m, c), vert(m, a)));
  };
  size_t flips = 0;
  for (int pass = 0; pass < 1000; ++pass) {
    std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edge_tris;  // directed edge -> triangles
    for (size_t t = 0; t < m.tri_count(); ++t)
      for (int k = 0; k < 3; ++k) edge_tris[{m.idx[3 * t + k], m.idx[3 * t + (k + 1) % 3]}].push_back(t);
    std::vector<bool> touched(m.tri_count(), false);
    size_t pass_flips = 0;
    for (auto& [e, ts] : edge_tris) {
      auto [u, v] = e;
      if (u > v || ts.size() != 1) continue;
      auto rev = edge_tris.find({v, u});
      if (rev == edge_tris.end() || rev->second.size() != 1) continue;
      size_t t1 = ts[0], t2 = rev->second[0];
      if (touched[t1] || touched[t2]) continue;
      auto third = [&](size_t t) {
        for (int k = 0; k < 3; ++k)
          if (m.idx[3 * t + k] != u && m.idx[3 * t + k] != v) return m.idx[3 * t + k];
        return UINT32_MAX;
      };
      uint32_t x = third(t1), y = third(t2);  // t1 = (u,v,x), t2 = (v,u,y)
      if (x == UINT32_MAX || y == UINT32_MAX || x == y) continue;
      if (edge_tris.count({x, y}) || edge_tris.count({y, x})) continue;  // would duplicate an edge
      V3 pu = vert(m, u), pv = vert(m, v), px = vert(m, x), py = vert(m, y);
      double lmax = std::max({len(sub(pv, pu)), len(sub(px, pu)), len(sub(py, pu)), len(sub(px, pv)), len(sub(py, pv))});
      double vol6 = std::abs(dot(sub(px, pu), cross(sub(pv, pu), sub(py, pu))));
      if (vol6 > 1e-6 * lmax * lmax * lmax) continue;  // not coplanar
      V3 nref = normal(u, v, x);
      V3 n2 = normal(v, u, y);
      nref = {nref.x + n2.x, nref.y + n2.y, nref.z + n2.z};
      V3 na = normal(u, y, x), nb = normal(y, v, x);  // new triangles (u,y,x), (y,v,x)
      if (dot(na, nref) <= 0 || dot(nb, nref) <= 0) continue;   // non-convex quad: would fold
      if (len(na) <= 1e-12 * ext * ext || len(nb) <= 1e-12 * ext * ext) continue;
      double before = std::min(min_angle(u, v, x), min_angle(v, u, y));
      double after = std::min(min_angle(u, y, x), min_angle(y, v, x));
      if (after <= before + 1e-9) continue;
      m.idx[3 * t1] = u, m.idx[3 * t1 + 1] = y, m.idx[3 * t1 + 2] = x;
      m.idx[3 * t2] = y, m.idx[3 * t2 + 1] = v, m.idx[3 * t2 + 2] = x;
      touched[t1] = touched[t2] = true;
      ++pass_flips;
    }
    flips += pass_flips;
    if (pass_flips == 0) return flips;
  }
  fail("flip_coplanar did not converge");
}

// Midpoint subdivision: every triangle -> 4 (geometry unchanged).
Mesh subdivide_midpoint(const Mesh& in) {
  Mesh m;
  m.pos = in.pos;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
  auto midpoint = [&](uint32_t a, uint32_t b) {
    auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    uint32_t id = uint32_t(m.vertex_count());
    for (int k = 0; k < 3; ++k)
      m.pos.push_back(float(0.5 * (double(in.pos[3 * a + k]) + double(in.pos[3 * b + k]))));
    mid.emplace(key, id);
    return id;
  };
  for (size_t t = 0; t < in.tri_count(); ++t) {
    uint32_t a = in.idx[3 * t], b = in.idx[3 * t + 1], c = in.idx[3 * t + 2];
    uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    m.idx.insert(m.idx.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return m;
}

void require(bool ok, const std::string& what) {
  if (!ok) fail("check failed: " + what);
}

// Final checks shared by all meshes (on the normalized mesh).
void final_checks(const std::string& name, const Mesh& m, size_t target) {
  Stats s = stats(m);
  print_stats(name, s);
  require(s.tris == target, name + ": triangle count " + std::to_string(s.tris) + " != " + std::to_string(target));
  require(s.dup_positions == 0, name + ": duplicate vertex positions");
  require(s.degenerate == 0 && s.repeated_index == 0, name + ": degenerate triangles");
  require(s.unused_verts == 0, name + ": unused vertices");
  require(s.misoriented_edges == 0, name + ": inconsistent winding");
  require(s.signed_volume > 0, name + ": inward winding (negative signed volume)");
  require(std::abs(s.box.max_extent() - 2.0) < 1e-5, name + ": extent != 2");
}

// ---------------------------------------------------------------------------
// The four meshes
// ---------------------------------------------------------------------------
struct Result {
  Mesh mesh;
  std::vector<std::string> notes;
};

Result make_sphere() {
  // UV sphere, y-up. S segments around, R rings from pole to pole: R-1
  // latitude circles of S vertices plus two pole vertices.  Pole caps are
  // triangle fans (S triangles each), the R-2 bands between circles are S
  // quads = 2S triangles each: 2S + 2S(R-2) = 2S(R-1) = 2*32*12 = 768.
  const int S = 32, R = 13;
  const double pi = 3.14159265358979323846;
  Mesh m;
  m.pos.insert(m.pos.end(), {0.0f, 1.0f, 0.0f});  // 0: north pole
  for (int r = 1; r < R; ++r) {
    double th = pi * r / R;
    for (int s = 0; s < S; ++s) {
      double ph = 2 * pi * s / S;
      m.pos.insert(m.pos.end(), {float(std::sin(th) * std::sin(ph)), float(std::cos(th)), float(std::sin(th) * std::cos(ph))});
    }
  }
  const uint32_t south = uint32_t(m.vertex_count());
  m.pos.insert(m.pos.end(), {0.0f, -1.0f, 0.0f});
  auto ring = [&](int r, int s) { return uint32_t(1 + (r - 1) * S + (s % S)); };
  for (int s = 0; s < S; ++s) m.idx.insert(m.idx.end(), {0u, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r < R - 1; ++r)
    for (int s = 0; s < S; ++s) {
      uint32_t a = ring(r, s), b = ring(r + 1, s), c = ring(r + 1, s + 1), d = ring(r, s + 1);
      m.idx.insert(m.idx.end(), {a, b, c, c, d, a});
    }
  for (int s = 0; s < S; ++s) m.idx.insert(m.idx.end(), {south, ring(R - 1, s + 1), ring(R - 1, s)});
  std::printf("sphere: UV sphere S=%d R=%d -> %zu triangles, %zu vertices\n", S, R, m.tri_count(), m.vertex_count());
  return {m,
          {"source: procedural UV sphere, 32 segments x 13 rings (pole fans), 2*S*(R-1) = 768 triangles",
           "license: generated by sdfbench (no third-party data)"}};
}

Result make_teapot(const fs::path& src) {
  const fs::path file = src / "teapot" / "package" / "teapot.js";
  Mesh in = load_js_mesh(file);
  std::printf("teapot: source %zu vertices, %zu triangles\n", in.vertex_count(), in.tri_count());

  // --- 1. Split the 4x4 tessellation back into its 32 patches. -----------
  // Triangles are listed patch by patch: 4 strips of 4 cells.  A full cell
  // is the pair [a,b,c],[c,d,a] with corners a=s[k][j], b=s[k+1][j],
  // c=s[k+1][j+1], d=s[k][j+1] of the patch's 5x5 sample grid s (the pair is
  // recognised by its shared diagonal a-c).  A cell touching a pole lost one
  // (degenerate) triangle in the package, so it is a single triangle, either
  // [a,b,c] (d dropped) or [c,d,a] (b dropped); which one is decided below
  // by consistency of the grid and by the fit residual.
  struct Cell {
    bool quad;
    std::array<uint32_t, 4> v;  // quad: a,b,c,d; single: the 3 listed vertices
  };
  struct Patch {
    std::vector<Cell> cells;
    bool pole = false;
  };
  std::vector<Patch> patches;
  {
    const auto& I = in.idx;
    size_t cur = 0;
    while (cur < in.tri_count()) {
      Patch P;
      for (int c = 0; c < 16; ++c) {
        if (cur >= in.tri_count()) fail("teapot: triangle list ended inside a patch");
        uint32_t a = I[3 * cur], b = I[3 * cur + 1], cc = I[3 * cur + 2];
        if (cur + 1 < in.tri_count() && I[3 * cur + 3] == cc && I[3 * cur + 5] == a) {
          P.cells.push_back({true, {a, b, cc, I[3 * cur + 4]}});
          cur += 2;
        } else {
          P.cells.push_back({false, {a, b, cc, 0}});
          P.pole = true;
          cur += 1;
        }
      }
      patches.push_back(std::move(P));
    }
  }
  size_t npole = size_t(std::count_if(patches.begin(), patches.end(), [](const Patch& p) { return p.pole; }));
  std::printf("teapot: %zu patches recovered (%zu close at a pole, listed as 28 instead of 32 triangles)\n",
              patches.size(), npole);
  require(patches.size() == 32 && npole == 8, "teapot: expected 32 patches, 8 at poles");

  // --- 2. Least-squares fit of the 16 bicubic Bezier control points. -------
  // Samples are at u = k/4, v = j/4.  Grid slots no cell lists (the dropped
  // corner of the last pole cell) are left out of the fit (>= 24 samples
  // remain for 16 unknowns per coordinate).
  auto bern = [](int i, double t) {
    static const double binom[4] = {1, 3, 3, 1};
    return binom[i] * std::pow(t, i) * std::pow(1 - t, 3 - i);
  };
  std::array<std::array<double, 16>, 25> A{};  // A[(k,j)][(m,n)] = B_m(k/4) B_n(j/4)
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int mm = 0; mm < 4; ++mm)
        for (int n = 0; n < 4; ++n) A[k * 5 + j][mm * 4 + n] = bern(mm, k / 4.0) * bern(n, j / 4.0);
  // Solves the masked normal equations; returns control points and max residual.
  auto fit = [&](const std::array<int, 25>& slot, std::array<V3, 16>& ctrl_out) {
    double max_r = 0;
    std::array<std::array<double, 16>, 3> xs;
    for (int axis = 0; axis < 3; ++axis) {
      auto y = [&](int s) {
        V3 q = vert(in, uint32_t(slot[s]));
        return axis == 0 ? q.x : axis == 1 ? q.y : q.z;
      };
      double M[16][17];
      for (int r = 0; r < 16; ++r) {
        for (int c = 0; c <= 16; ++c) M[r][c] = 0;
        for (int s = 0; s < 25; ++s) {
          if (slot[s] < 0) continue;
          for (int c = 0; c < 16; ++c) M[r][c] += A[s][r] * A[s][c];
          M[r][16] += A[s][r] * y(s);
        }
      }
      for (int c = 0; c < 16; ++c) {  // Gauss-Jordan with partial pivoting
        int piv = c;
        for (int r = c + 1; r < 16; ++r)
          if (std::abs(M[r][c]) > std::abs(M[piv][c])) piv = r;
        for (int k = 0; k < 17; ++k) std::swap(M[c][k], M[piv][k]);
        if (std::abs(M[c][c]) < 1e-12) return 1e300;  // singular: not enough samples
        for (int r = 0; r < 16; ++r)
          if (r != c) {
            double f = M[r][c] / M[c][c];
            for (int k = c; k < 17; ++k) M[r][k] -= f * M[c][k];
          }
      }
      for (int r = 0; r < 16; ++r) xs[axis][r] = M[r][16] / M[r][r];
      for (int s = 0; s < 25; ++s) {
        if (slot[s] < 0) continue;
        double f = 0;
        for (int c = 0; c < 16; ++c) f += A[s][c] * xs[axis][c];
        max_r = std::max(max_r, std::abs(f - y(s)));
      }
    }
    for (int c = 0; c < 16; ++c) ctrl_out[c] = {xs[0][c], xs[1][c], xs[2][c]};
    return max_r;
  };
  std::vector<std::array<V3, 16>> ctrl(patches.size());
  double max_resid = 0;
  for (size_t pi = 0; pi < patches.size(); ++pi) {
    const Patch& P = patches[pi];
    std::vector<int> singles;
    for (int c = 0; c < 16; ++c)
      if (!P.cells[c].quad) singles.push_back(c);
    double best = 1e300;
    int n_best = 0;
    for (unsigned combo = 0; combo < (1u << singles.size()); ++combo) {
      std::array<int, 25> slot;
      slot.fill(-1);
      bool ok = true;
      auto set = [&](int k, int j, uint32_t v) {
        int& sl = slot[k * 5 + j];
        if (sl >= 0 && sl != int(v)) ok = false;
        sl = int(v);
      };
      for (int c = 0; c < 16 && ok; ++c) {
        const int k = c / 4, j = c % 4;
        const Cell& C = P.cells[c];
        std::array<int, 4> corner{-1, -1, -1, -1};  // a,b,c,d
        if (C.quad) corner = {int(C.v[0]), int(C.v[1]), int(C.v[2]), int(C.v[3])};
        else {
          size_t si = size_t(std::find(singles.begin(), singles.end(), c) - singles.begin());
          if (combo >> si & 1) corner = {int(C.v[2]), -1, int(C.v[0]), int(C.v[1])};  // listed [c,d,a]
          else corner = {int(C.v[0]), int(C.v[1]), int(C.v[2]), -1};                    // listed [a,b,c]
        }
        const int kk[4] = {k, k + 1, k + 1, k}, jj[4] = {j, j, j + 1, j + 1};
        for (int q = 0; q < 4; ++q)
          if (corner[q] >= 0) set(kk[q], jj[q], uint32_t(corner[q]));
      }
      if (!ok) continue;
      std::array<V3, 16> cp;
      double r = fit(slot, cp);
      if (r < 1e-5) ++n_best;
      if (r < best) {
        best = r;
        ctrl[pi] = cp;
      }
    }
    if (n_best != 1) fail("teapot: patch " + std::to_string(pi) + " has " + std::to_string(n_best) +
                          " consistent sample orderings (need exactly 1)");
    max_resid = std::max(max_resid, best);
  }
  Box sb = bbox(in);
  std::printf("teapot: bicubic fit max residual %.3g (source extent %.3f, data has 6 decimals)\n", max_resid,
              sb.max_extent());
  require(max_resid < 1e-5, "teapot: patch fit residual too large (sample ordering wrong?)");

  // --- 3. Tessellate every patch 8x8 (9x9 samples), same cell split. -------
  const int N = 8;
  Mesh m;
  for (size_t pi = 0; pi < patches.size(); ++pi) {
    const uint32_t base = uint32_t(m.vertex_count());
    for (int k = 0; k <= N; ++k)
      for (int j = 0; j <= N; ++j) {
        V3 q{0, 0, 0};
        for (int mm = 0; mm < 4; ++mm)
          for (int n = 0; n < 4; ++n) {
            double w = bern(mm, double(k) / N) * bern(n, double(j) / N);
            V3 c = ctrl[pi][mm * 4 + n];
            q = {q.x + w * c.x, q.y + w * c.y, q.z + w * c.z};
          }
        m.pos.insert(m.pos.end(), {float(q.x), float(q.y), float(q.z)});
      }
    auto at = [&](int k, int j) { return base + uint32_t(k * (N + 1) + j); };
    for (int k = 0; k < N; ++k)
      for (int j = 0; j < N; ++j) {
        uint32_t a = at(k, j), b = at(k + 1, j), c = at(k + 1, j + 1), d = at(k, j + 1);
        m.idx.insert(m.idx.end(), {a, b, c, c, d, a});
      }
  }
  // The source has exact zeros on the patches' symmetry plane; the fit leaves
  // ~1e-9 noise there.  Snap |c| < 1e-6 (source units) back to 0.
  for (auto& c : m.pos)
    if (std::abs(c) < 1e-6f) c = 0.0f;
  const size_t raw_tris = m.tri_count();
  // --- 4. Weld seams / poles and drop the collapsed pole triangles. -------
  const double eps = 1e-4;  // source units (extent ~17): far above fit noise, far below vertex spacing
  double min_sep = weld_tolerance(m, eps);
  std::vector<uint32_t> kept;
  std::vector<size_t> dropped_per_patch(patches.size(), 0);
  for (size_t t = 0; t < m.tri_count(); ++t) {
    uint32_t a = m.idx[3 * t], b = m.idx[3 * t + 1], c = m.idx[3 * t + 2];
    if (a == b || b == c || a == c) {
      ++dropped_per_patch[t / (2 * N * N)];
      continue;
    }
    kept.insert(kept.end(), {a, b, c});
  }
  m.idx = std::move(kept);
  compact(m);
  size_t dropped = raw_tris - m.tri_count();
  for (size_t pi = 0; pi < patches.size(); ++pi)
    require(dropped_per_patch[pi] == (patches[pi].pole ? size_t(N) : 0u), "teapot: unexpected degenerate triangles");
  std::printf("teapot: tessellated 32 patches 8x8 -> %zu triangles; welded (eps %.0e, closest unwelded pair %.4f) "
              "-> %zu vertices; dropped %zu pole triangles -> %zu\n",
              raw_tris, eps, min_sep, m.vertex_count(), dropped, m.tri_count());
  require(min_sep > 100 * eps, "teapot: weld tolerance not well separated");
  return {m,
          {"source: npm teapot@1.0.0 (Newell's Utah teapot, 32 bicubic patches stored as a 4x4 tessellation)",
           "license: Public Domain (package.json \"license\": \"Public Domain\"; README: \"(c) 1984 Matin [sic] "
           "Newell.  Public Domain.\")",
           "processing: patches recovered by least-squares bicubic fit, re-tessellated 8x8, welded, 64 pole "
           "triangles dropped: 32*128-64 = 4032",
           "note: not closed: 128 boundary edges (body rim and lid edge, 32 each; open ends of handle and spout, "
           "16 each); spout and handle are not stitched to the body (the handle's lower end touches it at one "
           "shared vertex: 1 non-manifold vertex)"}};
}

Result make_bunny(const fs::path& src) {
  Mesh in = load_js_mesh(src / "bunny" / "package" / "index.js");
  print_stats("bunny-in", stats(in));
  weld_exact(in);
  Mesh fine = subdivide_midpoint(in);
  std::printf("bunny: source %zu triangles, midpoint subdivision -> %zu triangles, %zu vertices\n", in.tri_count(),
              fine.tri_count(), fine.vertex_count());
  std::string log;
  Mesh m = simplify_exact(fine, 4968, log);
  std::printf("bunny: %s\n", log.c_str());
  Stats s0 = stats(m);
  size_t flips = flip_coplanar(m);
  Stats s1 = stats(m);
  std::printf("bunny: coplanar edge flips: %zu (zero-area triangles %zu -> %zu, min area %.3g -> %.3g)\n", flips,
              s0.degenerate, s1.degenerate, s0.min_area, s1.min_area);
  log += "; then " + std::to_string(flips) + " coplanar edge flips removed " + std::to_string(s0.degenerate) +
         " zero-area triangles";
  // The Stanford data is y-up with the bunny looking along -x; turn it 90
  // degrees about +y so that it faces +z (exact: a swap and a negation).
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    float x = m.pos[3 * i], z = m.pos[3 * i + 2];
    m.pos[3 * i] = z;
    m.pos[3 * i + 2] = -x;
  }
  return {m,
          {"source: npm bunny@1.0.1 (Stanford bunny, Stanford 3D Scanning Repository, 3674 triangles)",
           "license: package.json says \"Public Domain\" (Stanford asks that the repository be credited)",
           "processing: midpoint subdivision 3674 -> 14696; " + log,
           "orientation: rotated 90 degrees about +y (x,z) -> (z,-x) so the bunny faces +z",
           "note: closed and manifold (0 boundary edges): this low-resolution package version has no holes"}};
}

Result make_monkey(const fs::path& src) {
  Mesh in = load_gltf(src / "suzanne" / "suzanne-decoded.gltf", "Suzanne");
  std::printf("monkey: glTF %zu vertices, %zu triangles\n", in.vertex_count(), in.tri_count());
  weld_exact(in);
  print_stats("monkey-in", stats(in));
  std::string log;
  Mesh m = simplify_exact(in, 968, log);
  std::printf("monkey: %s\n", log.c_str());
  return {m,
          {"source: npm @gsimone/suzanne@0.0.12 (Blender's Suzanne, Draco-compressed GLB, 3936 triangles; "
           "decoded with npm draco3d@1.5.7)",
           "license: package.json says \"ISC\"",
           "processing: welded by position 7872 -> 2012 vertices; " + log,
           "note: not closed: 84 boundary edges (two open eye sockets in the head, 26 edges each; the two eyes are "
           "separate open caps, 16 edges each)"}};
}

}  // namespace

int main(int argc, char** argv) {
  try {
    fs::path sources, out;
    std::vector<std::string> only, check;
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) fail("missing value after " + a);
        return argv[++i];
      };
      if (a == "--sources") sources = next();
      else if (a == "--out") out = next();
      else if (a == "--only") only.push_back(next());
      else if (a == "--check") {
        while (i + 1 < argc) check.push_back(argv[++i]);
      } else if (a == "-h" || a == "--help") {
        std::puts("usage: make_meshes --sources DIR --out OUTDIR [--only bunny|teapot|monkey|sphere]...\n"
                  "       make_meshes --check FILE.obj...\n"
                  "DIR: output of scenes/tools/fetch_mesh_sources.sh");
        return 0;
      } else fail("unknown argument " + a);
    }
    if (!check.empty()) {
      for (auto& f : check) print_stats(fs::path(f).filename().string(), stats(read_obj(f)));
      return 0;
    }
    if (out.empty()) fail("--out is required (see --help)");
    const std::vector<std::pair<std::string, size_t>> targets = {
        {"bunny", 4968}, {"teapot", 4032}, {"monkey", 968}, {"sphere", 768}};
    fs::create_directories(out);
    for (auto& [name, count] : targets) {
      if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
      if (name != "sphere" && sources.empty()) fail("--sources is required for " + name);
      Result r = name == "bunny"    ? make_bunny(sources)
                 : name == "teapot" ? make_teapot(sources)
                 : name == "monkey" ? make_monkey(sources)
                                    : make_sphere();
      normalize(r.mesh);
      final_checks(name, r.mesh, count);
      write_obj(out / (name + ".obj"), r.mesh, name, r.notes);
      std::printf("wrote %s\n", (out / (name + ".obj")).string().c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_meshes: error: %s\n", e.what());
    return 1;
  }
}
