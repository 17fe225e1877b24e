#pragma once
// The detector's score cut, changed while the pipeline runs (SIGHUP, the page's POST /api/settings:
// docs/web.md). The detector keeps the cut it was built with (inside its post-processing); this
// one is applied after it, by the detect stage, to every batch's boxes. So it can be raised above
// the start's cut and brought back down to it, not below (that needs a restart): floor() is the
// start's.
//
// Memory order: relaxed both ways. The cut is one self-contained value: nothing else is published
// with it, so no write needs to happen before the detect stage sees it; the stage reads it once
// per batch, so every box of a batch is cut by one value, and a new value is seen at the latest a
// few batches later (coherence of one atomic). std::atomic<float> is lock-free on every target
// (checked below): the detect thread never waits on a setter.
#include <atomic>

namespace rtmot::pipeline {

class ScoreCut {
 public:
  explicit ScoreCut(float start) : floor_(start), cut_(start) {}

  /// The cut the detector itself was built with: a lower one has no effect.
  float floor() const { return floor_; }
  /// Any thread.
  void set(float cut) { cut_.store(cut, std::memory_order_relaxed); }
  /// The detect stage, once per batch; the page's status.
  float get() const { return cut_.load(std::memory_order_relaxed); }

 private:
  static_assert(std::atomic<float>::is_always_lock_free, "the detect thread must never wait");
  const float floor_;
  std::atomic<float> cut_;
};

}  // namespace rtmot::pipeline
