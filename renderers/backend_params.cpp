#include "renderers/backend_params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "util/error.h"

namespace sdfbench {
namespace {

std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

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
      return words + "a number in " + (spec.lo_open ? "(" : "[") + short_number(spec.lo) + ", " + short_number(spec.hi) + "]";
    case ParamKind::Choice: return join(spec.choices, "or");
    case ParamKind::Flag: return "0 (off) or 1 (on)";
  }
  return "?";
}

std::string canonical_param_value(const ParamSpec& spec, const std::string& value, std::string& why) {
  why.clear();
  if (is_choice(spec, value)) return value;
  const std::string expected = "expected " + describe_values(spec) + ", got " + quoted(value);
  if (spec.kind == ParamKind::Choice) return why = expected, "";
  if (spec.kind == ParamKind::Flag) {
    if (value == "0" || value == "1") return value;
    return why = expected, "";
  }
  double v = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (value.empty() || ec != std::errc() || end != value.data() + value.size() || !std::isfinite(v)) return why = expected, "";
  if (spec.kind == ParamKind::Integer) {
    if (v != std::floor(v) || v < spec.lo || v > spec.hi) return why = expected, "";
    return std::to_string(static_cast<int64_t>(v));
  }
  // A real is used as it is recorded: rounded to the CSV's 6 digits, then checked again (so a
  // value below the range's resolution is refused, not measured as another one).
  const std::string canonical = short_number(v);
  const double used = std::strtod(canonical.c_str(), nullptr);
  if (used < spec.lo || used > spec.hi || (spec.lo_open && used <= spec.lo)) return why = expected, "";
  return canonical;
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
  throw Error("internal: no parameter '" + name + "' is declared");
}

const std::string& BackendParams::text(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end())
    throw Error("internal: parameter '" + name + "' read by a backend that does not declare it (renderers/backend_registry.h)");
  return it->second;
}

int64_t BackendParams::integer(const std::string& name) const { return std::stoll(text(name)); }

double BackendParams::real(const std::string& name) const { return std::strtod(text(name).c_str(), nullptr); }

bool BackendParams::flag(const std::string& name) const { return text(name) == "1"; }

}  // namespace sdfbench
