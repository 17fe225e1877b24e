#pragma once
// Outputs that appear only when finished (common/output_file.hpp's `on_close`, the video files of
// outputs/gst_video_output.hpp) are written under PATH.tmp-PID and renamed at the end. A writer
// killed by SIGKILL or a power cut cannot remove its temporary: the next writer of the same PATH
// does, for every PID that no longer runs. Two hosts or containers (other PID namespaces) writing
// one PATH at once are not supported: their temporaries look stale to each other, and their
// finished files would replace each other anyway.
#include <cstddef>
#include <filesystem>

namespace rtmot {

/// PATH.tmp-<this process's id>: where a file published on close is written.
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

/// Removes every PATH.tmp-N beside PATH whose process N no longer runs (kill(N, 0) fails with
/// ESRCH), this process's own excepted; logs each one. Returns how many it removed. Never throws:
/// what cannot be listed or removed stays, and the output is written as before.
std::size_t remove_stale_temporaries(const std::filesystem::path& path);

}  // namespace rtmot
