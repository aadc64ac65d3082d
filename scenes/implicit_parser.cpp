#include "scenes/implicit_parser.h"

#include <string>

#include "util/error.h"


namespace sdfbench {
namespace {

constexpr const char* kTypes = "sphere, box, ellipsoid, capsule, torus, plane, union, intersection or subtraction";
// Every operation has at least 2 children, so a tree of kImplicitMaxNodes nodes nests at most
// this deep: deeper JSON is refused before recursing into it (bounded stack and memory).
constexpr uint32_t kMaxNesting = kImplicitMaxNodes / 2;

// Appends the node's subtree in postfix order. n-ary operations fold left: (((c0 c1 op) c2 op) ...),
// so subtraction takes every later child away from the first.
void flatten(const JsonField& f, uint32_t nesting, std::vector<ImplicitNode>& out) {
  if (nesting > kMaxNesting)
    f.fail("operations nested more than " + std::to_string(kMaxNesting) + " deep (an implicit shape holds at most " +
           std::to_string(kImplicitMaxNodes) + " nodes)");
  if (out.size() >= kImplicitMaxNodes)
    f.fail("too many nodes: an implicit shape holds at most " + std::to_string(kImplicitMaxNodes));
  if (!f.raw().is_object()) f.fail(std::string("expected a shape object with a \"type\", got ") + f.raw().type_name());
  const std::string type = f.at("type").string();
  ImplicitNode n;
  if (type == "union" || type == "intersection" || type == "subtraction") {
    f.expect_object({"type", "children"});
    const JsonField children = f.at("children");
    children.expect_array();
    if (children.size() < 2) children.fail("an operation needs at least 2 children");
    n.kind = type == "union" ? ImplicitKind::Union
                             : (type == "intersection" ? ImplicitKind::Intersection : ImplicitKind::Subtraction);
    flatten(children.item(0), nesting + 1, out);
    for (size_t i = 1; i < children.size(); ++i) {
      flatten(children.item(i), nesting + 1, out);
      if (out.size() >= kImplicitMaxNodes)
        f.fail("too many nodes: an implicit shape holds at most " + std::to_string(kImplicitMaxNodes));
      out.push_back(n);
    }
    return;
  }
  if (type == "sphere") {
    f.expect_object({"type", "radius", "translate", "rotate"});
    n.kind = ImplicitKind::Sphere;
    n.a.x = f.at("radius").positive();
  } else if (type == "box") {
    f.expect_object({"type", "half_extents", "rounding", "translate", "rotate"});
    n.kind = ImplicitKind::Box;
    const glm::vec3 h = f.at("half_extents").vec3();
    if (!(h.x > 0.0f && h.y > 0.0f && h.z > 0.0f)) f.at("half_extents").fail("half extents must be > 0");
    n.a = glm::vec4(h, 0.0f);
    if (f.has("rounding")) n.a.w = f.at("rounding").number_in(0.0f, glm::min(h.x, glm::min(h.y, h.z)));
  } else if (type == "ellipsoid") {
    f.expect_object({"type", "radii", "translate", "rotate"});
    n.kind = ImplicitKind::Ellipsoid;
    const glm::vec3 r = f.at("radii").vec3();
    if (!(r.x > 0.0f && r.y > 0.0f && r.z > 0.0f)) f.at("radii").fail("radii must be > 0");
    n.a = glm::vec4(r, 0.0f);
  } else if (type == "capsule") {
    f.expect_object({"type", "a", "b", "radius", "translate", "rotate"});
    n.kind = ImplicitKind::Capsule;
    n.a = glm::vec4(f.at("a").vec3(), f.at("radius").positive());
    n.b = glm::vec4(f.at("b").vec3(), 0.0f);
  } else if (type == "torus") {
    f.expect_object({"type", "major", "minor", "translate", "rotate"});
    n.kind = ImplicitKind::Torus;
    n.a = glm::vec4(f.at("major").positive(), f.at("minor").positive(), 0.0f, 0.0f);
  } else if (type == "plane") {
    f.expect_object({"type", "normal", "offset", "translate", "rotate"});
    n.kind = ImplicitKind::Plane;
    const glm::vec3 normal = f.at("normal").vec3();
    if (glm::length(normal) < 1e-12f) f.at("normal").fail("plane normal must not be zero");
    n.a = glm::vec4(glm::normalize(normal), f.has("offset") ? f.at("offset").number() : 0.0f);
  } else {
    f.at("type").fail("unknown shape type '" + type + "' (expected " + kTypes + ")");
  }
  if (f.has("translate")) n.placement.translation = f.at("translate").vec3();
  if (f.has("rotate")) n.placement.rotation = f.at("rotate").rotation();
  out.push_back(n);
}

}  // namespace

std::vector<ImplicitNode> parse_implicit_shape(const JsonField& shape) {
  std::vector<ImplicitNode> nodes;
  flatten(shape, 0, nodes);
  try {
    implicit_bounds(nodes);  // stack depth, boundedness
  } catch (const Error& e) {
    shape.fail(e.what());
  }
  return nodes;
}

}  // namespace sdfbench
