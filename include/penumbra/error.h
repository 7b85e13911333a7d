// The one error type for bad input, missing files, GL and shader failures: its message says what
// went wrong and what the valid choices are. Logic errors assert instead.
#pragma once

#include <stdexcept>
#include <string>

namespace penumbra {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace penumbra
