#include "scenes/json_field.h"

#include <cmath>
#include <cstdio>

#include "util/error.h"
#include "util/input_file.h"
#include "util/number_text.h"

namespace sdfbench {
namespace {

// A path deeper than a message line should carry (a hostile file nests thousands of levels):
// its start and end, which say where, and how much was left out.
std::string short_path(const std::string& path) {
  constexpr size_t kKeep = 60;
  if (path.size() <= 2 * kKeep + 40) return path;
  return path.substr(0, kKeep) + "...(" + std::to_string(path.size() - 2 * kKeep) + " characters)..." +
         path.substr(path.size() - kKeep);
}

}  // namespace

// Keys and names quoted in the message may hold any character: escaped, so that a NUL does not
// end the message nor a newline split it.
void JsonField::fail(const std::string& what) const {
  throw Error(printable(file_ + ": " + (path_.empty() ? std::string("(top level)") : short_path(path_)) + ": " + what));
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
  if (!std::isfinite(v) || std::abs(v) > 1e30) fail("number out of range (magnitude at most 1e30), got " + six_digits(v));
  return static_cast<float>(v);
}

float JsonField::number_in(float lo, float hi) const {
  const float v = number();
  if (v < lo || v > hi) fail("must be in [" + six_digits(lo) + ", " + six_digits(hi) + "], got " + six_digits(v));
  return v;
}

float JsonField::positive() const {
  const float v = number();
  if (!(v > 0.0f)) fail("must be > 0, got " + six_digits(v));
  return v;
}

uint32_t JsonField::integer_in(uint32_t lo, uint32_t hi) const {
  if (!value_.is_number_integer()) fail(std::string("expected an integer, got ") + value_.type_name());
  // Unsigned and signed JSON integers are read as what they are (18446744073709551615 is not -1).
  const bool in_range = value_.is_number_unsigned() ? value_.get<uint64_t>() >= lo && value_.get<uint64_t>() <= hi
                                                    : value_.get<int64_t>() >= lo && value_.get<int64_t>() <= hi;
  if (!in_range)
    fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + value_.dump());
  return value_.get<uint32_t>();
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
