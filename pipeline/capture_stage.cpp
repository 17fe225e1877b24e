#include "pipeline/capture_stage.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <thread>
#include <utility>

#include "common/simulated_clock.hpp"
#include "platform/clock.hpp"

namespace rtmot::pipeline {
namespace {

using platform::steady_now_ns;

SlotMode slot_mode_for(PlaybackMode mode, bool live) {
  if (live) return SlotMode::latest;
  // simulated decides in the capture thread which frames exist for the detector; those must all
  // arrive, so it needs the waiting slot just like every-frame.
  return mode == PlaybackMode::realtime ? SlotMode::latest : SlotMode::every_frame;
}

}  // namespace

CaptureStage::CaptureStage(std::unique_ptr<platform::VideoSource> source,
                           const CaptureOptions& options, WakeSignal* detector_signal)
    : source_(std::move(source)),
      options_(options),
      live_(source_->info().live),
      playback_(live_ ? PlaybackMode::realtime : options.playback),
      slot_(slot_mode_for(options.playback, live_), detector_signal) {}

CaptureCounts CaptureStage::counts() const {
  CaptureCounts counts;
  counts.frames_captured = frames_captured();
  counts.frames_lost = frames_lost_;
  counts.outages = outages_;
  counts.first_capture_ns = first_capture_ns_;
  counts.source_error = source_error_;
  return counts;
}

// Reads the next frame into `item`; counts it and the source's gaps.
CaptureStage::Next CaptureStage::read_frame(FrameSlotItem& item, const std::atomic<bool>& stop,
                                            const std::atomic<bool>& abort) {
  if (stop.load(std::memory_order_relaxed) || abort.load(std::memory_order_relaxed)) {
    return Next::end;
  }
  const auto captured = frames_captured();
  if (options_.max_frames > 0 && captured >= options_.max_frames) return Next::end;
  const platform::ReadStatus status = source_->read(item.image, item.info);
  if (status == platform::ReadStatus::error && source_->reconnecting()) return outage_tick(item);
  if (status == platform::ReadStatus::error) source_error_ = source_->last_error();
  if (status != platform::ReadStatus::frame) return Next::end;
  if (in_outage_) {
    spdlog::info("{}: source is back after outage {}", source_->info().uri, outages_);
    in_outage_ = false;
    if (board_ != nullptr) {
      if (const auto line = board_->came_back(steady_now_ns())) spdlog::info("{}", *line);
    }
  }
  if (last_number_ > 0 && item.info.frame_number > last_number_ + 1) {
    frames_lost_ += item.info.frame_number - last_number_ - 1;
  }
  last_number_ = item.info.frame_number;
  last_pts_ns_ = item.info.pts_ns;
  last_capture_ns_ = item.info.capture_ns;
  item.outage = false;
  frames_captured_.store(captured + 1, std::memory_order_relaxed);
  if (tap_ != nullptr) tap_->on_frame(item.image, item.info);
  return Next::frame;
}

// The live source is down and being reopened (its read() returned promptly). Instead of ending,
// send a tick without a picture at the current time: the tracker advances (tracks coast) and the
// ground station keeps receiving messages, flagged source_outage, until the source is back.
CaptureStage::Next CaptureStage::outage_tick(FrameSlotItem& item) {
  const std::int64_t now_ns = steady_now_ns();
  // An operator reading the journal of a board whose camera is gone sees a line every 30 s, not
  // one line at the start and then silence.
  constexpr std::int64_t still_down_every_ns = 30'000'000'000;
  if (!in_outage_) {
    in_outage_ = true;
    ++outages_;
    outage_since_ns_ = now_ns;
    next_still_down_ns_ = now_ns + still_down_every_ns;
    spdlog::warn("{}: source outage {}: {}", source_->info().uri, outages_, source_->last_error());
    if (board_ != nullptr) {
      if (const auto line = board_->went_down(now_ns)) spdlog::error("{}", *line);
    }
  } else if (now_ns >= next_still_down_ns_) {
    next_still_down_ns_ = now_ns + still_down_every_ns;
    spdlog::warn("{}: still down after {} s (outage {}; messages flagged source_outage go on): {}",
                 source_->info().uri, (now_ns - outage_since_ns_) / 1'000'000'000, outages_,
                 source_->last_error());
  }
  if (board_ != nullptr) {
    if (const auto line = board_->tick(now_ns)) spdlog::error("{}", *line);
  }
  item.outage = true;
  item.info.frame_number = last_number_;  // no new frame: keeps the dropped-frame count honest
  item.info.pts_ns = last_capture_ns_ > 0 ? last_pts_ns_ + (now_ns - last_capture_ns_) : 0;
  item.info.capture_ns = now_ns;
  return Next::outage_tick;
}

// Hands `item` to the detector: swaps image buffers with the slot's back buffer (no copy).
bool CaptureStage::publish(FrameSlotItem& item, const std::atomic<bool>& abort) {
  // every-frame/simulated: wait for the detector before stamping, so that the time the capture
  // thread spends blocked is not counted as the frame's latency.
  if (!slot_.wait_for_room(abort)) return false;
  if (!live_ && !item.outage) {
    // Recordings: the frame enters the pipeline now, not when the decoder produced it ahead of
    // time; live sources keep the time the frame reached us.
    item.info.capture_ns = steady_now_ns();
  }
  if (first_capture_ns_ == 0) first_capture_ns_ = item.info.capture_ns;
  FrameSlotItem& back = slot_.back();
  std::swap(back.image, item.image);
  back.info = item.info;
  back.outage = item.outage;
  back.trail = trail_;
  if (!item.outage) pass(item);
  return slot_.publish(abort);
}

// A real frame goes by: it enters the trail the next published items carry.
void CaptureStage::pass(const FrameSlotItem& item) {
  trail_.push(FrameStamp{item.info.frame_number, item.info.pts_ns, item.info.capture_ns});
}

void CaptureStage::run_simulated(const std::atomic<bool>& stop, const std::atomic<bool>& abort) {
  // One frame of look-ahead: frame k is taken only if frame k+1 is not there yet when the
  // simulated detector looks.
  SimulatedClock clock(simulated_latency_ns(options_.simulated_latency_ms));
  FrameSlotItem current;
  FrameSlotItem next;
  // (Only recordings play simulated, and they have no outages.)
  bool have_current = read_frame(current, stop, abort) == Next::frame;
  while (have_current) {
    const bool have_next = read_frame(next, stop, abort) == Next::frame;
    const auto next_pts = have_next ? std::optional(next.info.pts_ns) : std::nullopt;
    if (!clock.takes(current.info.pts_ns, next_pts)) {
      pass(current);
    } else if (!publish(current, abort)) {
      return;
    }
    std::swap(current, next);
    have_current = have_next;
  }
}

// Sleeps until the wall time `due_ns`, in slices short enough that a stop or an abort is seen at
// once: a recording whose timestamps jump by an hour (a gap, or a hostile file) must not hold the
// run for that hour. False when stopped or aborted first.
bool CaptureStage::wait_for_pts(std::int64_t due_ns, const std::atomic<bool>& stop,
                                const std::atomic<bool>& abort) {
  constexpr std::int64_t kSliceNs = 20'000'000;
  for (std::int64_t wait_ns = due_ns - steady_now_ns(); wait_ns > 0;
       wait_ns = due_ns - steady_now_ns()) {
    if (stop.load(std::memory_order_relaxed) || abort.load(std::memory_order_relaxed)) return false;
    std::this_thread::sleep_for(std::chrono::nanoseconds(std::min(wait_ns, kSliceNs)));
  }
  return true;
}

void CaptureStage::run(const std::atomic<bool>& stop, const std::atomic<bool>& abort) {
  if (playback_ == PlaybackMode::simulated) {
    run_simulated(stop, abort);
    return;
  }
  FrameSlotItem current;
  std::int64_t wall_origin_ns = 0;  // realtime: the wall time of pts 0
  for (Next next = read_frame(current, stop, abort); next != Next::end;
       next = read_frame(current, stop, abort)) {
    if (playback_ == PlaybackMode::realtime && !live_) {
      if (wall_origin_ns == 0) wall_origin_ns = steady_now_ns() - current.info.pts_ns;
      if (!wait_for_pts(wall_origin_ns + current.info.pts_ns, stop, abort)) return;
    }
    if (!publish(current, abort)) return;
  }
}

}  // namespace rtmot::pipeline
