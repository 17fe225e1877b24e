#pragma once
// Outputs never name an input or each other. An output opened (and truncated) before the inputs
// were read destroyed them: `run --jsonl` naming the replayed det file emptied it and tracked
// nothing, `--report` naming the configuration replaced it, two outputs naming one file overwrote
// each other. Every command lists what it reads and what it writes and calls
// check_distinct_files() before anything is opened for writing.
#include <filesystem>
#include <string>
#include <vector>

namespace rtmot {

/// A file a command reads or writes, and where the user named it ("--jsonl", "output.report_file").
struct NamedFile {
  std::filesystem::path path;
  std::string named_by;
};

/// Throws InputError (bad_input) naming both when an output is the same file as an input or as
/// another output: the same device and inode (through symbolic and hard links) for files that
/// exist, the same absolute path with links and `..` resolved for outputs that do not exist yet.
/// Empty paths are skipped (an output not configured).
void check_distinct_files(const std::vector<NamedFile>& inputs,
                          const std::vector<NamedFile>& outputs);

}  // namespace rtmot
