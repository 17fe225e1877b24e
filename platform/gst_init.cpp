#include <spdlog/spdlog.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "common/input_error.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::platform::gst {

void ensure_initialized() {
  // gst_init sets up process-wide state, so the guard has to be process-wide too. If the lambda
  // throws, call_once is not marked done and the next caller retries.
  static std::once_flag once;
  std::call_once(once, [] {
    // GStreamer itself honours GST_REGISTRY (where the plugin cache lives) and
    // GST_REGISTRY_UPDATE=no (trust the cache, skip the rescan). Under qemu the first scan can take
    // over 10 minutes, so cross-test setups pre-build the cache and set both; we only report them.
    for (const char* name : {"GST_REGISTRY", "GST_REGISTRY_UPDATE", "GST_REGISTRY_FORK",
                             "GST_PLUGIN_SYSTEM_PATH", "GST_PLUGIN_PATH"}) {
      if (const char* value = std::getenv(name)) spdlog::debug("gstreamer: {}={}", name, value);
    }
    GError* raw_error = nullptr;
    if (!gst_init_check(nullptr, nullptr, &raw_error)) {
      const ErrorPtr error(raw_error);
      throw InputError("", 0, "",
                       std::string("GStreamer failed to initialise: ") +
                           (error ? error->message : "unknown reason"),
                       ExitCode::source_failed);
    }
  });
}

}  // namespace rtmot::platform::gst
