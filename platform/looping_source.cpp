#include "platform/looping_source.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <utility>

#include "common/input_error.hpp"

namespace rtmot::platform {
namespace {

// Whether the start of pass `pass` is logged: passes 2 to 10, then 20, 30, ..., 100, 200, ... A
// folder of three images looping for ever starts thousands of passes a second; one line each
// drowned the log (19,000 lines in 3 s). This keeps the first restarts and then tens of lines
// however long it runs.
bool logged_pass(int pass) {
  int leading = pass;
  while (leading >= 10 && leading % 10 == 0) leading /= 10;
  return pass <= 10 || leading < 10;
}

}  // namespace

LoopingSource::LoopingSource(Opener open, int loops)
    : open_(std::move(open)), loops_(loops), source_(open_()), info_(source_->info()) {
  info_.frame_count = loops_ < 0 ? 0 : info_.frame_count * (loops_ + 1);
  if (info_.fps > 0.0) period_ns_ = std::llround(1e9 / info_.fps);
}

ReadStatus LoopingSource::read(cv::Mat& bgr, FrameInfo& info) {
  for (;;) {
    if (!source_) return ReadStatus::error;
    const ReadStatus status = source_->read(bgr, info);
    if (status == ReadStatus::frame) {
      info.frame_number += frame_offset_;
      info.pts_ns += pts_offset_ns_;
      if (last_frame_ > frame_offset_ && info.pts_ns > last_pts_ns_ && info_.fps <= 0.0) {
        period_ns_ = info.pts_ns - last_pts_ns_;
      }
      last_frame_ = info.frame_number;
      last_pts_ns_ = info.pts_ns;
      return status;
    }
    const bool empty_pass = last_frame_ == frame_offset_;
    if (status == ReadStatus::error || empty_pass || (loops_ >= 0 && passes_ > loops_)) {
      return status;
    }
    ++passes_;
    frame_offset_ = last_frame_;
    pts_offset_ns_ = last_pts_ns_ + period_ns_;
    if (logged_pass(passes_)) {
      const std::string of =
          loops_ < 0 ? ", looping for ever" : " of " + std::to_string(loops_ + 1);
      spdlog::info(
          "{}: end of the file, playing it again (pass {}{}{})", info_.uri, passes_, of,
          passes_ == 10 ? "; from here on logged at passes 20, 30, ..., 100, 200, ..." : "");
    }
    source_.reset();  // the decoder of the last pass goes before the next one starts
    try {
      source_ = open_();
    } catch (const InputError& error) {
      reopen_error_ =
          std::string("cannot reopen it for pass ") + std::to_string(passes_) + ": " + error.what();
      return ReadStatus::error;
    }
  }
}

std::string LoopingSource::last_error() const {
  return source_ ? source_->last_error() : reopen_error_;
}

}  // namespace rtmot::platform
