#pragma once
// Error is for user mistakes (bad scene, bad flag, unwritable output): the command line prints
// "sdfbench: error: <message>" and exits 1. InternalError is a broken invariant of sdfbench itself,
// never the input's fault: "sdfbench: internal error: <message>", exit 3, so that a bug is never
// mistaken for bad input (and a table stops instead of recording it as a row's error).
#include <stdexcept>
#include <string>

namespace sdfbench {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace sdfbench
