#pragma once
// The frames a run processed, written beside its MOTChallenge results as <sequence>.frames so that
// `rtmot eval --processed-frames` scores those frames only: a run that skips frames (a fixed
// interval, or a pipeline whose detector is slower than the camera) reports nothing for the frames
// it never saw, and scored at the full rate those count as misses. Format: one frame number per
// line, ascending, 1..the sequence's length; lines starting with '#' are comments.
#include <filesystem>
#include <string>
#include <vector>

namespace rtmot::motio {

/// "<name>.frames" in `dir`.
std::filesystem::path processed_frames_file(const std::filesystem::path& dir,
                                            const std::string& sequence_name);

/// Writes `frames` (ascending) whole, or not at all (common/output_file.hpp).
void write_processed_frames(const std::filesystem::path& path, const std::vector<int>& frames);

/// Reads a processed-frames file of a sequence of `sequence_length` frames. Throws InputError
/// naming the file, line and field for anything but ascending frame numbers in 1..length.
std::vector<int> read_processed_frames(const std::filesystem::path& path, int sequence_length);

}  // namespace rtmot::motio
