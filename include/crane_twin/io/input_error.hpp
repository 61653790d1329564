// The error for bad user input: a scene or crane file, a `--set` override, a command-line
// argument or a ROS parameter. The message names the file (or source) and the key; the CLI
// maps it to exit status 2 (docs/cli.md).
#pragma once

#include <stdexcept>

namespace crane_twin {

/// Bad user input (file, key, value). The message names the file and the key.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace crane_twin
