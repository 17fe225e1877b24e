#include "pipeline/outage_board.hpp"

#include <fmt/format.h>

namespace rtmot::pipeline {
namespace {

double seconds(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-9;
}

}  // namespace

std::optional<std::string> OutageBoard::went_down(std::int64_t now_ns) {
  const int down = down_.fetch_add(1, std::memory_order_acq_rel) + 1;
  if (sources_ < 2 || down != sources_) return std::nullopt;
  all_down_since_ns_.store(now_ns, std::memory_order_relaxed);
  next_line_ns_.store(now_ns + repeat_ns_, std::memory_order_release);
  return fmt::format(
      "all {} sources are down: no pictures to track (each is reopened with backoff; messages "
      "flagged source_outage go on)",
      sources_);
}

std::optional<std::string> OutageBoard::came_back(std::int64_t now_ns) {
  const int before = down_.fetch_sub(1, std::memory_order_acq_rel);
  if (sources_ < 2 || before != sources_) return std::nullopt;
  next_line_ns_.store(kNever, std::memory_order_relaxed);
  const std::int64_t since = all_down_since_ns_.load(std::memory_order_relaxed);
  return fmt::format("a source is back after all {} were down for {:.0f} s", sources_,
                     seconds(now_ns - since));
}

std::optional<std::string> OutageBoard::tick(std::int64_t now_ns) {
  if (sources_ < 2 || down_.load(std::memory_order_relaxed) != sources_) return std::nullopt;
  std::int64_t due = next_line_ns_.load(std::memory_order_acquire);
  if (now_ns < due) return std::nullopt;
  if (!next_line_ns_.compare_exchange_strong(due, now_ns + repeat_ns_, std::memory_order_acq_rel)) {
    return std::nullopt;  // another capture thread printed it
  }
  const std::int64_t since = all_down_since_ns_.load(std::memory_order_relaxed);
  return fmt::format("all {} sources still down after {:.0f} s", sources_, seconds(now_ns - since));
}

}  // namespace rtmot::pipeline
