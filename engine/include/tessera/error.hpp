// The one error type of Tessera's public API.
// Every function that can fail on bad input throws tessera::Error with a one-line message
// naming the argument or file and what is wrong; nothing the caller passed in is modified.
#pragma once

#include <stdexcept>
#include <string>

#include "tessera/export.hpp"

namespace tessera {

enum class ErrorCode {
  kInvalidArgument,  // a parameter out of range or inconsistent with another
  kInvalidInput,     // vertex data, indices or file contents that cannot be drawn
  kIo,               // a file that cannot be opened, read or written
  kOutOfMemory,      // an allocation larger than the documented limits
  kUnsupported,      // a valid state that the chosen backend cannot draw (it names the state)
};

class TESSERA_API Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ErrorCode code() const noexcept { return code_; }

 private:
  ErrorCode code_;
};

}  // namespace tessera
