#pragma once
// Writing a study out: a table per configuration and input (CSV + Markdown), plots of MOTA, IDF1,
// MOTP and the share of GT tracks not mostly lost against the interval, and a summary page.
#include <filesystem>
#include <string>
#include <vector>

#include "study/study_runner.hpp"

namespace rtmot::study {

/// Columns Rcll Prcn FAR GT MT PT ML FP FN IDs FM MOTA MOTP IDF1 HOTA, a row per interval.
std::string format_study_csv(const StudyTable& table);
std::string format_study_markdown(const StudyTable& table);

/// 100 * (1 - ML / GT): the share of ground-truth tracks that are at least partly tracked.
double not_mostly_lost_percent(const mot::Metrics& metrics);

/// Writes OUT/tables/<input>/<configuration>.{csv,md}, OUT/plots/<input>-<group>-<metric>.svg and
/// OUT/summary.md (every table, links to the plots relative to `link_prefix`). Returns the files.
std::vector<std::filesystem::path> write_study(const std::filesystem::path& out_dir,
                                               const std::vector<StudyTable>& tables,
                                               const std::string& link_prefix = "");

}  // namespace rtmot::study
