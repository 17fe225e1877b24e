#include "platform/stall_injector.hpp"

#include <chrono>

namespace rtmot::platform {

void StallInjector::attach(GstPad* pad) {
  gst_pad_add_probe(pad, GST_PAD_PROBE_TYPE_BUFFER, &StallInjector::on_buffer, this, nullptr);
}

void StallInjector::cancel() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    cancelled_ = true;
  }
  wake_.notify_all();
}

GstPadProbeReturn StallInjector::on_buffer(GstPad* /*pad*/, GstPadProbeInfo* /*info*/,
                                           gpointer self) {
  auto& injector = *static_cast<StallInjector*>(self);
  if (injector.buffers_seen_++ == injector.stall_after_) injector.stall();
  return GST_PAD_PROBE_OK;
}

void StallInjector::stall() {
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait_for(lock, std::chrono::milliseconds(stall_ms_), [this] { return cancelled_; });
}

}  // namespace rtmot::platform
