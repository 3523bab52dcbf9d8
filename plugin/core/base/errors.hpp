// Error types of the nbm core. The FreeFEM binding turns both into ExecError.
#pragma once

#include <stdexcept>
#include <string>

namespace nbm {

/// Malformed input: the message names the argument and what was expected.
struct InputError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// A numerical failure the input could not be blamed for in advance
/// (a singular block met during stepping, a non-terminating pivot sequence).
struct NumericalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace nbm
