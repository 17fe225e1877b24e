#include "outputs/delivery_report.hpp"

#include <fmt/format.h>

namespace rtmot::outputs {

DeliveryReport report_deliveries(const std::vector<OutputProbe>& probes) {
  DeliveryReport report;
  std::size_t empty_outputs = 0;
  for (const OutputProbe& probe : probes) {
    const std::uint64_t sent = probe.sent ? probe.sent() : 0;
    const std::uint64_t dropped = probe.dropped ? probe.dropped() : 0;
    const std::uint64_t attempted = probe.attempted ? probe.attempted() : sent + dropped;
    std::string line = fmt::format("{}: delivered {} of {} messages", probe.name, sent, attempted);
    if (dropped > 0) line += fmt::format(", {} given up", dropped);
    if (attempted > sent + dropped)
      line += fmt::format(", {} still unsent", attempted - sent - dropped);
    if (attempted > 0 && sent == 0) {
      const std::string why = probe.why_nothing ? probe.why_nothing() : std::string();
      line += why.empty() ? ": NOTHING DELIVERED" : ": NOTHING DELIVERED, " + why;
      report.empty.push_back(probe.name);
      ++empty_outputs;
    }
    report.lines.push_back(std::move(line));
  }
  report.nothing_delivered = !probes.empty() && empty_outputs == probes.size();
  return report;
}

}  // namespace rtmot::outputs
