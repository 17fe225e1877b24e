#pragma once
// A scratch folder per catalogue case, with helpers that build the bad inputs from real data.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace rtmot::test {

class Workspace {
 public:
  explicit Workspace(const std::string& case_name);
  ~Workspace();
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path path(const std::string& relative) const { return dir_ / relative; }

  /// Writes `text` to `relative`, creating folders.
  void write(const std::string& relative, const std::string& text) const;
  /// Copies a MOT15 training sequence (seqinfo.ini, det, gt) from ../shared to `relative`.
  void copy_sequence(const std::string& name, const std::string& relative) const;
  /// Replaces line `line_number` (1-based) of a file with `text`.
  void replace_line(const std::string& relative, int line_number, const std::string& text) const;
  /// Keeps the first `bytes` bytes of a file.
  void truncate(const std::string& relative, std::uintmax_t bytes) const;

  /// Binds a UDP socket on 127.0.0.1 and keeps it until the workspace ends; returns its port.
  int occupy_udp_port();

 private:
  std::filesystem::path dir_;
  std::vector<int> held_sockets_;
};

std::string read_text(const std::filesystem::path& path);

/// A case's check that `folder` (relative to the workspace; absent is fine) holds no output
/// temporary (`NAME.tmp-PID`, common/output_file.hpp) after the run.
std::function<void(const Workspace&)> no_temporaries(const std::string& folder);

}  // namespace rtmot::test
