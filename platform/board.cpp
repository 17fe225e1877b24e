#include "platform/board.hpp"

#include <sys/utsname.h>

#include <array>
#include <cstdio>
#include <memory>
#include <regex>
#include <sstream>
#include <thread>

#include "common/input_error.hpp"
#include "common/input_file.hpp"

namespace rtmot::platform {
namespace {

// Through the one input reader, bounded: a board's description files are a line each; a missing
// or unreadable one means "not this board" ({}).
std::string read_text(const std::filesystem::path& path) {
  constexpr std::uint64_t kMaxDescriptionBytes = 64 * 1024;
  try {
    return read_text_file(path, kMaxDescriptionBytes);
  } catch (const InputError&) {
    return {};
  }
}

// Device-tree strings end in NUL; config files in newlines.
std::string trim(std::string text) {
  const auto last = text.find_last_not_of(std::string(" \t\r\n\0", 5));
  text.erase(last == std::string::npos ? 0 : last + 1);
  const auto first = text.find_first_not_of(" \t\r\n");
  return first == std::string::npos ? std::string() : text.substr(first);
}

std::string first_match(const std::string& text, const std::regex& pattern) {
  std::smatch match;
  return std::regex_search(text, match, pattern) ? match[1].str() : std::string();
}

std::string run_nvpmodel_query() {
  const std::filesystem::path candidates[] = {"/usr/sbin/nvpmodel", "/usr/bin/nvpmodel"};
  for (const auto& program : candidates) {
    std::error_code error;
    if (!std::filesystem::exists(program, error)) continue;
    const std::string command = program.string() + " -q 2>/dev/null";
    const std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
    if (!pipe) return {};
    std::string output;
    std::array<char, 256> chunk{};
    while (fgets(chunk.data(), chunk.size(), pipe.get()) != nullptr) output += chunk.data();
    return parse_nvpmodel_query(output);
  }
  return {};
}

std::string this_machine() {
  utsname name{};
  return uname(&name) == 0 ? std::string(name.machine) : std::string("unknown");
}

// "NVIDIA Jetson Xavier NX Developer Kit" -> "Jetson Xavier NX"
std::string short_model(std::string model) {
  const std::string vendor = "NVIDIA ";
  const std::string suffix = " Developer Kit";
  if (model.rfind(vendor, 0) == 0) model.erase(0, vendor.size());
  if (model.size() > suffix.size() &&
      model.compare(model.size() - suffix.size(), suffix.size(), suffix) == 0) {
    model.erase(model.size() - suffix.size());
  }
  return model;
}

}  // namespace

std::string parse_l4t_release(const std::string& text) {
  static const std::regex release(R"(R(\d+) \(release\), REVISION: ([0-9.]+))");
  std::smatch match;
  if (!std::regex_search(text, match, release)) return {};
  return "R" + match[1].str() + "." + match[2].str();
}

std::string parse_nvpmodel_query(const std::string& output) {
  static const std::regex mode(R"(NV Power Mode:\s*(\S+))");
  return first_match(output, mode);
}

std::string power_mode_from_nvpmodel_files(const std::string& conf, const std::string& status) {
  static const std::regex status_id(R"(pmode:\s*0*(\d+))");
  static const std::regex default_id(R"(<\s*PM_CONFIG\s+DEFAULT=(\d+)\s*>)");
  std::string id = first_match(status, status_id);
  if (id.empty()) id = first_match(conf, default_id);
  if (id.empty()) return {};
  const std::regex model("<\\s*POWER_MODEL\\s+ID=" + id + "\\s+NAME=(\\S+?)\\s*>");
  return first_match(conf, model);
}

int count_cpu_list(const std::string& cpu_list) {
  static const std::regex range(R"((\d+)(?:-(\d+))?)");
  int count = 0;
  for (auto it = std::sregex_iterator(cpu_list.begin(), cpu_list.end(), range);
       it != std::sregex_iterator(); ++it) {
    const int first = std::stoi((*it)[1].str());
    const int last = (*it)[2].matched ? std::stoi((*it)[2].str()) : first;
    if (last >= first) count += last - first + 1;
  }
  return count;
}

BoardInfo detect_board(const std::filesystem::path& root) {
  BoardInfo board;
  board.machine = this_machine();
  board.model = trim(read_text(root / "proc/device-tree/model"));
  const std::string tegra_release = read_text(root / "etc/nv_tegra_release");
  board.l4t_release = parse_l4t_release(tegra_release);
  board.is_jetson = board.model.find("Jetson") != std::string::npos || !trim(tegra_release).empty();

  if (board.is_jetson) {
    if (root == std::filesystem::path("/")) board.power_mode = run_nvpmodel_query();
    if (board.power_mode.empty()) {
      board.power_mode = power_mode_from_nvpmodel_files(
          read_text(root / "etc/nvpmodel.conf"), read_text(root / "var/lib/nvpmodel/status"));
    }
  }

  board.cpu_count = count_cpu_list(trim(read_text(root / "sys/devices/system/cpu/online")));
  if (board.cpu_count == 0) board.cpu_count = static_cast<int>(std::thread::hardware_concurrency());
  return board;
}

std::string describe(const BoardInfo& board) {
  if (!board.is_jetson) {
    std::string line = "not a Jetson: ";
    if (!board.model.empty()) line += board.model + ", ";
    return line + board.machine + ", " + std::to_string(board.cpu_count) + " CPUs";
  }
  std::string line = board.model.empty() ? "Jetson (model unknown)" : short_model(board.model);
  line += " (L4T " + (board.l4t_release.empty() ? std::string("unknown") : board.l4t_release) + ")";
  line += ", power mode " + (board.power_mode.empty() ? std::string("unknown") : board.power_mode);
  return line;
}

}  // namespace rtmot::platform
