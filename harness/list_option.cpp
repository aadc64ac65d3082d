#include "harness/list_option.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "util/error.h"


namespace sdfbench {
namespace {

template <class T>
std::string text_of(T v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

template <class T>
void refuse_repeats(const std::vector<T>& values, const std::vector<std::string>& items, const std::string& text,
                    const std::string& option) {
  for (size_t i = 0; i < values.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (values[j] == values[i])
        throw Error(option + " '" + text + "': '" + items[i] + "' is listed twice" +
                    (items[i] == items[j] ? "" : " (as '" + items[j] + "')") + "; each value is one configuration");
}

// The comma-separated items of `text`, empty ones skipped; at least one.
std::vector<std::string> non_empty_items(const std::string& text, const std::string& option) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  if (items.empty()) throw Error(option + " '" + text + "': expected a comma-separated list");
  return items;
}

}  // namespace

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
  const std::vector<std::string> items = non_empty_items(text, option);
  refuse_repeats(items, items, text, option);
  return items;
}

template <class T>
std::vector<T> parse_list(const std::string& text, const std::string& option) {
  const std::vector<std::string> items = non_empty_items(text, option);
  std::vector<T> values;
  for (const std::string& item : items) {
    T v{};
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    const std::string where = option + " '" + text + "': '" + item + "'";
    if (ec == std::errc::result_out_of_range && end == item.data() + item.size() && item[0] != '-')
      throw Error(where + " is out of range (at most " + text_of(std::numeric_limits<T>::max()) + ")");
    if (ec != std::errc() || end != item.data() + item.size() || item[0] == '-')
      throw Error(where + " is not a non-negative number");
    if constexpr (std::is_floating_point_v<T>)
      if (!std::isfinite(v)) throw Error(where + " is not a finite number");
    values.push_back(v);
  }
  refuse_repeats(values, items, text, option);
  return values;
}
template std::vector<double> parse_list<double>(const std::string&, const std::string&);
template std::vector<float> parse_list<float>(const std::string&, const std::string&);
template std::vector<unsigned> parse_list<unsigned>(const std::string&, const std::string&);
template std::vector<size_t> parse_list<size_t>(const std::string&, const std::string&);

}  // namespace sdfbench
