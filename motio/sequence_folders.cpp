#include "motio/sequence_folders.hpp"

#include <algorithm>
#include <map>
#include <system_error>

#include "common/input_error.hpp"

namespace rtmot::motio {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void cannot_read(const fs::path& where, const std::error_code& error) {
  throw InputError(where.string(), 0, "", "cannot read: " + error.message());
}

bool holds_seqinfo(const fs::path& dir) {
  std::error_code error;
  const bool found = fs::exists(dir / "seqinfo.ini", error);
  if (error) cannot_read(dir, error);
  return found;
}

std::vector<fs::path> sequence_dirs(const fs::path& dataset) {
  std::error_code error;
  const bool is_dir = fs::is_directory(dataset, error);
  if (error && error != std::errc::no_such_file_or_directory) cannot_read(dataset, error);
  if (!is_dir) throw InputError(dataset.string(), 0, "", "is not a folder");
  if (holds_seqinfo(dataset)) return {dataset};
  std::vector<fs::path> sequences;
  fs::directory_iterator entries(dataset, error);
  if (error) cannot_read(dataset, error);
  for (const fs::directory_iterator end; entries != end; entries.increment(error)) {
    if (error) cannot_read(dataset, error);
    const fs::path& path = entries->path();
    const bool sub_dir = entries->is_directory(error);
    if (error) cannot_read(path, error);
    if (sub_dir && holds_seqinfo(path)) sequences.push_back(path);
  }
  if (error) cannot_read(dataset, error);
  if (sequences.empty()) {
    throw InputError(dataset.string(), 0, "", "holds no sequence folder (one with a seqinfo.ini)");
  }
  std::sort(sequences.begin(), sequences.end());
  return sequences;
}

}  // namespace

std::vector<SequenceFolder> find_sequences(const fs::path& dataset) {
  std::vector<SequenceFolder> sequences;
  std::map<std::string, fs::path> first_with_name;
  for (const fs::path& dir : sequence_dirs(dataset)) {
    SequenceFolder sequence{dir, read_seqinfo(dir / "seqinfo.ini")};
    const auto [earlier, fresh] = first_with_name.emplace(sequence.info.name, dir);
    if (!fresh) {
      throw InputError((dir / "seqinfo.ini").string(), 0, "name",
                       "'" + sequence.info.name + "' is also the name of " +
                           (earlier->second / "seqinfo.ini").string() +
                           ": their outputs would overwrite each other");
    }
    sequences.push_back(std::move(sequence));
  }
  return sequences;
}

std::vector<fs::path> find_sequence_dirs(const fs::path& dataset) {
  std::vector<fs::path> dirs;
  for (auto& sequence : find_sequences(dataset)) dirs.push_back(std::move(sequence.dir));
  return dirs;
}

fs::path sequence_file(const fs::path& dir, const std::string& name, const std::string& extension) {
  check_sequence_name(name, "", 0);  // names from read_seqinfo() pass; others must too
  return dir / (name + extension);
}

std::vector<NamedFile> sequence_inputs(const std::vector<SequenceFolder>& sequences,
                                       const std::vector<std::string>& per_sequence,
                                       const std::vector<std::filesystem::path>& named_files) {
  std::vector<NamedFile> files;
  for (const auto& sequence : sequences) {
    files.push_back({sequence.dir / "seqinfo.ini", sequence.info.name + "'s seqinfo.ini"});
    for (const auto& relative : per_sequence) {
      files.push_back({sequence.dir / relative, sequence.info.name + "'s " + relative});
    }
    for (const auto& dir : named_files) {
      files.push_back(
          {sequence_file(dir, sequence.info.name, ".txt"), sequence.info.name + "'s results"});
    }
  }
  return files;
}

}  // namespace rtmot::motio
