#include "scenes/mesh_file_check.h"

#include <charconv>
#include <cctype>
#include <cmath>
#include <cstring>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

constexpr size_t kMaxHeaderBytes = 64 << 10;
constexpr uint64_t kMaxGltfBufferBytes = 1ull << 30;
constexpr uint64_t kMaxGltfItems = 1u << 20;  // buffers, views, accessors, meshes, nodes, ...

std::string_view as_text(std::span<const std::byte> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

// The character at i, or NUL past the end; a line ends at \n, \r or \r\n (as assimp reads them).
char text_at(std::string_view text, size_t i) { return i < text.size() ? text[i] : '\0'; }

bool parse_count(std::string_view token, uint64_t& value) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t end = i;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != '\r') ++end;
    if (end > i) out.push_back(line.substr(i, end - i));
    i = end;
  }
  return out;
}

// Bytes of one PLY scalar type, 0 if unknown.
uint64_t ply_type_bytes(std::string_view type) {
  for (const char* t : {"char", "uchar", "int8", "uint8"})
    if (type == t) return 1;
  for (const char* t : {"short", "ushort", "int16", "uint16"})
    if (type == t) return 2;
  for (const char* t : {"int", "uint", "int32", "uint32", "float", "float32"})
    if (type == t) return 4;
  for (const char* t : {"double", "float64"})
    if (type == t) return 8;
  return 0;
}

}  // namespace

namespace {

struct PlyProperty {
  uint64_t count_bytes = 0;  // a list's item count (0: a scalar)
  uint64_t item_bytes = 0;   // the scalar's, or each list item's
  bool count_signed = false;
};
struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

// Element and property names as PLY writers write them: assimp reads a name that starts with a
// digit differently (as a count), so the header would mean one thing here and another there.
bool ply_name(std::string_view name) {
  if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  return true;
}

bool ply_signed(std::string_view type) { return type == "char" || type == "short" || type.rfind("int", 0) == 0; }

// The largest item count a list's count type can say (and that a reader should loop for).
uint64_t ply_count_limit(const PlyProperty& p) {
  if (p.count_bytes == 1) return p.count_signed ? 127 : 255;
  if (p.count_bytes == 2) return p.count_signed ? 32767 : 65535;
  return 1u << 16;  // wider counts: no polygon of a mesh file has more corners
}

// Every element of an ASCII body, one line each as assimp reads them: numbers where numbers go,
// list counts within their type, as many tokens as the header declares (assimp loops on a list
// count it cannot read), and enough lines.
void check_ply_ascii_body(std::string_view body, const std::vector<PlyElement>& elements, const std::string& where) {
  size_t pos = 0;
  for (const PlyElement& e : elements) {
    for (uint64_t n = 0; n < e.count; ++n) {
      auto fail = [&](const std::string& what) {
        throw Error(where + ": element '" + printable(e.name) + "' " + std::to_string(n) + ": " + what);
      };
      std::vector<std::string_view> t;
      while (t.empty()) {  // blank lines are skipped
        if (pos >= body.size()) fail("the file ends (truncated?)");
        size_t end = body.find_first_of("\r\n", pos);
        if (end == std::string_view::npos) end = body.size();
        t = tokens(body.substr(pos, end - pos));
        pos = end + (text_at(body, end) == '\r' && text_at(body, end + 1) == '\n' ? 2 : 1);
      }
      size_t k = 0;
      auto number = [&]() {
        if (k == t.size()) fail("fewer values on its line than the header declares");
        double value = 0.0;
        const std::string_view token = t[k++];
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
          fail("'" + printable(std::string(token.substr(0, 40))) + "' is not a finite number");
      };
      for (const PlyProperty& p : e.properties) {
        uint64_t items = 1;
        if (p.count_bytes) {
          if (k == t.size()) fail("fewer values on its line than the header declares");
          if (!parse_count(t[k], items) || items > ply_count_limit(p))
            fail("list count '" + printable(std::string(t[k].substr(0, 40))) + "' is not 0.." +
                 std::to_string(ply_count_limit(p)));
          ++k;
        }
        for (uint64_t i = 0; i < items; ++i) number();
      }
      if (k != t.size()) fail("more values on its line than the header declares");
    }
  }
}

uint64_t read_uint(const std::byte* p, uint64_t bytes, bool big_endian) {
  uint64_t v = 0;
  for (uint64_t i = 0; i < bytes; ++i) v |= uint64_t(std::to_integer<uint8_t>(p[big_endian ? i : bytes - 1 - i])) << (8 * (bytes - 1 - i));
  return v;
}

// The same for a binary body: every list count within its type and the bytes it needs present.
void check_ply_binary_body(std::span<const std::byte> body, bool big_endian, const std::vector<PlyElement>& elements,
                           const std::string& where) {
  uint64_t pos = 0;
  for (const PlyElement& e : elements) {
    for (uint64_t n = 0; n < e.count; ++n) {
      for (const PlyProperty& p : e.properties) {
        uint64_t items = 1;
        if (p.count_bytes) {
          if (body.size() - pos < p.count_bytes) throw Error(where + ": element '" + printable(e.name) + "' " + std::to_string(n) + ": the file ends (truncated?)");
          items = read_uint(body.data() + pos, p.count_bytes, big_endian);
          pos += p.count_bytes;
          const uint64_t sign_bit = uint64_t{1} << (8 * p.count_bytes - 1);
          if ((p.count_signed && (items & sign_bit)) || items > ply_count_limit(p))
            throw Error(where + ": element '" + printable(e.name) + "' " + std::to_string(n) + ": list count " +
                        std::to_string(items) + " is not 0.." + std::to_string(ply_count_limit(p)));
        }
        if ((body.size() - pos) / p.item_bytes < items)
          throw Error(where + ": element '" + printable(e.name) + "' " + std::to_string(n) + ": the file ends (truncated?)");
        pos += items * p.item_bytes;
      }
    }
  }
}

}  // namespace

void check_ply(std::span<const std::byte> file, const std::string& where) {
  const std::string_view text = as_text(file.first(std::min(file.size(), kMaxHeaderBytes)));
  size_t line_number = 0, pos = 0;
  auto fail = [&](const std::string& what) {
    throw Error(where + " header line " + std::to_string(line_number) + ": " + what);
  };
  std::string format;
  bool ended = false;
  std::vector<PlyElement> elements;
  while (!ended) {
    const size_t end = text.find_first_of("\r\n", pos);
    ++line_number;
    if (end == std::string_view::npos)
      fail("no end_header within the first " + describe_bytes(kMaxHeaderBytes) + " (not a PLY file, or a truncated one)");
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + (text_at(text, end) == '\r' && text_at(text, end + 1) == '\n' ? 2 : 1);
    if (line.find('\0') != std::string_view::npos) fail("a NUL byte in the header");
    const std::vector<std::string_view> t = tokens(line);
    if (line_number == 1) {
      if (t.size() != 1 || t[0] != "ply") fail("expected 'ply' (not a PLY file)");
      continue;
    }
    // Debian 13's assimp (5.4) reads a comment whose text starts with a digit as a count
    // ("comment 4294967295 x", with or without indentation: a 100 GB allocation), Debian 12's skips
    // it: refused, so that the file means one thing everywhere.
    if (t.size() > 1 && t[0] == "comment" && std::isdigit(static_cast<unsigned char>(t[1][0])))
      fail("a comment that starts with a number ('" + printable(std::string(line.substr(0, 40))) +
           "'): assimp 5.4 reads it as a count; put a word first");
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() != 3 || (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
        fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      format = std::string(t[1]);
    } else if (t[0] == "element") {
      PlyElement e;
      if (t.size() != 3 || !parse_count(t[2], e.count)) fail("expected 'element NAME COUNT'");
      e.name = std::string(t[1]);
      if (!ply_name(e.name)) fail("element name '" + printable(e.name) + "' is not a name (letters, digits, _ and -)");
      const uint64_t limit = e.name == "face" ? kMaxMeshFileTriangles : kMaxMeshFileVertices;
      if (e.count > limit)
        fail("element '" + printable(e.name) + "' declares " + std::to_string(e.count) + " items (the limit is " +
             std::to_string(limit) + ")");
      elements.push_back(std::move(e));
    } else if (t[0] == "property") {
      if (elements.empty()) fail("a property before any element");
      PlyProperty p;
      if (t.size() == 5 && t[1] == "list") {
        p.count_bytes = ply_type_bytes(t[2]);
        p.count_signed = ply_signed(t[2]);
        p.item_bytes = ply_type_bytes(t[3]);
        if (p.count_bytes == 0 || p.item_bytes == 0) fail("unknown list types '" + printable(line) + "'");
      } else if (t.size() == 3) {
        p.item_bytes = ply_type_bytes(t[1]);
        if (p.item_bytes == 0) fail("unknown property type '" + printable(std::string(t[1])) + "'");
      } else {
        fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
      }
      if (!ply_name(t.back())) fail("property name '" + printable(std::string(t.back())) + "' is not a name (letters, digits, _ and -)");
      if (elements.back().properties.size() == 64) fail("more than 64 properties in one element");
      elements.back().properties.push_back(p);
    } else if (t[0] == "end_header") {
      ended = true;
    }  // other lines (exporters' notes without "comment") are skipped, as assimp skips them
  }
  if (format.empty()) fail("no format line before end_header");
  if (format == "ascii") check_ply_ascii_body(as_text(file.subspan(pos)), elements, where);
  else check_ply_binary_body(file.subspan(pos), format == "binary_big_endian", elements, where);
}

void check_off_header(std::span<const std::byte> file, const std::string& where) {
  const std::string_view text = as_text(file.first(std::min(file.size(), kMaxHeaderBytes)));
  std::vector<std::string_view> words;
  size_t pos = 0, line_number = 0;
  // The keyword and the three counts, over as many lines as they take (comments skipped).
  while (words.size() < 4) {
    const size_t end = text.find_first_of("\r\n", pos);
    ++line_number;
    const std::string_view line = text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
    if (line.find('\0') != std::string_view::npos)
      throw Error(where + " line " + std::to_string(line_number) + ": a NUL byte (binary OFF is not supported)");
    if (line.empty() || line[0] != '#')
      for (std::string_view w : tokens(line)) words.push_back(w);
    if (end == std::string_view::npos) break;
    pos = end + (text_at(text, end) == '\r' && text_at(text, end + 1) == '\n' ? 2 : 1);
  }
  if (words.empty() || words[0].size() < 3 || words[0].substr(words[0].size() - 3) != "OFF")
    throw Error(where + ": expected the keyword OFF first (not an OFF file)");
  if (words[0] != "OFF" && words[0] != "COFF" && words[0] != "NOFF" && words[0] != "CNOFF")
    throw Error(where + ": '" + printable(std::string(words[0])) + "' files are not supported (OFF, COFF, NOFF, CNOFF are)");
  uint64_t vertices = 0, faces = 0;
  if (words.size() < 3 || !parse_count(words[1], vertices) || !parse_count(words[2], faces))
    throw Error(where + ": expected the vertex and face counts after OFF");
  if (vertices > kMaxMeshFileVertices || faces > kMaxMeshFileTriangles)
    throw Error(where + ": declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                " faces (the limits are " + std::to_string(kMaxMeshFileVertices) + " and " +
                std::to_string(kMaxMeshFileTriangles) + ")");
  // A vertex line holds at least "0 0 0\n", a face line "3 0 0 0\n".
  if (vertices * 6 + faces * 8 > file.size())
    throw Error(where + ": declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                " faces, more than its " + describe_bytes(file.size()) + " can hold (truncated?)");
}

namespace {

// The glTF JSON's checks: every index in range, every byte range inside its container.
class GltfCheck {
 public:
  GltfCheck(const nlohmann::json& root, uint64_t glb_bin_bytes, const std::string& where)
      : root_(root), glb_bin_bytes_(glb_bin_bytes), where_(where) {}

  std::vector<GltfPrimitive> run() {
    if (!root_.is_object()) fail("", "the JSON is not an object");
    const nlohmann::json* asset = find(root_, "asset");
    const nlohmann::json* version = asset && asset->is_object() ? find(*asset, "version") : nullptr;
    if (!version || !version->is_string() || version->get<std::string>().rfind("2.", 0) != 0)
      fail("asset.version", "only glTF 2.0 files are read");
    const size_t buffers = check_buffers();
    const size_t views = check_views(buffers);
    const size_t accessors = check_accessors(views);
    const size_t meshes = check_meshes(accessors);
    const size_t nodes = check_nodes(meshes);
    check_scenes(nodes);
    check_images(views);
    return std::move(primitives_);
  }

 private:
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw Error(where_ + (field.empty() ? "" : ": " + field) + ": " + what);
  }
  static std::string join(const std::string& field, const char* key) { return field.empty() ? key : field + "." + key; }
  static const nlohmann::json* find(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }
  // root[key] as an array of objects (empty if absent).
  const nlohmann::json& array(const char* key) const {
    static const nlohmann::json empty = nlohmann::json::array();
    const nlohmann::json* a = find(root_, key);
    if (!a) return empty;
    if (!a->is_array()) fail(key, "expected an array");
    if (a->size() > kMaxGltfItems) fail(key, "more than " + std::to_string(kMaxGltfItems) + " entries");
    for (size_t i = 0; i < a->size(); ++i)
      if (!(*a)[i].is_object()) fail(std::string(key) + "[" + std::to_string(i) + "]", "expected an object");
    return *a;
  }
  // object[key] as an unsigned integer (`fallback` if absent and optional).
  uint64_t integer(const nlohmann::json& object, const std::string& field, const char* key, bool required,
                   uint64_t fallback = 0) const {
    const nlohmann::json* v = find(object, key);
    if (!v) {
      if (required) fail(field, "missing \"" + std::string(key) + "\"");
      return fallback;
    }
    if (!v->is_number_unsigned()) fail(join(field, key), "expected a non-negative integer");
    return v->get<uint64_t>();
  }
  uint64_t index(const nlohmann::json& object, const std::string& field, const char* key, size_t count,
                 const char* of) const {
    const uint64_t i = integer(object, field, key, true);
    if (i >= count)
      fail(join(field, key), std::to_string(i) + " is out of range (" + std::to_string(count) + " " + of + ")");
    return i;
  }
  // A relative path inside the file's folder, or a data: URI.
  void check_uri(const nlohmann::json& object, const std::string& field) const {
    const nlohmann::json* uri = find(object, "uri");
    if (!uri) return;
    if (!uri->is_string()) fail(field + ".uri", "expected a string");
    const std::string u = uri->get<std::string>();
    if (u.rfind("data:", 0) == 0) return;
    if (u.empty() || u[0] == '/' || u.find('\\') != std::string::npos || u.find(':') != std::string::npos ||
        u == ".." || u.rfind("../", 0) == 0 || u.find("/../") != std::string::npos ||
        (u.size() >= 3 && u.compare(u.size() - 3, 3, "/..") == 0) || u.find('%') != std::string::npos)
      fail(field + ".uri", "'" + printable(u) + "' is not a plain relative path inside the glTF file's folder");
  }

  size_t check_buffers() {
    const nlohmann::json& buffers = array("buffers");
    for (size_t i = 0; i < buffers.size(); ++i) {
      const std::string field = "buffers[" + std::to_string(i) + "]";
      const uint64_t bytes = integer(buffers[i], field, "byteLength", true);
      if (bytes > kMaxGltfBufferBytes)
        fail(field + ".byteLength", std::to_string(bytes) + " is over the limit of " + describe_bytes(kMaxGltfBufferBytes));
      check_uri(buffers[i], field);
      if (!find(buffers[i], "uri")) {
        if (i != 0 || glb_bin_bytes_ == kNoBin) fail(field, "no uri, and not the binary chunk of a .glb");
        if (bytes > glb_bin_bytes_)
          fail(field + ".byteLength", std::to_string(bytes) + " is more than the .glb's binary chunk of " +
                                          std::to_string(glb_bin_bytes_) + " bytes");
      } else if (const std::string u = buffers[i]["uri"].get<std::string>(); u.rfind("data:", 0) == 0) {
        const size_t comma = u.find(',');
        const uint64_t decoded = comma == std::string::npos ? 0 : (u.size() - comma - 1) / 4 * 3;
        if (decoded + 2 < bytes)
          fail(field + ".byteLength", std::to_string(bytes) + " is more than its data: URI holds (" +
                                          std::to_string(decoded) + " bytes)");
      }
      buffer_bytes_.push_back(bytes);
    }
    return buffers.size();
  }

  size_t check_views(size_t buffers) {
    const nlohmann::json& views = array("bufferViews");
    for (size_t i = 0; i < views.size(); ++i) {
      const std::string field = "bufferViews[" + std::to_string(i) + "]";
      const uint64_t buffer = index(views[i], field, "buffer", buffers, "buffers");
      const uint64_t offset = integer(views[i], field, "byteOffset", false);
      const uint64_t bytes = integer(views[i], field, "byteLength", true);
      const uint64_t stride = integer(views[i], field, "byteStride", false);
      if (stride != 0 && (stride < 4 || stride > 252)) fail(field + ".byteStride", "must be 4 to 252");
      if (offset > buffer_bytes_[buffer] || bytes > buffer_bytes_[buffer] - offset)
        fail(field, "bytes " + std::to_string(offset) + " + " + std::to_string(bytes) + " pass the end of buffers[" +
                        std::to_string(buffer) + "] (" + std::to_string(buffer_bytes_[buffer]) + " bytes)");
      view_bytes_.push_back(bytes);
      view_stride_.push_back(stride);
    }
    return views.size();
  }

  size_t check_accessors(size_t views) {
    const nlohmann::json& accessors = array("accessors");
    for (size_t i = 0; i < accessors.size(); ++i) {
      const nlohmann::json& a = accessors[i];
      const std::string field = "accessors[" + std::to_string(i) + "]";
      const uint64_t count = integer(a, field, "count", true);
      if (count == 0 || count > kMaxMeshFileVertices)
        fail(field + ".count", std::to_string(count) + " is outside 1.." + std::to_string(kMaxMeshFileVertices));
      const uint64_t component = integer(a, field, "componentType", true);
      uint64_t component_bytes = 0;
      if (component == 5120 || component == 5121) component_bytes = 1;
      if (component == 5122 || component == 5123) component_bytes = 2;
      if (component == 5125 || component == 5126) component_bytes = 4;
      if (component_bytes == 0) fail(field + ".componentType", std::to_string(component) + " is not a glTF component type");
      const nlohmann::json* type = find(a, "type");
      uint64_t components = 0;
      if (type && type->is_string()) {
        const std::string t = type->get<std::string>();
        const std::pair<const char*, uint64_t> known[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                          {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
        for (const auto& [name, n] : known)
          if (t == name) components = n;
      }
      if (components == 0) fail(field + ".type", "expected SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
      if (find(a, "sparse")) fail(field + ".sparse", "sparse accessors are not read");
      accessor_count_.push_back(count);
      if (!find(a, "bufferView")) continue;  // all zeros
      const uint64_t view = index(a, field, "bufferView", views, "bufferViews");
      const uint64_t offset = integer(a, field, "byteOffset", false);
      const uint64_t element = component_bytes * components;
      const uint64_t stride = view_stride_[view] ? view_stride_[view] : element;
      const uint64_t end = offset + stride * (count - 1) + element;  // < 2^32 + 2^31: no overflow
      if (end > view_bytes_[view])
        fail(field, std::to_string(count) + " elements from byte " + std::to_string(offset) + " need " +
                        std::to_string(end) + " bytes, more than bufferViews[" + std::to_string(view) + "] holds (" +
                        std::to_string(view_bytes_[view]) + ")");
    }
    return accessors.size();
  }

  size_t check_meshes(size_t accessors) {
    const nlohmann::json& meshes = array("meshes");
    for (size_t i = 0; i < meshes.size(); ++i) {
      const std::string field = "meshes[" + std::to_string(i) + "]";
      const nlohmann::json* primitives = find(meshes[i], "primitives");
      if (!primitives || !primitives->is_array() || primitives->empty() || primitives->size() > kMaxGltfItems)
        fail(field + ".primitives", "expected a non-empty array");
      for (size_t p = 0; p < primitives->size(); ++p) {
        const nlohmann::json& primitive = (*primitives)[p];
        const std::string pfield = field + ".primitives[" + std::to_string(p) + "]";
        if (!primitive.is_object()) fail(pfield, "expected an object");
        const nlohmann::json* attributes = find(primitive, "attributes");
        if (!attributes || !attributes->is_object()) fail(pfield + ".attributes", "expected an object");
        for (auto it = attributes->begin(); it != attributes->end(); ++it)
          index(*attributes, pfield + ".attributes", it.key().c_str(), accessors, "accessors");
        if (!find(*attributes, "POSITION")) fail(pfield + ".attributes", "no POSITION");
        uint64_t corners = accessor_count_[index(*attributes, pfield + ".attributes", "POSITION", accessors, "accessors")];
        if (find(primitive, "indices")) corners = accessor_count_[index(primitive, pfield, "indices", accessors, "accessors")];
        const uint64_t mode = integer(primitive, pfield, "mode", false, 4);
        if (mode > 6) fail(pfield + ".mode", "expected 0 to 6");
        primitives_.push_back({pfield, mode == 4 ? static_cast<int64_t>(corners / 3) : -1});
      }
    }
    return meshes.size();
  }

  size_t check_nodes(size_t meshes) const {
    const nlohmann::json& nodes = array("nodes");
    const size_t cameras = array("cameras").size();
    std::vector<int64_t> parent(nodes.size(), -1);
    for (size_t i = 0; i < nodes.size(); ++i) {
      const std::string field = "nodes[" + std::to_string(i) + "]";
      if (find(nodes[i], "mesh")) index(nodes[i], field, "mesh", meshes, "meshes");
      if (find(nodes[i], "camera")) index(nodes[i], field, "camera", cameras, "cameras");
      const nlohmann::json* children = find(nodes[i], "children");
      if (!children) continue;
      if (!children->is_array()) fail(field + ".children", "expected an array");
      for (size_t c = 0; c < children->size(); ++c) {
        const std::string cfield = field + ".children[" + std::to_string(c) + "]";
        if (!(*children)[c].is_number_unsigned()) fail(cfield, "expected a node index");
        const uint64_t child = (*children)[c].get<uint64_t>();
        if (child >= nodes.size()) fail(cfield, std::to_string(child) + " is out of range (" + std::to_string(nodes.size()) + " nodes)");
        if (parent[child] != -1)
          fail(cfield, "node " + std::to_string(child) + " already has a parent (nodes[" + std::to_string(parent[child]) +
                           "]): the node graph must be a forest");
        parent[child] = static_cast<int64_t>(i);
      }
    }
    // With one parent per node, a cycle is a chain of parents that comes back to its start.
    for (size_t i = 0; i < nodes.size(); ++i) {
      int64_t n = parent[i];
      for (size_t steps = 0; n != -1; n = parent[static_cast<size_t>(n)], ++steps)
        if (static_cast<size_t>(n) == i || steps > nodes.size())
          fail("nodes[" + std::to_string(i) + "]", "is its own ancestor (a cycle in the node graph)");
    }
    return nodes.size();
  }

  void check_scenes(size_t nodes) const {
    const nlohmann::json& scenes = array("scenes");
    for (size_t i = 0; i < scenes.size(); ++i) {
      const std::string field = "scenes[" + std::to_string(i) + "]";
      const nlohmann::json* roots = find(scenes[i], "nodes");
      if (!roots) continue;
      if (!roots->is_array()) fail(field + ".nodes", "expected an array");
      for (size_t r = 0; r < roots->size(); ++r)
        if (!(*roots)[r].is_number_unsigned() || (*roots)[r].get<uint64_t>() >= nodes)
          fail(field + ".nodes[" + std::to_string(r) + "]", "expected a node index below " + std::to_string(nodes));
    }
    if (find(root_, "scene")) index(root_, "", "scene", scenes.size(), "scenes");
  }

  void check_images(size_t views) const {
    const nlohmann::json& images = array("images");
    for (size_t i = 0; i < images.size(); ++i) {
      const std::string field = "images[" + std::to_string(i) + "]";
      check_uri(images[i], field);
      if (find(images[i], "bufferView")) index(images[i], field, "bufferView", views, "bufferViews");
    }
  }

 public:
  static constexpr uint64_t kNoBin = ~uint64_t{0};

 private:
  const nlohmann::json& root_;
  uint64_t glb_bin_bytes_;
  std::string where_;
  std::vector<uint64_t> buffer_bytes_, view_bytes_, view_stride_, accessor_count_;
  std::vector<GltfPrimitive> primitives_;
};

uint32_t read_u32(std::span<const std::byte> bytes, size_t offset) {
  uint32_t v = 0;
  std::memcpy(&v, bytes.data() + offset, 4);  // little-endian hosts only (Debian amd64/arm64)
  return v;
}

}  // namespace

std::string_view gltf_json_text(std::span<const std::byte> file, bool binary, const std::string& where,
                                uint64_t* bin_bytes_out) {
  std::string_view json_text = as_text(file);
  uint64_t bin_bytes = GltfCheck::kNoBin;
  if (binary) {
    // 12-byte header (magic, version, length), then chunks (length, type, data), JSON first.
    if (file.size() < 20 || read_u32(file, 0) != 0x46546C67u) throw Error(where + ": not a .glb file (no glTF magic)");
    if (read_u32(file, 4) != 2) throw Error(where + ": .glb version " + std::to_string(read_u32(file, 4)) + " (only 2 is read)");
    if (read_u32(file, 8) > file.size())
      throw Error(where + ": the header says " + std::to_string(read_u32(file, 8)) + " bytes, the file has " +
                  std::to_string(file.size()) + " (truncated?)");
    const uint64_t json_bytes = read_u32(file, 12);
    if (read_u32(file, 16) != 0x4E4F534Au || json_bytes > file.size() - 20)
      throw Error(where + ": the first chunk is not a JSON chunk inside the file");
    json_text = as_text(file.subspan(20, json_bytes));
    const uint64_t bin_at = 20 + ((json_bytes + 3) & ~uint64_t{3});
    if (bin_at + 8 <= file.size() && read_u32(file, bin_at + 4) == 0x004E4942u) {
      bin_bytes = read_u32(file, bin_at);
      if (bin_bytes > file.size() - bin_at - 8)
        throw Error(where + ": the binary chunk claims " + std::to_string(bin_bytes) + " bytes, more than the file holds (truncated?)");
    }
  }
  if (bin_bytes_out) *bin_bytes_out = bin_bytes;
  return json_text;
}

std::vector<GltfPrimitive> check_gltf(std::span<const std::byte> file, bool binary, const std::string& where) {
  uint64_t bin_bytes = 0;
  const std::string_view json_text = gltf_json_text(file, binary, where, &bin_bytes);
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(where + ": not valid JSON: " + printable(e.what()));
  }
  return GltfCheck(root, bin_bytes, where).run();
}

}  // namespace sdfbench
