#pragma once
// Which board are we on? Logged at start-up and written into benchmark reports, because the same
// build runs at very different speeds on a Jetson in 10 W mode, in MAXN mode, and on a PC.
#include <filesystem>
#include <string>

namespace rtmot::platform {

struct BoardInfo {
  bool is_jetson{false};
  std::string model;        // /proc/device-tree/model, e.g. "NVIDIA Jetson Xavier NX Developer Kit"
  std::string l4t_release;  // from /etc/nv_tegra_release, e.g. "R35.4.1"; empty if unknown
  std::string power_mode;   // nvpmodel's mode name, e.g. "MODE_15W_6CORE"; empty if unknown
  int cpu_count{0};         // online CPUs
  std::string machine;      // uname's machine of this process, e.g. "aarch64"
};

/// Reads the board's files under `root` ("/" on a real system; tests pass a fake tree). Only with
/// root "/" is `nvpmodel -q` asked for the power mode; otherwise, and when nvpmodel is not there,
/// /var/lib/nvpmodel/status and /etc/nvpmodel.conf are read. Never throws for missing files.
BoardInfo detect_board(const std::filesystem::path& root = "/");

/// One line, e.g. "Jetson Xavier NX (L4T R35.4.1), power mode MODE_15W_6CORE" or
/// "not a Jetson: x86_64, 2 CPUs".
std::string describe(const BoardInfo& board);

// The parsers, exposed for tests. Each returns an empty string when the text does not say.
/// "# R35 (release), REVISION: 4.1, ..." -> "R35.4.1"
std::string parse_l4t_release(const std::string& nv_tegra_release);
/// `nvpmodel -q` output ("NV Power Mode: MODE_15W_6CORE\n2\n") -> "MODE_15W_6CORE"
std::string parse_nvpmodel_query(const std::string& output);
/// The mode named in nvpmodel.conf for the id in the status file ("pmode:0002 ..."), or the conf's
/// default mode when there is no status.
std::string power_mode_from_nvpmodel_files(const std::string& conf, const std::string& status);
/// "0-3,6" -> 5
int count_cpu_list(const std::string& cpu_list);

}  // namespace rtmot::platform
