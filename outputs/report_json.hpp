#pragma once
// The run's final report (pipeline::PipelineReport) as JSON, for `--report FILE`: serialisation
// lives here, outside pipeline/, so that the pipeline's includers do not get a JSON library.
#include <nlohmann/json.hpp>
#include <string>

#include "pipeline/pipeline_report.hpp"

namespace rtmot::outputs {

/// The JSON report; "streams" (per source) only when there are several. Latency stages are named
/// by pipeline::kStageNames, as the Prometheus metrics name them.
nlohmann::json to_json(const pipeline::PipelineReport& report);
/// Writes to_json(report) to `path` whole or not at all; throws rtmot::InputError if it cannot.
void write_report(const pipeline::PipelineReport& report, const std::string& path);

}  // namespace rtmot::outputs
