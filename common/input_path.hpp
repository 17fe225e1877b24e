#pragma once
// Where a relative input path is looked for. A path in a configuration file is relative to the
// file's folder (DeepStream's convention: a config and what it names travel together, whatever
// the working directory); the working directory and the installed data folder
// (<prefix>/share/rtmot, found from the running binary) follow, so a command-line default and an
// installed rtmot find the installed model and configs. Outputs are not resolved here: they are
// written relative to the working directory (a service's state directory).
#include <filesystem>
#include <string>
#include <vector>

namespace rtmot {

/// <prefix>/share/rtmot for the binary that runs (/proc/self/exe/../../share/rtmot); empty if
/// the binary's path cannot be read.
std::filesystem::path installed_data_dir();

/// The candidates for `value`, in the order they are tried: `value` itself if absolute; else
/// `base_dir`/value (when `base_dir` is not empty), value (the working directory), then
/// installed_data_dir()/value and installed_data_dir()/`installed_subdir`/filename.
std::vector<std::filesystem::path> input_path_candidates(const std::string& value,
                                                         const std::filesystem::path& base_dir,
                                                         const std::string& installed_subdir = {});

/// The first candidate that exists; if none does, `value` unchanged (the reader then fails on
/// it) and `tried` lists every candidate, for the error.
std::string resolve_input_path(const std::string& value, const std::filesystem::path& base_dir,
                               const std::string& installed_subdir, std::string& tried);

}  // namespace rtmot
