#pragma once
// Process exit codes, documented in docs/exit-codes.md. Scripts and systemd rely on them: keep
// stable.

namespace rtmot {

// A clean stop on SIGINT/SIGTERM is a success (ok).
enum class ExitCode : int {
  ok = 0,
  internal_error = 1,  // a bug: an exception we did not expect
  usage = 2,           // bad command line: unknown option, bad value
  bad_input = 3,       // a data, config or message file is malformed or missing
  bad_model = 4,       // the detector model is missing, truncated or does not load
  source_failed = 5,   // a video source cannot be opened or decoded
  network = 6,         // a socket cannot be opened/bound (e.g. port in use)
  io_error = 7,        // reading or writing a file failed: disk full, EIO (not the data's fault);
                       // the annotated video's write failing mid-run
  encoder_failed = 8,  // the video encoder refused the frames (a size or format it cannot take)
};

constexpr int to_int(ExitCode code) {
  return static_cast<int>(code);
}

}  // namespace rtmot
