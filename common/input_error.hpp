#pragma once
// The one error type for anything the user hands us (files, configs, URIs, command-line values,
// received messages). It carries where the problem is so the message can name file, line and field,
// and which exit code the program should end with.
#include <stdexcept>
#include <string>

#include "common/exit_codes.hpp"

namespace rtmot {

class InputError : public std::runtime_error {
 public:
  /// `line` is 1-based; 0 means "no line" (e.g. a missing file). `field` may be empty.
  InputError(std::string file, int line, std::string field, const std::string& problem,
             ExitCode code = ExitCode::bad_input)
      : std::runtime_error(format(file, line, field, problem)),
        problem_(problem),
        file_(std::move(file)),
        line_(line),
        field_(std::move(field)),
        code_(code) {}

  /// What is wrong, without where.
  const std::string& problem() const noexcept { return problem_; }
  const std::string& file() const noexcept { return file_; }
  int line() const noexcept { return line_; }
  const std::string& field() const noexcept { return field_; }
  ExitCode exit_code() const noexcept { return code_; }

 private:
  static std::string format(const std::string& file, int line, const std::string& field,
                            const std::string& problem) {
    std::string where = file;
    if (line > 0) where += ":" + std::to_string(line);
    if (!field.empty()) where += ": field '" + field + "'";
    return where.empty() ? problem : where + ": " + problem;
  }

  std::string problem_;
  std::string file_;
  int line_;
  std::string field_;
  ExitCode code_;
};

}  // namespace rtmot
