#include "harness/overlap_axis.h"

#include <charconv>

#include "harness/list_option.h"
#include "scenes/overlap_layout.h"
#include "util/error.h"

namespace sdfbench {
namespace {

std::string shortest(double k) {
  char text[32];
  return {text, std::to_chars(text, text + sizeof text, k).ptr};
}

// An overlap: spec (four or five parts) with its k replaced by `k`, the rest as written.
std::string replace_k(const std::string& spec, const std::string& k) {
  const size_t before_k = spec.find(':', spec.find(':', spec.find(':') + 1) + 1);
  const size_t after_k = spec.find(':', before_k + 1);  // the seed's colon, if any
  return spec.substr(0, before_k + 1) + k + (after_k == std::string::npos ? "" : spec.substr(after_k));
}

}  // namespace

std::vector<double> parse_overlap_list(const std::string& text) {
  const std::vector<double> ks = parse_list<double>(text, "--overlap");
  for (const double k : ks)
    if (!(k >= 1 && k <= kMaxOverlap))
      throw Error("--overlap '" + text + "': " + shortest(k) + " is outside [1, " + shortest(kMaxOverlap) +
                  "] (the boxes over each point)");
  return ks;
}

std::string overlap_scene(const std::string& mesh, size_t count, double k) {
  return "overlap:" + mesh + ":" + std::to_string(count) + ":" + shortest(k);
}

std::string with_overlap(const std::string& spec, double k) {
  if (asked_overlap(spec).empty())
    throw Error("--overlap varies the k of an overlap:<mesh>:<count>:<k> scene; --scene '" + spec + "' is not one");
  parse_overlap_spec(spec);  // a malformed spec fails as the scene would
  return replace_k(spec, shortest(k));
}

std::string overlap_family(const std::string& spec) { return asked_overlap(spec).empty() ? spec : replace_k(spec, "<k>"); }

std::string asked_overlap(const std::string& spec) {
  if (spec.rfind("overlap:", 0) != 0) return "";
  size_t at = 0;
  for (int colon = 0; colon < 3 && at != std::string::npos; ++colon) at = spec.find(':', at + 1);
  return at == std::string::npos ? "" : spec.substr(at + 1, spec.find(':', at + 1) - at - 1);
}

}  // namespace sdfbench
