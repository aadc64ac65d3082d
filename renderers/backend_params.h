#pragma once
// Parameters a backend owns (issue 36), as Mitsuba's plugins own their properties: each is
// declared once (name, kind, default, range or choices, help) next to the code that reads it, and
// the commands' flags, the sweep's axes, the CSV's columns and their read-back are made from those
// declarations (renderers/backend_registry.h). A backend reads only the parameters it declares,
// through the typed accessors of BackendParams.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
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

// --max-structure-mb, the memory cap of a structure a backend builds (an SDF's lists, octrees or
// sampled field; bvh's flat tree): one declaration, which every backend that builds one owns.
inline constexpr uint64_t kDefaultMaxStructureBytes = uint64_t(2048) << 20;
const ParamSpec& max_structure_mb_param();

// A value as its declaration makes it: Integer -> int64_t, Real -> double (the value the canonical
// text reads back as), Flag -> bool, and a word (a Choice, or a word an Integer or Real accepts:
// --global-voxel auto) -> std::string.
using ParamValue = std::variant<int64_t, double, std::string, bool>;
struct TypedParam {
  std::string text;  // canonical: what the CSV records and configuration keys compare
  ParamValue value;  // what a backend reads
  bool operator==(const TypedParam&) const = default;
};

// The one parser of a parameter's value: the text checked against `spec` and made its typed value
// and canonical text (one spelling per value: "064" -> "64", "0.50" -> "0.5", reals to 6
// significant digits as the CSV writes numbers), or nullopt with `why` set (without the flag's
// name: "expected an integer in [4, 1024], got '2'").
std::optional<TypedParam> parse_param(const ParamSpec& spec, const std::string& value, std::string& why);
// Whether a value parsed against another declaration of the same parameter (the catalogue's, whose
// choices are every backend's) is one `spec` takes (its own choices and range); no parsing.
bool param_accepts(const ParamSpec& spec, const TypedParam& value);
// parse_param's canonical text, or an empty string with `why` set.
std::string canonical_param_value(const ParamSpec& spec, const std::string& value, std::string& why);
// The spec's range or choices in words ("an integer in [1, 1000000]", "exact, thesis or field").
std::string describe_values(const ParamSpec& spec);
// `spec` with another default or a narrower set of choices (a backend's own view of a shared parameter).
ParamSpec with_default(ParamSpec spec, const std::string& default_value);
ParamSpec with_choices(ParamSpec spec, const std::vector<std::string>& choices, const std::string& default_value);
// The spec named `name` in `specs`; throws InternalError when there is none.
const ParamSpec& find_spec(const std::vector<ParamSpec>& specs, const std::string& name);

// Parameter values by name. On the command side: the values given, as text (a test's, a CSV row's
// read back) or already typed (a flag's, parsed against the catalogue's spec); on a backend's side
// (resolve_params, backend_registry.h): every parameter it owns, given or its default, typed once
// against the backend's own declaration. The typed accessors return that value without parsing
// again; they refuse a parameter the backend does not declare (it would silently read nothing), a
// value not yet resolved and one of another kind, each an internal error.
class BackendParams {
 public:
  void set(const std::string& name, const std::string& text) {  // as given: resolved by resolve_params
    texts_[name] = text;
    typed_.erase(name);
  }
  void set(const std::string& name, const TypedParam& value) {
    texts_[name] = value.text;
    typed_.insert_or_assign(name, value.value);
  }
  void erase(const std::string& name) {
    texts_.erase(name);
    typed_.erase(name);
  }
  bool has(const std::string& name) const { return texts_.count(name) > 0; }
  const std::map<std::string, std::string>& values() const { return texts_; }  // the canonical texts
  // The typed value, where it is one (set from a TypedParam).
  std::optional<TypedParam> typed(const std::string& name) const;

  const std::string& text(const std::string& name) const;
  int64_t integer(const std::string& name) const;
  double real(const std::string& name) const;  // a Real given as a number (not one of its words)
  bool flag(const std::string& name) const;
  bool is_word(const std::string& name) const;  // a Real or Integer given as one of its words ("auto")

  // Equal when the canonical texts are (the typed values follow from them): a configuration key.
  bool operator==(const BackendParams& other) const { return texts_ == other.texts_; }

 private:
  const ParamValue& value(const std::string& name) const;
  std::map<std::string, std::string> texts_;
  std::map<std::string, ParamValue> typed_;
};

}  // namespace sdfbench
