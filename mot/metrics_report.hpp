#pragma once
// Presenting an EvaluationReport: the devkit's table, CSV and JSON.
#include <filesystem>
#include <string>

#include "mot/evaluation.hpp"

namespace rtmot::mot {

/// Columns as the devkit prints them, then HOTA DetA AssA LocA; one line per sequence + OVERALL.
std::string format_table(const EvaluationReport& report);
/// Same columns, header `sequence,IDF1,...`, printed precision as in the table.
std::string format_csv(const EvaluationReport& report);
/// Full precision, and the raw counts, for scripts.
std::string format_json(const EvaluationReport& report);

}  // namespace rtmot::mot
