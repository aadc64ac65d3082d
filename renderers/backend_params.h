#pragma once
// Parameters a backend family owns (issue 28), as Mitsuba's plugins own their properties: each
// family declares its parameters once (name, default, allowed values, help), and the commands'
// flags, the sweep's axes and the CSV's columns are made from those declarations. A new backend
// adds parameters here, not to BackendOptions or the harness.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sdfbench {

struct ParamSpec {
  std::string name;           // CSV column; the flag is --name with '-' for '_'
  std::vector<std::string> families;  // the backends that read it ("sdf-bricks", "sdf-global")
  std::string default_value;
  std::string help;
  std::vector<std::string> choices;  // one of these; else (none, or also) a number:
  int64_t lo = 0, hi = 0;            // an integer in [lo, hi], or
  bool positive_real = false;        // a finite real number > 0
};

// Every family's parameters, in CSV column order.
const std::vector<ParamSpec>& param_specs();
std::string flag_of(const ParamSpec& spec);
bool belongs_to(const ParamSpec& spec, const std::string& backend);
std::string families_of(const ParamSpec& spec);  // "sdf-bricks, sdf-global"
// An empty string when `value` is allowed, else why not (without the flag's name).
std::string check_param_value(const ParamSpec& spec, const std::string& value);

// The values given for a run; unset parameters read as their defaults.
class BackendParams {
 public:
  // Throws Error naming the flag for an unknown parameter or a value its spec does not allow.
  void set(const std::string& name, const std::string& value);
  const std::string& get(const std::string& name) const;
  int64_t integer(const std::string& name) const;
  double real(const std::string& name) const;  // a positive_real parameter given as a number
  // Whether a parameter of a family other than `backend`'s was given (it would do nothing).
  std::string misplaced_for(const std::string& backend) const;

 private:
  std::map<std::string, std::string> values_;
};

}  // namespace sdfbench
