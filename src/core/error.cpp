#include "core/error.hpp"

namespace armctl {

const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::invalid_argument: return "invalid argument";
    case ErrorKind::invalid_config: return "invalid config";
    case ErrorKind::io: return "I/O error";
    case ErrorKind::timeout: return "timeout";
    case ErrorKind::protocol: return "protocol error";
    case ErrorKind::device: return "device error";
    case ErrorKind::unsupported: return "unsupported";
  }
  return "error";
}

}  // namespace armctl
