#include "pipeline/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace rtmot::pipeline {
namespace {
constexpr double first_edge_ns = 1000.0;  // bucket 0 holds everything up to 1 us
constexpr double growth = 1.02;
const double log_growth = std::log(growth);
}  // namespace

int LatencyHistogram::bucket_of(std::int64_t nanoseconds) {
  if (nanoseconds <= first_edge_ns) return 0;
  const double steps = std::log(static_cast<double>(nanoseconds) / first_edge_ns) / log_growth;
  return std::min(bucket_count - 1, 1 + static_cast<int>(steps));
}

std::int64_t LatencyHistogram::upper_edge_ns(int bucket) {
  return static_cast<std::int64_t>(std::ceil(first_edge_ns * std::pow(growth, bucket)));
}

void LatencyHistogram::record(std::int64_t nanoseconds) {
  nanoseconds = std::max<std::int64_t>(0, nanoseconds);
  ++buckets_[static_cast<std::size_t>(bucket_of(nanoseconds))];
  ++count_;
  sum_ns_ += static_cast<double>(nanoseconds);
  max_ns_ = std::max(max_ns_, nanoseconds);
}

void LatencyHistogram::clear() {
  *this = LatencyHistogram{};
}

std::int64_t LatencyHistogram::quantile_ns(double q) const {
  if (count_ == 0) return 0;
  // The rank of the q-quantile among the sorted samples (nearest-rank definition).
  const auto rank = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::ceil(q * static_cast<double>(count_))));
  std::int64_t seen = 0;
  for (int bucket = 0; bucket < bucket_count; ++bucket) {
    seen += buckets_[static_cast<std::size_t>(bucket)];
    if (seen >= rank) return std::min(upper_edge_ns(bucket), max_ns_);
  }
  return max_ns_;
}

}  // namespace rtmot::pipeline
