#include "platform/reconnecting_source.hpp"

#include <algorithm>
#include <cmath>
#include <thread>
#include <utility>

#include "common/input_error.hpp"
#include "platform/clock.hpp"

namespace rtmot::platform {

namespace {

std::int64_t to_ns(std::chrono::milliseconds duration) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(duration).count();
}

}  // namespace

ReconnectClock ReconnectClock::steady() {
  return {steady_now_ns,
          [](std::int64_t ns) { std::this_thread::sleep_for(std::chrono::nanoseconds(ns)); }};
}

ReconnectingSource::ReconnectingSource(Factory factory, ReconnectPolicy policy,
                                       ReconnectClock clock, SourceInfo expected)
    : factory_(std::move(factory)),
      policy_(policy),
      clock_(std::move(clock)),
      delay_(policy_.initial_delay) {
  try {
    source_ = factory_();
  } catch (const InputError& error) {
    if (!policy_.retry_first_open) throw;
    // Cold start: the camera is not there yet. Start as an outage; the first reopen comes after
    // the initial delay and backs off like any other.
    info_ = std::move(expected);
    info_.live = true;
    ++stats_.outages;
    ++stats_.failed_attempts;
    frame_since_reopen_ = false;
    last_error_ = std::string("reconnecting: not available at start-up: ") + error.what();
    outage_start_ns_ = clock_.now_ns();
    next_attempt_ns_ = outage_start_ns_ + to_ns(delay_);
    return;
  }
  if (!source_)
    throw InputError("", 0, "", "the video source factory returned no source",
                     ExitCode::source_failed);
  info_ = source_->info();
}

ReadStatus ReconnectingSource::read(cv::Mat& bgr, FrameInfo& info) {
  return source_ ? read_connected(bgr, info) : wait_or_reopen(bgr, info);
}

ReadStatus ReconnectingSource::read_connected(cv::Mat& bgr, FrameInfo& info) {
  const ReadStatus status = source_->read(bgr, info);
  if (status == ReadStatus::frame) {
    if (!frame_since_reopen_) {
      // Reset only once the reopened source delivers: one that opens and dies at once keeps
      // backing off instead of being hammered at the initial delay.
      frame_since_reopen_ = true;
      delay_ = policy_.initial_delay;
    }
    info.frame_number += frame_offset_;
    info.pts_ns += pts_offset_ns_;
    last_frame_number_ = info.frame_number;
    last_pts_ns_ = info.pts_ns;
    return status;
  }
  if (!info_.live) {  // a file's end or decode error is final: nothing to reconnect to
    last_error_ = source_->last_error();
    return status;
  }
  begin_outage(status == ReadStatus::end_of_stream ? std::string("end of stream")
                                                   : source_->last_error());
  return ReadStatus::error;
}

void ReconnectingSource::begin_outage(const std::string& reason) {
  ++stats_.outages;
  if (!frame_since_reopen_) delay_ = std::min(delay_ * 2, policy_.max_delay);
  source_.reset();  // releases the device/socket before we try to open it again
  last_error_ = "reconnecting: " + reason;
  outage_start_ns_ = clock_.now_ns();
  next_attempt_ns_ = outage_start_ns_ + to_ns(delay_);
}

ReadStatus ReconnectingSource::wait_or_reopen(cv::Mat& bgr, FrameInfo& info) {
  std::int64_t now = clock_.now_ns();
  if (now < next_attempt_ns_) {
    // Sleep at most one poll interval so the caller gets control back at a steady tick.
    clock_.sleep_ns(std::min(next_attempt_ns_ - now, to_ns(policy_.poll_interval)));
    now = clock_.now_ns();
    if (now < next_attempt_ns_) return ReadStatus::error;
  }
  try {
    source_ = factory_();
  } catch (const InputError& error) {  // anything else is a bug and propagates
    source_.reset();
    last_error_ = std::string("reconnecting: ") + error.what();
  }
  if (!source_) {
    ++stats_.failed_attempts;
    delay_ = std::min(delay_ * 2, policy_.max_delay);
    next_attempt_ns_ = clock_.now_ns() + to_ns(delay_);
    return ReadStatus::error;
  }
  ++stats_.reconnects;
  frame_since_reopen_ = false;
  info_.width = source_->info().width;
  info_.height = source_->info().height;
  if (info_.fps <= 0.0) info_.fps = source_->info().fps;  // a cold start did not know it

  // The new source counts from frame 1 and pts 0 again; continue our numbering after the gap.
  const std::int64_t outage_ns = std::max<std::int64_t>(clock_.now_ns() - outage_start_ns_, 1);
  // Nothing was lost before the first frame of a cold start: the camera was not there yet.
  const bool delivered_before = last_frame_number_ > 0;
  const std::int64_t lost = info_.fps > 0.0 && delivered_before
                                ? std::llround(static_cast<double>(outage_ns) * info_.fps * 1e-9)
                                : 0;
  stats_.frames_lost += lost;
  frame_offset_ = last_frame_number_ + lost;
  pts_offset_ns_ = last_pts_ns_ + outage_ns;
  return read_connected(bgr, info);
}

}  // namespace rtmot::platform
