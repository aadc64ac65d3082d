#include <charconv>
#include <istream>
#include <streambuf>
#include <cmath>
#include <limits>
#include <sstream>
#include <string_view>

#include <tiny_obj_loader.h>

#include "scenes/mesh.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

// What one OBJ may hold, checked before tinyobjloader allocates anything for it: 8 Mi vertices
// and triangles keep its parse under ~1.5 GB (the thesis meshes have ~5000 triangles).
constexpr uint64_t kMaxObjBytes = 512ull << 20;
constexpr uint64_t kMaxObjVertices = 1ull << 23;
constexpr uint64_t kMaxObjTriangles = 1ull << 23;
// tinyobjloader's ear clipping is quadratic in a face's corners (one face of 16 000 takes 3 s,
// of 400 000 minutes). A 256-gon takes under a millisecond, and a file of 8 Mi triangles in
// 256-gons parses in about twice the time of the same triangles as triangles.
constexpr uint64_t kMaxFaceVertices = 256;

// tinyobjloader reads a stream; this one reads the text in place (ParseFromString copies it).
class TextStreamBuf : public std::streambuf {
 public:
  explicit TextStreamBuf(const std::string& text) {
    char* begin = const_cast<char*>(text.data());  // only read: std::streambuf never writes its get area
    setg(begin, begin, begin + text.size());
  }
};

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// The next blank-separated token of `rest` (empty at the end); no allocation, as one line of
// a hostile file may hold millions of them.
std::string_view next_token(std::string_view& rest) {
  size_t i = 0;
  while (i < rest.size() && is_blank(rest[i])) ++i;
  size_t end = i;
  while (end < rest.size() && !is_blank(rest[end])) ++end;
  const std::string_view token = rest.substr(i, end - i);
  rest.remove_prefix(end);
  return token;
}

// std::from_chars of the whole token (a leading '+' allowed, as tinyobjloader allows it).
template <class T>
bool parse_whole(std::string_view token, T& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

// tinyobjloader reads `v nan 0 0` and `v abc 0 0` as 0 and wraps the face index 4294967299 to
// 3, silently. This pass checks every `v` coordinate and `f` vertex index as written (the parts
// of the file the mesh uses) and the counts, so that tinyobjloader only sees what it reads right.
void check_obj_text(std::string_view text, const std::string& where) {
  uint64_t vertices = 0, triangles = 0;
  int64_t max_index = 0;  // the largest positive vertex index, and its line (forward references)
  size_t max_index_line = 0, line_number = 0;
  auto fail = [&](const std::string& what) { throw Error(where + " line " + std::to_string(line_number) + ": " + what); };
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find_first_of("\r\n", pos);  // tinyobjloader ends lines at \n, \r\n and \r
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    ++line_number;
    if (line.find('\0') != std::string_view::npos) fail("a NUL byte: not a text file");  // read_input_file refuses it too
    size_t first = 0;
    while (first < line.size() && is_blank(line[first])) ++first;
    if (line.size() < first + 2 || !is_blank(line[first + 1])) continue;  // only "v ..." and "f ..." lines
    std::string_view rest = line.substr(first + 1);
    if (line[first] == 'v') {
      for (int k = 0; k < 3; ++k) {
        const std::string_view t = next_token(rest);
        double value = 0.0;
        if (t.empty()) fail("a vertex needs 3 coordinates, got " + std::to_string(k));
        if (!parse_whole(t, value)) fail("vertex coordinate '" + std::string(t) + "' is not a number");
        if (!std::isfinite(value) || std::abs(value) > std::numeric_limits<float>::max())
          fail("vertex coordinate '" + std::string(t) + "' is not a finite 32-bit float");
      }
      if (++vertices > kMaxObjVertices)
        fail("more than " + std::to_string(kMaxObjVertices) + " vertices (the limit for an OBJ)");
    } else if (line[first] == 'f') {
      uint64_t corners = 0;
      for (std::string_view corner = next_token(rest); !corner.empty(); corner = next_token(rest), ++corners) {
        if (corners == kMaxFaceVertices)
          fail("a face has more than " + std::to_string(kMaxFaceVertices) + " vertices (the limit for an OBJ face)");
        const std::string_view v = corner.substr(0, corner.find('/'));  // "v", "v/vt", "v//vn", "v/vt/vn"
        int64_t index = 0;
        if (!parse_whole(v, index) || index == 0)
          fail("face vertex '" + std::string(corner) + "' is not a vertex index (1, 2, ... or -1, -2, ...)");
        if (index < 0 && static_cast<uint64_t>(-(index + 1)) >= vertices)
          fail("face vertex index " + std::to_string(index) + " refers before the first vertex (" +
               std::to_string(vertices) + " vertices so far)");
        if (index > max_index) {
          max_index = index;
          max_index_line = line_number;
        }
      }
      if (corners < 3) fail("a face needs at least 3 vertices, got " + std::to_string(corners));
      triangles += corners - 2;  // a polygon of n vertices becomes n - 2 triangles
      if (triangles > kMaxObjTriangles)
        fail("more than " + std::to_string(kMaxObjTriangles) + " triangles (the limit for an OBJ)");
    }
  }
  if (static_cast<uint64_t>(max_index) > vertices) {
    line_number = max_index_line;
    fail("face uses vertex index " + std::to_string(max_index) + " but the file has " + std::to_string(vertices) +
         " vertices");
  }
}

}  // namespace

Mesh parse_obj(const std::string& text, const std::filesystem::path& source, const std::string& name) {
  const std::string where = "mesh '" + printable(name) + "': OBJ '" + printable(source.string()) + "'";
  check_obj_text(text, where);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  TextStreamBuf buffer(text);
  std::istream stream(&buffer);
  // No material reader: materials come from the scene descriptor, never from files the OBJ names.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &stream, nullptr, /*triangulate=*/true,
                        /*default_vcols_fallback=*/false))
    throw Error(where + ": cannot read it: " + error);

  Mesh mesh;
  mesh.name = name;
  mesh.source = source;
  const size_t vertex_count = attrib.vertices.size() / 3;
  mesh.positions.resize(vertex_count);
  for (size_t i = 0; i < vertex_count; ++i) {
    const glm::vec3 p(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(where + ": vertex " + std::to_string(i + 1) + " is not a finite number");
    mesh.positions[i] = p;
  }
  for (const tinyobj::shape_t& shape : shapes) {
    const auto& indices = shape.mesh.indices;
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const unsigned fv = shape.mesh.num_face_vertices[f];
      if (fv != 3)  // triangulation can leave lines/points out of faces; reject anything else
        throw Error(where + ": face " + std::to_string(f + 1) + " of shape '" + shape.name + "' has " +
                    std::to_string(fv) + " vertices after triangulation");
      glm::uvec3 tri;
      for (unsigned k = 0; k < 3; ++k) {
        const int index = indices[offset + k].vertex_index;
        if (index < 0 || static_cast<size_t>(index) >= vertex_count) {
          std::ostringstream msg;
          msg << where << ": face " << (f + 1) << " of shape '" << shape.name << "' uses vertex index " << (index + 1)
              << " but the file has " << vertex_count << " vertices";
          throw Error(msg.str());
        }
        tri[k] = static_cast<unsigned>(index);
      }
      offset += fv;
      mesh.triangles.push_back(tri);
    }
  }
  if (mesh.triangles.empty()) throw Error(where + " contains no triangles");
  finish_mesh(mesh);
  return mesh;
}

Mesh load_obj(const std::filesystem::path& path, const std::string& name) {
  return parse_obj(read_input_file(path, "OBJ", kMaxObjBytes), path, name);
}

}  // namespace sdfbench
