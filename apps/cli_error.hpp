#pragma once
// CLI11's parse errors in the project's error format: one line that starts with "command line:",
// names the word it could not use and, for a mistyped flag or subcommand, the nearest valid one.
// CLI11 itself prints two lines ("... not expected: 2 --threads" / "Run with --help ...").
#include <CLI/CLI.hpp>
#include <string>

namespace rtmot::app {

/// The one error line for `error`, raised while `app` parsed argv (not --help or --version).
std::string parse_error_line(const CLI::App& app, int argc, const char* const* argv,
                             const CLI::ParseError& error);

}  // namespace rtmot::app
