#pragma once
// The final report's word on each network output: how many messages it delivered of those it was
// handed. A run that tracked but whose outputs delivered nothing (an MQTT broker never reached)
// used to end with exit 0 and no word about it.
#include <string>
#include <vector>

#include "outputs/pipeline_metrics.hpp"

namespace rtmot::outputs {

struct DeliveryReport {
  std::vector<std::string> lines;  // one per output: "mqtt: delivered 0 of 120 messages (...)"
  std::vector<std::string> empty;  // the outputs that were handed messages and delivered none
  bool nothing_delivered{false};   // every output was handed messages and delivered none
};

/// Reads every probe (after the run: the outputs are flushed). No probes: an empty report.
DeliveryReport report_deliveries(const std::vector<OutputProbe>& probes);

}  // namespace rtmot::outputs
