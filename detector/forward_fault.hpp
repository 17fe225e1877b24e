#pragma once
// A test hook, part of the product as shipped (no other build): RTMOT_FAULT_FORWARD_AFTER=N in
// the environment makes each SSD detector's forward passes after its first N (start-up passes not
// counted) fail as a CUDA graph or stream failure would, on any OpenCV backend. It is how the
// run-time failure path (error naming the backend and `backend: cpu`, exit code 4, every output
// whole, every detect lane joined) is provoked on a machine without a GPU to break
// (tests/system/forward_failure_run.sh, docs/reliability.md). Unset: never fails.
#include <cstdint>
#include <string>

namespace rtmot::detector {

class ForwardFault {
 public:
  /// Reads RTMOT_FAULT_FORWARD_AFTER once. Throws InputError (usage) when it is set but not a
  /// count.
  ForwardFault();
  /// True on every call after the first N: the forward pass must fail now.
  bool fails_now();
  /// The failure's text.
  std::string what() const;

 private:
  std::int64_t after_{-1};  // -1: off
  std::int64_t passes_{0};
};

}  // namespace rtmot::detector
