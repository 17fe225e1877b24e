#pragma once
// Whether XNNPACK's next forward pass runs on its thread pool or on the caller's thread alone,
// decided by the two ways' measured times. Why: Debian 12's pthreadpool (2021-05) spin-waits at
// the end of every operator, the caller for workers to check in and the workers for the next
// operator (1,000,000 pause instructions, no flag turns either off: XNNPACK's
// XNN_FLAG_YIELD_WORKERS reaches only a runtime's last operator). A worker without a core keeps
// the whole pass waiting, ~90 times a pass: measured 1.3 s a forward at 2 threads on the loaded
// 2-core VM against 0.11 s on one thread (docs/cpu-detector.md). The pool cannot be made to sleep,
// so it is used only while it is the faster way. Pure logic, no clock: the caller times the pass.
#include <array>
#include <cstdint>

namespace rtmot::detector {

class PoolGovernor {
 public:
  /// The losing way is tried again after `first_probe` passes of the winning way, then after twice
  /// as many each time it loses again, up to `last_probe`; a probe that wins switches at once.
  explicit PoolGovernor(int first_probe = 8, int last_probe = 256);

  /// True: run the next pass on the pool; false: on the caller's thread.
  bool use_pool() const;
  /// The wall time of the pass just run the way use_pool() said.
  void record(std::int64_t ns);

  /// The current estimate of each way (0 until measured once), for the log and the benchmark.
  std::int64_t pooled_ns() const { return estimate_[kPooled]; }
  std::int64_t inline_ns() const { return estimate_[kInline]; }
  /// Passes run on the pool and in all, since construction.
  std::int64_t pooled_passes() const { return pooled_passes_; }
  std::int64_t passes() const { return passes_; }

 private:
  static constexpr int kPooled = 0;
  static constexpr int kInline = 1;
  int next_way() const;

  int first_probe_;
  int last_probe_;
  int current_{kPooled};
  int probe_after_;
  int since_probe_{0};
  std::array<std::int64_t, 2> estimate_{0, 0};
  std::int64_t pooled_passes_{0};
  std::int64_t passes_{0};
};

}  // namespace rtmot::detector
