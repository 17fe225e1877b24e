#include "outputs/civetweb_library.hpp"

#include <civetweb.h>

#include <mutex>

namespace rtmot::outputs {

void ensure_civetweb_library() {
  static std::once_flag once;
  std::call_once(once, [] { mg_init_library(0); });
}

}  // namespace rtmot::outputs
