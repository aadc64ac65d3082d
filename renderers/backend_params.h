#pragma once
// Parameters a backend owns (issue 36), as Mitsuba's plugins own their properties: each is
// declared once (name, kind, default, range or choices, help) next to the code that reads it, and
// the commands' flags, the sweep's axes, the CSV's columns and their read-back are made from those
// declarations (renderers/backend_registry.h). A backend reads only the parameters it declares,
// through the typed accessors of BackendParams.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sdfbench {

enum class ParamKind {
  Integer,  // an integer in [lo, hi] (or one of `choices`)
  Real,     // a finite real in [lo, hi] ((lo, hi] when lo_open), or one of `choices` ("auto")
  Choice,   // one of `choices`
  Flag,     // 0 or 1: a switch on the command line (--cell-bound), 0,1 as a sweep axis
};

struct ParamSpec {
  std::string name;  // CSV column; the flag is --name with '-' for '_'
  ParamKind kind = ParamKind::Integer;
  std::string default_value;
  std::string help;
  std::string group;                 // the help section ("SDF structures", "SDF tracing", ...)
  std::vector<std::string> choices;  // Choice: the values; Integer/Real: words accepted besides numbers
  double lo = 0, hi = 0;
  bool lo_open = false;
  // Recorded only where another parameter has a value (cells_per_extent: where mesh_cell is 0);
  // elsewhere it changes nothing, and its column stays empty.
  std::string only_when_param, only_when_value;
};

std::string flag_of(const ParamSpec& spec);  // "--hash-cell"
// The value as it is used and recorded (one spelling per value: "064" -> "64", "0.50" -> "0.5",
// reals to 6 significant digits as the CSV writes numbers), or an empty string with `why` set
// (without the flag's name: "expected an integer in [4, 1024], got '2'").
std::string canonical_param_value(const ParamSpec& spec, const std::string& value, std::string& why);
// The spec's range or choices in words ("an integer in [1, 1000000]", "exact, thesis or field").
std::string describe_values(const ParamSpec& spec);
// `spec` with another default or a narrower set of choices (a backend's own view of a shared parameter).
ParamSpec with_default(ParamSpec spec, const std::string& default_value);
ParamSpec with_choices(ParamSpec spec, const std::vector<std::string>& choices, const std::string& default_value);
// The spec named `name` in `specs`; throws Error("internal: ...") when there is none.
const ParamSpec& find_spec(const std::vector<ParamSpec>& specs, const std::string& name);

// Parameter values by name. On the command side: the values given (validated against the
// catalogue's specs by the caller); on a backend's side: every parameter it owns, resolved
// (given or its default), read through the typed accessors, which refuse a parameter the backend
// does not own (it would silently read nothing).
class BackendParams {
 public:
  void set(const std::string& name, const std::string& canonical_value) { values_[name] = canonical_value; }
  void erase(const std::string& name) { values_.erase(name); }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  const std::map<std::string, std::string>& values() const { return values_; }

  const std::string& text(const std::string& name) const;
  int64_t integer(const std::string& name) const;
  double real(const std::string& name) const;  // a Real given as a number (not one of its words)
  bool flag(const std::string& name) const;

  bool operator==(const BackendParams&) const = default;

 private:
  std::map<std::string, std::string> values_;
};

}  // namespace sdfbench
