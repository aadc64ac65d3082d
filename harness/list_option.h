#pragma once
// Comma-separated list flags (--backends, --objects, a sweep's axes): parsed once, each value
// checked, and a value given twice refused, since it would measure one configuration twice (and
// merge and --resume then refuse the CSV).
#include <string>
#include <vector>

namespace sdfbench {

// The non-empty items of `text`; throws Error naming `option` for an empty list or an item given twice.
std::vector<std::string> split_list(const std::string& text, const std::string& option);

// Non-negative finite numbers (unsigned, size_t, float, double); throws Error naming `option` and the item
// for anything else (out of range: with the type's maximum), and for a value given twice.
template <class T>
std::vector<T> parse_list(const std::string& text, const std::string& option);

}  // namespace sdfbench
