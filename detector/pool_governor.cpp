#include "detector/pool_governor.hpp"

#include <algorithm>

namespace rtmot::detector {

PoolGovernor::PoolGovernor(int first_probe, int last_probe)
    : first_probe_(std::max(1, first_probe)),
      last_probe_(std::max(first_probe_, last_probe)),
      probe_after_(first_probe_) {}

int PoolGovernor::next_way() const {
  const int other = 1 - current_;
  // A way never measured is measured next; then the other way once its turn comes.
  if (estimate_[current_] == 0) return current_;
  if (estimate_[other] == 0 || since_probe_ >= probe_after_) return other;
  return current_;
}

bool PoolGovernor::use_pool() const {
  return next_way() == kPooled;
}

void PoolGovernor::record(std::int64_t ns) {
  ns = std::max<std::int64_t>(ns, 1);
  const int way = next_way();
  ++passes_;
  if (way == kPooled) ++pooled_passes_;
  if (way != current_) {  // a probe of the losing way: its time as measured now
    estimate_[way] = ns;
    since_probe_ = 0;
    if (ns < estimate_[current_]) {
      current_ = way;
      probe_after_ = first_probe_;
    } else {
      probe_after_ = std::min(2 * probe_after_, last_probe_);
    }
    return;
  }
  // The winning way: a running estimate (a quarter of each new pass), so one slow pass does not
  // switch, a lasting change does.
  std::int64_t& estimate = estimate_[way];
  estimate = estimate == 0 ? ns : estimate + (ns - estimate) / 4;
  ++since_probe_;
  const int other = 1 - way;
  if (estimate_[other] != 0 && estimate > estimate_[other]) {
    current_ = other;  // the other way was faster when last measured: run it (and measure it)
    since_probe_ = 0;
    probe_after_ = first_probe_;
  }
}

}  // namespace rtmot::detector
