#include "scenes/scene_loader.h"

#include <algorithm>
#include <map>

#include <glm/gtc/quaternion.hpp>

#include "scenes/implicit_parser.h"
#include "scenes/json_field.h"
#include "scenes/mesh_file.h"
#include "scenes/named_mesh.h"
#include "scenes/scene_texture.h"
#include "util/error.h"
#include "util/image_codec.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

constexpr uint32_t kMaxRenderSide = 16384;  // render.width and render.height
constexpr uint64_t kMaxSceneFileBytes = 32ull << 20;  // a scene of 100 000 instances is ~10 MB

// Looks up a name declared in a section ("meshes", "materials") and says what exists if not.
uint32_t lookup(const JsonField& field, const std::map<std::string, uint32_t>& names, const char* section) {
  const std::string name = field.string();
  auto it = names.find(name);
  if (it != names.end()) return it->second;
  std::string known;
  for (const auto& [n, i] : names) known += (known.empty() ? "" : ", ") + n;
  field.fail("unknown " + std::string(section) + " '" + name + "' (declared: " + (known.empty() ? "none" : known) + ")");
}

// An image file of a `texture` material, decoded into Scene::texels (scene_texture.h); a failure
// is an error of the field. The codecs read the bytes from memory: the file itself was opened by
// read_input_bytes (a FIFO or /dev/zero is refused, not read for ever).
Texture load_texture(const JsonField& field, const std::filesystem::path& path, Scene& scene) {
  try {
    return add_texture(read_input_bytes(path, "image", kMaxImageFileBytes), path, "image '" + path.string() + "'", scene);
  } catch (const Error& e) {
    field.fail(e.what());
  }
}

Material parse_material(const JsonField& f, const std::string& name, const std::filesystem::path& base, Scene& scene) {
  f.expect_object({"albedo", "checker", "texture", "reflectance", "transmission", "ior"});
  Material m;
  m.name = name;
  if (f.has("albedo")) m.albedo = f.at("albedo").color();
  if (f.has("checker")) {
    const JsonField c = f.at("checker");
    c.expect_object({"size", "albedo"});
    m.checker_size = c.at("size").positive();
    if (c.has("albedo")) m.checker_albedo = c.at("albedo").color();
  }
  if (f.has("texture")) {
    const JsonField t = f.at("texture");
    t.expect_object({"file", "size"});
    std::filesystem::path path = t.at("file").string();
    if (path.is_relative()) path = base / path;
    if (t.has("size")) m.texture_size = t.at("size").positive();
    for (m.texture = 0; m.texture < scene.textures.size(); ++m.texture)  // one copy per image file
      if (scene.textures[m.texture].source == path) break;
    if (m.texture == scene.textures.size()) scene.textures.push_back(load_texture(t.at("file"), path, scene));
  }
  if (f.has("reflectance")) m.reflectance = f.at("reflectance").number_in(0.0f, 1.0f);
  if (f.has("transmission")) m.transmission = f.at("transmission").number_in(0.0f, 1.0f);
  if (f.has("ior")) m.ior = f.at("ior").number_in(1.0f, 4.0f);
  if (m.reflectance + m.transmission > 1.0f) f.fail("reflectance + transmission must not exceed 1");
  return m;
}

Transform parse_transform(const JsonField& f) {
  Transform t;
  if (f.has("translate")) t.translation = f.at("translate").vec3();
  if (f.has("scale")) t.scale = f.at("scale").number_in(1e-6f, 1e6f);
  if (f.has("rotate")) t.rotation = f.at("rotate").rotation();
  return t;
}

Light parse_light(const JsonField& f) {
  Light light;
  const std::string type = f.at("type").string();
  if (type == "directional") {
    f.expect_object({"type", "direction", "color"});
    const glm::vec3 d = f.at("direction").vec3();
    if (glm::length(d) < 1e-12f) f.at("direction").fail("direction must not be zero");
    light.kind = Light::Kind::Directional;
    light.direction = glm::normalize(d);
  } else if (type == "point") {
    f.expect_object({"type", "position", "color"});
    light.kind = Light::Kind::Point;
    light.position = f.at("position").vec3();
  } else {
    f.at("type").fail("unknown light type '" + type + "' (expected directional or point)");
  }
  if (f.has("color")) light.color = f.at("color").color();
  return light;
}

Camera parse_camera(const JsonField& f) {
  f.expect_object({"position", "look_at", "up", "fov_y"});
  Camera c;
  c.position = f.at("position").vec3();
  c.look_at = f.at("look_at").vec3();
  if (f.has("up")) c.up = f.at("up").vec3();
  if (f.has("fov_y")) c.fov_y_degrees = f.at("fov_y").number_in(1.0f, 179.0f);
  const glm::vec3 forward = c.look_at - c.position;
  if (glm::length(forward) < 1e-9f) f.at("look_at").fail("camera look_at equals its position");
  if (glm::length(c.up) < 1e-12f || glm::length(glm::cross(forward, c.up)) < 1e-6f * glm::length(forward) * glm::length(c.up)) {
    if (!f.has("up"))  // the default up (0, 1, 0): say what to give, not that a field is missing
      f.fail("the view from position to look_at is vertical, parallel to the default up [0, 1, 0]; give camera.up");
    f.at("up").fail("camera up is zero or parallel to the viewing direction");
  }
  return c;
}

// nlohmann's messages start with "[json.exception.parse_error.101] ": the rest is for users.
std::string json_message(const nlohmann::ordered_json::exception& e) {
  const std::string what = e.what();
  const size_t end = what.find("] ");
  return what.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? what.substr(end + 2) : what;
}

// nlohmann's DOM parser, turning every parse failure into an Error with the file and position:
// a syntax error's message has its line and column, a number overflow (1e400) only its text.
struct DomParser : nlohmann::detail::json_sax_dom_parser<nlohmann::ordered_json> {
  DomParser(nlohmann::ordered_json& doc, const std::string& text, const std::string& file)
      : json_sax_dom_parser(doc), text(text), file(file) {}
  template <class Exception>
  [[noreturn]] bool parse_error(size_t position, const std::string& token, const Exception& e) {
    if (e.id / 100 == 1) throw Error(file + ": malformed JSON: " + json_message(e));  // parse_error.1xx
    // `position` is just past the token: report where it starts (line and column from 1).
    const size_t start = std::min(text.size(), position - std::min(position, token.size()));
    const size_t line_start = text.rfind('\n', start == 0 ? 0 : start - 1);
    const size_t column = line_start == std::string::npos ? start + 1 : start - line_start;
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(start), '\n');
    throw Error(file + ": malformed JSON at line " + std::to_string(line) + ", column " + std::to_string(column) + ": " +
                json_message(e));
  }
  const std::string& text;
  const std::string& file;
};

Scene build_scene(const nlohmann::ordered_json& doc, const std::filesystem::path& origin) {
  const std::string file = origin.string();
  const JsonField root(doc, "", file);
  root.expect_object(
      {"meshes", "materials", "instances", "implicits", "lights", "camera", "sky", "floor", "ambient", "render"});

  Scene scene;
  scene.name = file;
  const std::filesystem::path base = origin.parent_path();

  std::map<std::string, uint32_t> mesh_ids;
  const nlohmann::ordered_json no_meshes = nlohmann::ordered_json::object();
  const JsonField meshes = root.has("meshes") ? root.at("meshes") : JsonField(no_meshes, "meshes", file);
  if (!meshes.raw().is_object()) meshes.fail("expected an object of named meshes, e.g. {\"bunny\": {\"builtin\": \"bunny\"}}");
  for (auto it = meshes.raw().begin(); it != meshes.raw().end(); ++it) {
    const JsonField m(it.value(), "meshes." + it.key(), file);
    if (!m.raw().is_object()) m.fail("expected an object with \"builtin\" or \"file\"");
    m.expect_object({"builtin", "file"});
    std::filesystem::path path;
    std::string builtin;
    if (m.has("builtin") == m.has("file")) m.fail("give exactly one of \"builtin\" and \"file\"");
    if (m.has("builtin")) {
      builtin = m.at("builtin").string();
      if (!is_mesh_name(builtin)) m.at("builtin").fail("unknown built-in mesh '" + builtin + "' (built in: " + mesh_names_text() + ")");
    } else {
      path = m.at("file").string();
      if (path.is_relative()) path = base / path;
    }
    try {
      Mesh mesh = builtin.empty() ? load_mesh_file(path, it.key()) : load_named_mesh(builtin);
      mesh.name = it.key();
      scene.meshes.push_back(std::move(mesh));
    } catch (const Error& e) {
      m.fail(e.what());
    }
    mesh_ids[it.key()] = static_cast<uint32_t>(scene.meshes.size() - 1);
  }

  std::map<std::string, uint32_t> material_ids;
  if (root.has("materials")) {
    const JsonField materials = root.at("materials");
    if (!materials.raw().is_object()) materials.fail("expected an object of named materials");
    for (auto it = materials.raw().begin(); it != materials.raw().end(); ++it) {
      const JsonField material(it.value(), "materials." + it.key(), file);
      scene.materials.push_back(parse_material(material, it.key(), base, scene));
      material_ids[it.key()] = static_cast<uint32_t>(scene.materials.size() - 1);
    }
  }
  if (scene.materials.empty()) {  // a scene without materials gets one grey default
    scene.materials.push_back(Material{.name = "default"});
    material_ids["default"] = 0;
  }

  const nlohmann::ordered_json none = nlohmann::ordered_json::array();
  const JsonField instances = root.has("instances") ? root.at("instances") : JsonField(none, "instances", file);
  instances.expect_array();
  for (size_t i = 0; i < instances.size(); ++i) {
    const JsonField f = instances.item(i);
    f.expect_object({"mesh", "material", "translate", "rotate", "scale"});
    Instance instance;
    instance.mesh = lookup(f.at("mesh"), mesh_ids, "mesh");
    instance.material = f.has("material") ? lookup(f.at("material"), material_ids, "material") : 0;
    instance.transform = parse_transform(f);
    scene.instances.push_back(instance);
  }
  const JsonField implicits = root.has("implicits") ? root.at("implicits") : JsonField(none, "implicits", file);
  implicits.expect_array();
  for (size_t i = 0; i < implicits.size(); ++i) {
    const JsonField f = implicits.item(i);
    f.expect_object({"shape", "material", "translate", "rotate", "scale"});
    ImplicitObject object;
    object.nodes = parse_implicit_shape(f.at("shape"));
    object.material = f.has("material") ? lookup(f.at("material"), material_ids, "material") : 0;
    object.transform = parse_transform(f);
    scene.implicits.push_back(std::move(object));
  }
  if (scene.instances.empty() && scene.implicits.empty())
    (root.has("instances") ? instances : implicits).fail("a scene needs at least one instance or implicit object");

  if (root.has("lights")) {
    const JsonField lights = root.at("lights");
    lights.expect_array();
    for (size_t i = 0; i < lights.size(); ++i) scene.lights.push_back(parse_light(lights.item(i)));
  }
  scene.camera = parse_camera(root.at("camera"));
  if (root.has("sky")) {
    const JsonField sky = root.at("sky");
    sky.expect_object({"zenith", "horizon"});
    if (sky.has("zenith")) scene.sky.zenith = sky.at("zenith").color();
    if (sky.has("horizon")) scene.sky.horizon = sky.at("horizon").color();
  }
  if (root.has("floor")) {
    const JsonField floor = root.at("floor");
    floor.expect_object({"height", "material"});
    scene.floor.enabled = true;
    if (floor.has("height")) scene.floor.height = floor.at("height").number();
    if (floor.has("material")) scene.floor.material = lookup(floor.at("material"), material_ids, "material");
  }
  if (root.has("ambient")) scene.ambient = root.at("ambient").number_in(0.0f, 10.0f);
  if (root.has("render")) {
    const JsonField render = root.at("render");
    render.expect_object({"width", "height", "max_depth"});
    if (render.has("width")) scene.render.width = render.at("width").integer_in(1, kMaxRenderSide);
    if (render.has("height")) scene.render.height = render.at("height").integer_in(1, kMaxRenderSide);
    if (render.has("max_depth")) scene.render.max_depth = render.at("max_depth").integer_in(1, 16);
  }
  check_coordinates(scene);
  return scene;
}

}  // namespace

Scene parse_scene_json(const std::string& text, const std::filesystem::path& origin) {
  const std::string file = origin.string();
  try {
    nlohmann::ordered_json doc;  // declaration order: the first material is the default
    DomParser parser(doc, text, file);
    nlohmann::ordered_json::sax_parse(text, &parser);
    return build_scene(doc, origin);
  } catch (const nlohmann::ordered_json::exception& e) {  // a check JsonField does not make yet
    throw Error(file + ": " + json_message(e));
  }
}

Scene load_scene_file(const std::filesystem::path& path) {
  return parse_scene_json(read_input_file(path, "scene file", kMaxSceneFileBytes), path);
}

}  // namespace sdfbench
