#pragma once
// One error type for user mistakes (bad scene, bad flag, unwritable output): the command line
// prints its message and exits non-zero. Internal invariants use assert.
#include <stdexcept>
#include <string>

namespace sdfbench {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace sdfbench
