#pragma once
// A new events configuration (lines, zones: docs/events.md) for one source, handed to the track
// stage while the pipeline runs (the web page's "save", docs/web.md). Posters (HTTP workers) may be
// several and are serialised by a mutex of their own; the track thread takes the newest posted
// configuration between two frames with one atomic exchange, and never takes a lock or waits.
//
// Memory order: post() builds the configuration, keeps it, then stores its address with release;
// take() exchanges the slot with null with acquire, so every write that built the configuration
// happens before the track thread reads it. A configuration posted twice before the track thread
// took one is replaced: only the newest is ever applied. Every posted configuration lives as long
// as the mailbox (kept in a list only posters touch), so the address the track thread holds never
// dangles and nothing is freed on the track thread; the list grows by one small configuration per
// save, which a person makes.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "events/events_config.hpp"

namespace rtmot::pipeline {

/// A posted configuration and its number (the poster's: 1, 2, ... in posting order).
struct PostedEvents {
  events::EventsConfig config;
  std::uint32_t generation{0};
};

class EventsMailbox {
 public:
  /// Any thread: posts `config` as configuration number `generation`.
  void post(events::EventsConfig config, std::uint32_t generation) {
    const std::lock_guard<std::mutex> lock(posters_);
    kept_.push_back(
        std::make_unique<const PostedEvents>(PostedEvents{std::move(config), generation}));
    pending_.store(kept_.back().get(), std::memory_order_release);
  }

  /// Track thread: the newest configuration posted since the last take, or null.
  const PostedEvents* take() {
    // A relaxed look first: no read-modify-write (and no cache-line traffic) while nothing came.
    if (pending_.load(std::memory_order_relaxed) == nullptr) return nullptr;
    return pending_.exchange(nullptr, std::memory_order_acquire);
  }

 private:
  std::atomic<const PostedEvents*> pending_{nullptr};
  std::mutex posters_;
  std::vector<std::unique_ptr<const PostedEvents>> kept_;  // guarded by posters_
};

}  // namespace rtmot::pipeline
