#include "common/input_path.hpp"

#include <system_error>

namespace rtmot {

std::filesystem::path installed_data_dir() {
  std::error_code error;
  const auto binary = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error || binary.empty()) return {};
  return binary.parent_path().parent_path() / "share" / "rtmot";
}

std::vector<std::filesystem::path> input_path_candidates(const std::string& value,
                                                         const std::filesystem::path& base_dir,
                                                         const std::string& installed_subdir) {
  const std::filesystem::path path(value);
  if (value.empty() || path.is_absolute()) return {path};
  std::vector<std::filesystem::path> candidates;
  const auto add = [&](const std::filesystem::path& candidate) {
    const auto normal = candidate.lexically_normal();
    for (const auto& seen : candidates) {
      if (seen == normal) return;
    }
    candidates.push_back(normal);
  };
  if (!base_dir.empty()) add(base_dir / path);
  add(path);
  const auto data = installed_data_dir();
  if (!data.empty()) {
    add(data / path);
    if (!installed_subdir.empty()) add(data / installed_subdir / path.filename());
  }
  return candidates;
}

std::string resolve_input_path(const std::string& value, const std::filesystem::path& base_dir,
                               const std::string& installed_subdir, std::string& tried) {
  tried.clear();
  for (const auto& candidate : input_path_candidates(value, base_dir, installed_subdir)) {
    std::error_code error;
    if (std::filesystem::exists(candidate, error)) return candidate.string();
    tried += (tried.empty() ? "" : ", ") + candidate.string();
  }
  return value;
}

}  // namespace rtmot
