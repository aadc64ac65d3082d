#pragma once
// A JSON value together with where it came from, so every rejection names file and field.
// ordered_json keeps objects in declaration order (mesh and material indices follow the file).
#include <initializer_list>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

namespace sdfbench {

class JsonField {
 public:
  JsonField(const nlohmann::ordered_json& value, std::string path, std::string file)
      : value_(value), path_(std::move(path)), file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& what) const;

  const nlohmann::ordered_json& raw() const { return value_; }
  const std::string& path() const { return path_; }
  bool has(const char* key) const { return value_.is_object() && value_.contains(key); }
  JsonField at(const char* key) const;  // required member
  JsonField item(size_t index) const;
  size_t size() const { return value_.size(); }

  // Fails on any member outside `allowed` (catches typos such as "postion").
  void expect_object(std::initializer_list<const char*> allowed) const;
  void expect_array() const;
  float number() const;
  float number_in(float lo, float hi) const;  // inclusive range
  float positive() const;
  uint32_t integer_in(uint32_t lo, uint32_t hi) const;
  std::string string() const;
  glm::vec3 vec3() const;
  glm::vec3 color() const;  // vec3 with every component >= 0
  glm::quat rotation() const;  // {axis: non-zero vec3, degrees: number}

 private:
  const nlohmann::ordered_json& value_;
  std::string path_;
  std::string file_;
};

}  // namespace sdfbench
