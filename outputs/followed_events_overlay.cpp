#include "outputs/followed_events_overlay.hpp"

namespace rtmot::outputs {

void FollowedEventsOverlay::start_with(const events::EventsConfig& config) {
  if (config.lines.empty() && config.zones.empty()) {
    overlay_.reset();
  } else {
    overlay_.emplace(config);
  }
}

void FollowedEventsOverlay::switch_to(std::uint32_t generation) {
  if (mailbox_ == nullptr || generation == shown_) return;
  if (const pipeline::PostedEvents* posted = mailbox_->take()) next_ = posted;
  if (next_ == nullptr || next_->generation != generation) return;
  start_with(next_->config);
  shown_ = generation;
  next_ = nullptr;
}

}  // namespace rtmot::outputs
