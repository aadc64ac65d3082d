#include "renderers/backend_params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "util/error.h"
#include "util/number_text.h"

namespace sdfbench {
namespace {

std::string join(const std::vector<std::string>& words, const std::string& last) {
  std::string text;
  for (size_t i = 0; i < words.size(); ++i)
    text += (i == 0 ? "" : i + 1 == words.size() ? " " + last + " " : ", ") + words[i];
  return text;
}

bool is_choice(const ParamSpec& spec, const std::string& value) {
  return std::find(spec.choices.begin(), spec.choices.end(), value) != spec.choices.end();
}

std::string quoted(const std::string& value) {
  return "'" + (value.size() > 40 ? value.substr(0, 40) + "..." : value) + "'";
}

}  // namespace

std::string flag_of(const ParamSpec& spec) {
  std::string flag = "--" + spec.name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string describe_values(const ParamSpec& spec) {
  const std::string words = spec.choices.empty() ? "" : join(spec.choices, "or") + " or ";
  switch (spec.kind) {
    case ParamKind::Integer:
      return words + "an integer in [" + std::to_string(static_cast<int64_t>(spec.lo)) + ", " +
             std::to_string(static_cast<int64_t>(spec.hi)) + "]";
    case ParamKind::Real:
      return words + "a number in " + (spec.lo_open ? "(" : "[") + six_digits(spec.lo) + ", " + six_digits(spec.hi) + "]";
    case ParamKind::Choice: return join(spec.choices, "or");
    case ParamKind::Flag: return "0 (off) or 1 (on)";
  }
  return "?";
}

namespace {

// The range part of a declaration, on a number already read: the one range rule of a parameter.
bool in_range(const ParamSpec& spec, double v) {
  return v >= spec.lo && v <= spec.hi && !(spec.lo_open && v <= spec.lo);
}

}  // namespace

std::optional<TypedParam> parse_param(const ParamSpec& spec, const std::string& value, std::string& why) {
  why.clear();
  if (is_choice(spec, value)) return TypedParam{value, value};
  const std::string expected = "expected " + describe_values(spec) + ", got " + quoted(value);
  if (spec.kind == ParamKind::Choice) return why = expected, std::nullopt;
  if (spec.kind == ParamKind::Flag) {
    if (value == "0" || value == "1") return TypedParam{value, value == "1"};
    return why = expected, std::nullopt;
  }
  double v = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (value.empty() || ec != std::errc() || end != value.data() + value.size() || !std::isfinite(v))
    return why = expected, std::nullopt;
  if (spec.kind == ParamKind::Integer) {
    if (v != std::floor(v) || !in_range(spec, v)) return why = expected, std::nullopt;
    const int64_t i = static_cast<int64_t>(v);
    return TypedParam{std::to_string(i), i};
  }
  // A real is used as it is recorded: rounded to the CSV's 6 digits, then checked (so a value
  // below the range's resolution is refused, not measured as another one).
  const std::string canonical = six_digits(v);
  const double used = std::strtod(canonical.c_str(), nullptr);
  if (!in_range(spec, used)) return why = expected, std::nullopt;
  return TypedParam{canonical, used};
}

bool param_accepts(const ParamSpec& spec, const TypedParam& value) {
  if (const auto* word = std::get_if<std::string>(&value.value)) return is_choice(spec, *word);
  switch (spec.kind) {
    case ParamKind::Integer:
      return std::holds_alternative<int64_t>(value.value) && in_range(spec, static_cast<double>(std::get<int64_t>(value.value)));
    case ParamKind::Real: return std::holds_alternative<double>(value.value) && in_range(spec, std::get<double>(value.value));
    case ParamKind::Flag: return std::holds_alternative<bool>(value.value);
    case ParamKind::Choice: return false;  // a choice is a word
  }
  return false;
}

std::string canonical_param_value(const ParamSpec& spec, const std::string& value, std::string& why) {
  const std::optional<TypedParam> typed = parse_param(spec, value, why);
  return typed ? typed->text : "";
}

ParamSpec with_default(ParamSpec spec, const std::string& default_value) {
  spec.default_value = default_value;
  return spec;
}

ParamSpec with_choices(ParamSpec spec, const std::vector<std::string>& choices, const std::string& default_value) {
  spec.choices = choices;
  spec.default_value = default_value;
  return spec;
}

const ParamSpec& find_spec(const std::vector<ParamSpec>& specs, const std::string& name) {
  for (const ParamSpec& spec : specs)
    if (spec.name == name) return spec;
  throw InternalError("no parameter '" + name + "' is declared");
}

namespace {

[[noreturn]] void undeclared(const std::string& name) {
  throw InternalError("parameter '" + name + "' read by a backend that does not declare it in its BackendInfo::params");
}

const char* kind_name(const ParamValue& value) {
  switch (value.index()) {
    case 0: return "an integer";
    case 1: return "a number";
    case 2: return "a word";
    default: return "a flag";
  }
}

template <typename T>
T typed_as(const std::string& name, const ParamValue& value, const char* wanted) {
  if (const T* v = std::get_if<T>(&value)) return *v;
  throw InternalError("parameter '" + name + "' read as " + wanted + ", but its value is " + kind_name(value));
}

}  // namespace

const std::string& BackendParams::text(const std::string& name) const {
  const auto it = texts_.find(name);
  if (it == texts_.end()) undeclared(name);
  return it->second;
}

std::optional<TypedParam> BackendParams::typed(const std::string& name) const {
  const auto it = typed_.find(name);
  if (it == typed_.end()) return std::nullopt;
  return TypedParam{text(name), it->second};
}

const ParamValue& BackendParams::value(const std::string& name) const {
  const auto it = typed_.find(name);
  if (it != typed_.end()) return it->second;
  if (!has(name)) undeclared(name);
  throw InternalError("parameter '" + name + "' ('" + text(name) +
                        "') read before it was resolved against its declaration (resolve_params)");
}

int64_t BackendParams::integer(const std::string& name) const { return typed_as<int64_t>(name, value(name), "an integer"); }

double BackendParams::real(const std::string& name) const { return typed_as<double>(name, value(name), "a number"); }

bool BackendParams::flag(const std::string& name) const { return typed_as<bool>(name, value(name), "a flag"); }

bool BackendParams::is_word(const std::string& name) const { return std::holds_alternative<std::string>(value(name)); }

const ParamSpec& max_structure_mb_param() {
  static const ParamSpec spec{"max_structure_mb", ParamKind::Integer, std::to_string(kDefaultMaxStructureBytes >> 20),
                              "memory cap of each structure a backend builds (an SDF's cell lists, octrees or sampled field; "
                              "bvh's flat tree): a build that would pass it stops with an error",
                              "SDF structures", {}, 1, 16384};  // the group the build command takes its flags from
  return spec;
}

}  // namespace sdfbench
