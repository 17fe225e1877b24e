#pragma once
// Latency percentiles without per-frame allocation: a fixed log-scale histogram from 1 us to ~100 s
// with 2% wide buckets (so a percentile is exact to 2%), plus exact count, sum and max. Written by
// one thread; read by it or after it finished. Hand-written because the one library for this,
// HdrHistogram_c, is not packaged for Debian 12, and this needs ~60 lines.
// The run's report and log lines read it. The Prometheus endpoint keeps a different fact in its own
// class (outputs::LatencyBuckets: counts at fixed `le` bounds, read while written; why not this
// one: outputs/pipeline_metrics.hpp).
#include <array>
#include <cstdint>

namespace rtmot::pipeline {

class LatencyHistogram {
 public:
  void record(std::int64_t nanoseconds);
  void clear();

  std::int64_t count() const { return count_; }
  /// The q-quantile (0 < q <= 1) in nanoseconds; 0 when empty. Within 2% of the true value (the
  /// upper edge of the bucket holding it, capped at the exact max).
  std::int64_t quantile_ns(double q) const;
  std::int64_t max_ns() const { return max_ns_; }
  double mean_ns() const { return count_ == 0 ? 0.0 : sum_ns_ / static_cast<double>(count_); }
  double sum_ns() const { return sum_ns_; }

 private:
  static constexpr int bucket_count = 932;  // 1.02^932 * 1 us ~= 100 s
  static int bucket_of(std::int64_t nanoseconds);
  static std::int64_t upper_edge_ns(int bucket);

  std::array<std::int64_t, bucket_count> buckets_{};
  std::int64_t count_{0};
  std::int64_t max_ns_{0};
  double sum_ns_{0.0};
};

}  // namespace rtmot::pipeline
