#include "scenes/json_field.h"

#include <cmath>

#include "scenes/error.h"

namespace sdfbench {

void JsonField::fail(const std::string& what) const {
  throw Error(file_ + ": " + (path_.empty() ? std::string("(top level)") : path_) + ": " + what);
}

JsonField JsonField::at(const char* key) const {
  if (!value_.is_object()) fail("expected an object");
  auto it = value_.find(key);
  const std::string child = path_.empty() ? std::string(key) : path_ + "." + key;
  if (it == value_.end()) JsonField(value_, child, file_).fail("missing required field");
  return JsonField(*it, child, file_);
}

JsonField JsonField::item(size_t index) const {
  if (!value_.is_array() || index >= value_.size()) fail("index " + std::to_string(index) + " out of range");
  return JsonField(value_[index], path_ + "[" + std::to_string(index) + "]", file_);
}

void JsonField::expect_object(std::initializer_list<const char*> allowed) const {
  if (!value_.is_object()) fail(std::string("expected an object, got ") + value_.type_name());
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    bool known = false;
    std::string list;
    for (const char* name : allowed) {
      known = known || it.key() == name;
      list += (list.empty() ? "" : ", ") + std::string(name);
    }
    if (!known) {
      const std::string child = path_.empty() ? it.key() : path_ + "." + it.key();
      JsonField(it.value(), child, file_).fail("unknown field (allowed here: " + list + ")");
    }
  }
}

void JsonField::expect_array() const {
  if (!value_.is_array()) fail(std::string("expected an array, got ") + value_.type_name());
}

float JsonField::number() const {
  if (!value_.is_number()) fail(std::string("expected a number, got ") + value_.type_name());
  const double v = value_.get<double>();
  if (!std::isfinite(v) || std::abs(v) > 1e30) fail("number out of range");
  return static_cast<float>(v);
}

float JsonField::number_in(float lo, float hi) const {
  const float v = number();
  if (v < lo || v > hi) fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
  return v;
}

float JsonField::positive() const {
  const float v = number();
  if (!(v > 0.0f)) fail("must be > 0, got " + std::to_string(v));
  return v;
}

uint32_t JsonField::integer_in(uint32_t lo, uint32_t hi) const {
  if (!value_.is_number_integer()) fail(std::string("expected an integer, got ") + value_.type_name());
  const long long v = value_.get<long long>();
  if (v < static_cast<long long>(lo) || v > static_cast<long long>(hi))
    fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
  return static_cast<uint32_t>(v);
}

std::string JsonField::string() const {
  if (!value_.is_string()) fail(std::string("expected a string, got ") + value_.type_name());
  return value_.get<std::string>();
}

glm::vec3 JsonField::vec3() const {
  if (!value_.is_array() || value_.size() != 3) fail("expected an array of 3 numbers");
  return {item(0).number(), item(1).number(), item(2).number()};
}

glm::vec3 JsonField::color() const {
  const glm::vec3 c = vec3();
  if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) fail("colour components must be >= 0");
  return c;
}

glm::quat JsonField::rotation() const {
  expect_object({"axis", "degrees"});
  const glm::vec3 axis = at("axis").vec3();
  if (glm::length(axis) < 1e-12f) at("axis").fail("rotation axis must not be zero");
  return glm::angleAxis(glm::radians(at("degrees").number()), glm::normalize(axis));
}

}  // namespace sdfbench
