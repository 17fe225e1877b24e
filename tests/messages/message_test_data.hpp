#pragma once
// Realistic frames for the message tests: MOT15's published detections turned into track reports.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "messages/frame_result.hpp"
#include "messages/message_format.hpp"

namespace rtmot::test {

/// The frames of MOT15 training sequence `sequence` (e.g. "TUD-Campus"), at most `max_frames`,
/// each detection of det/det.txt one track (ids unique over the sequence, class person, ages and
/// hits growing with the frame), timed as a 30 fps capture with a few milliseconds of latency.
/// Fails the test (naming the file) if the data is missing.
std::vector<messages::FrameResult> frames_from_detections(const std::string& sequence,
                                                          std::size_t max_frames);

/// One frame holding `track_count` tracks: the detections of successive frames of `sequence`
/// pooled together, for crowds larger than any single frame of MOT15.
messages::FrameResult crowd_from_detections(const std::string& sequence, std::size_t track_count);

/// Whether `decoded` carries exactly what the message format promises to carry of `sent`.
::testing::AssertionResult same_as_sent(const messages::FrameResult& sent,
                                        const messages::DecodedMessage& decoded);

}  // namespace rtmot::test
