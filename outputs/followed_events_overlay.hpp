#pragma once
// The annotated video's lines and zones (outputs/events_overlay.hpp) as they change while the run
// goes on (a page save, SIGHUP: docs/web.md): each new configuration arrives through a mailbox of
// its own (pipeline/events_mailbox.hpp, posted by runner/events_editor.hpp) and is drawn, its
// counts from zero, from the first frame counted with it (FrameResult::events_generation) on, as
// the metrics switch. Sink thread only.
//
// A configuration replaced before any frame counted with it reached the video is never drawn (the
// mailbox keeps only the newest): the one before stays until the newest's first frame. A switch
// allocates the new overlay and frees the old one on the sink thread: once per save, a person's
// click, as the video's encoder allocates for every frame.
#include <cstdint>
#include <optional>

#include "outputs/events_overlay.hpp"
#include "pipeline/events_mailbox.hpp"

namespace rtmot::outputs {

class FollowedEventsOverlay {
 public:
  /// The run's own lines and zones (generation 0); none: nothing drawn until a save.
  void start_with(const events::EventsConfig& config);
  /// Where the changes arrive (not owned, outlives this); null: never.
  void follow(pipeline::EventsMailbox* mailbox) { mailbox_ = mailbox; }

  /// Before a frame counted with configuration `generation` is drawn or counted.
  void switch_to(std::uint32_t generation);

  /// What to draw and count now; null: nothing.
  EventsOverlay* get() { return overlay_ ? &*overlay_ : nullptr; }
  std::uint32_t generation() const { return shown_; }

 private:
  std::optional<EventsOverlay> overlay_;
  pipeline::EventsMailbox* mailbox_{nullptr};
  const pipeline::PostedEvents* next_{nullptr};  // taken, its frames not reached yet
  std::uint32_t shown_{0};
};

}  // namespace rtmot::outputs
