#pragma once
// The overlap axis (issue 37): `--overlap K,...` lists, shared by `table --table overlap` and
// `sweep`, and the overlap:<mesh>:<count>:<k> scenes they name (scenes/overlap_layout.h).
#include <cstddef>
#include <string>
#include <vector>

namespace sdfbench {

// The `table` column of the overlap table's rows (and its --table id).
inline constexpr char kOverlapTable[] = "overlap";

// The values of --overlap: numbers in [1, kMaxOverlap], none twice; throws Error naming the flag.
std::vector<double> parse_overlap_list(const std::string& text);

// "overlap:<mesh>:<count>:<k>", k in its shortest exact text ("4", "1.5").
std::string overlap_scene(const std::string& mesh, size_t count, double k);

// `spec` (an overlap: scene, as the user wrote it) with its k replaced, mesh, count and seed kept;
// throws Error naming --overlap and --scene when `spec` is not an overlap: scene.
std::string with_overlap(const std::string& spec, double k);

// The k an overlap: scene asks for, as written in it ("4"); empty for any other scene.
std::string asked_overlap(const std::string& spec);

// "overlap:bunny:100:<k>" for every k of one overlap: scene (seed kept); any other scene as it is.
std::string overlap_family(const std::string& spec);

}  // namespace sdfbench
