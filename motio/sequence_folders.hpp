#pragma once
// Finding a dataset's sequences, and the files named after them. A sequence's name comes from its
// seqinfo.ini, i.e. from the input: read_seqinfo() accepts only plain names, and two sequences
// with one name are an error, so every output named after a sequence stays in its folder and
// none overwrites another.
#include <filesystem>
#include <string>
#include <vector>

#include "common/distinct_files.hpp"
#include "motio/mot_files.hpp"

namespace rtmot::motio {

struct SequenceFolder {
  std::filesystem::path dir;
  SequenceInfo info;
};

/// `dataset` itself if it holds a seqinfo.ini, else its sub-folders that do (sorted by name).
/// Throws InputError if there is none, if a folder cannot be read, or if two sequences share a
/// name.
std::vector<SequenceFolder> find_sequences(const std::filesystem::path& dataset);
/// The folders only (same rules).
std::vector<std::filesystem::path> find_sequence_dirs(const std::filesystem::path& dataset);

/// `dir`/`name``extension` for a sequence name read_seqinfo() accepted: inside `dir`.
std::filesystem::path sequence_file(const std::filesystem::path& dir, const std::string& name,
                                    const std::string& extension);

/// The files a command reads from each sequence: its seqinfo.ini and each of `per_sequence`
/// (relative to the sequence folder, e.g. "det/det.txt", "gt/gt.txt"), and `dir`/NAME.txt for
/// each of `named_files` (e.g. eval's results folder); for check_distinct_files().
std::vector<NamedFile> sequence_inputs(const std::vector<SequenceFolder>& sequences,
                                       const std::vector<std::string>& per_sequence,
                                       const std::vector<std::filesystem::path>& named_files = {});

}  // namespace rtmot::motio
