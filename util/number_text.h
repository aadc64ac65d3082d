#pragma once
// A number as sdfbench writes it everywhere (CSV cells, help, messages, canonical parameter
// values): 6 significant digits, the shortest form printf's %g gives ("0.5", "1e+06", "inf").
#include <cstdio>
#include <string>

namespace sdfbench {

inline std::string six_digits(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace sdfbench
