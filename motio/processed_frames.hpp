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

class ResultsWriter;

/// Publishes `results` and the list of `frames` beside it both or neither
/// (common/output_file.hpp's publish_together): a full disk at the list leaves no results file
/// that `eval --processed-frames` could not score. Throws InputError (io_error).
void publish_results_and_frames(ResultsWriter& results, const std::filesystem::path& frames_file,
                                const std::vector<int>& frames);

/// Reads a processed-frames file of a sequence of `sequence_length` frames. Throws InputError
/// naming the file, line and field for anything but ascending frame numbers in 1..length, and
/// for a list without any (a run that processed nothing has nothing to score).
std::vector<int> read_processed_frames(const std::filesystem::path& path, int sequence_length);

}  // namespace rtmot::motio
