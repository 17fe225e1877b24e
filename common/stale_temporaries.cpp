#include "common/stale_temporaries.hpp"

#include <signal.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <string>
#include <string_view>
#include <system_error>

namespace rtmot {
namespace {

constexpr std::string_view kSuffix = ".tmp-";

// The PID in `name` if it is `stem` + ".tmp-" + digits, else 0.
pid_t writer_of(std::string_view name, std::string_view stem) {
  if (name.size() <= stem.size() + kSuffix.size() || name.substr(0, stem.size()) != stem ||
      name.substr(stem.size(), kSuffix.size()) != kSuffix) {
    return 0;
  }
  const std::string_view digits = name.substr(stem.size() + kSuffix.size());
  pid_t pid = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
  if (error != std::errc{} || end != digits.data() + digits.size() || pid <= 0) return 0;
  return pid;
}

// EPERM: a process of another user runs under that PID, which is alive for our purpose.
bool runs(pid_t pid) {
  return ::kill(pid, 0) == 0 || errno != ESRCH;
}

}  // namespace

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  return std::filesystem::path(path.string() + std::string(kSuffix) + std::to_string(::getpid()));
}

std::size_t remove_stale_temporaries(const std::filesystem::path& path) {
  const std::string stem = path.filename().string();
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
  std::error_code error;
  std::filesystem::directory_iterator entries(folder, error);
  std::size_t removed = 0;
  for (; !error && entries != std::filesystem::directory_iterator(); entries.increment(error)) {
    const std::filesystem::path candidate = entries->path();
    const pid_t writer = writer_of(candidate.filename().string(), stem);
    if (writer == 0 || writer == ::getpid() || runs(writer)) continue;
    std::error_code ignored;
    // A link is removed, never followed (remove() unlinks the name): a dangling or planted one
    // too. A folder under that name is nobody's temporary: left alone.
    const auto kind = entries->symlink_status(ignored).type();
    if ((kind != std::filesystem::file_type::regular &&
         kind != std::filesystem::file_type::symlink) ||
        !std::filesystem::remove(candidate, ignored)) {
      continue;
    }
    spdlog::warn("{}: removed {}, the unfinished output of process {}, which no longer runs",
                 path.string(), candidate.string(), writer);
    ++removed;
  }
  return removed;
}

}  // namespace rtmot
