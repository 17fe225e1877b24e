#include "apps/cli_error.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "common/nearest_name.hpp"

namespace rtmot::app {
namespace {

const CLI::App* find_subcommand(const CLI::App& app, std::string_view word) {
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == word) return sub;
  }
  return nullptr;
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  return names;
}

// Every spelling of every option `app` takes: "--detector-threads", "-h".
void add_flag_names(const CLI::App& app, std::vector<std::string>& names) {
  for (const CLI::Option* option : app.get_options()) {
    for (const auto& name : option->get_lnames()) names.push_back("--" + name);
    for (const auto& name : option->get_snames()) names.push_back("-" + name);
  }
}

// "-5" is a value (a negative number), "-" stdin, "--" the end of the options.
bool looks_like_flag(std::string_view word) {
  if (word.size() < 2 || word[0] != '-' || word == "--") return false;
  const std::string text(word);
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return *end != '\0';
}

std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

std::string parse_error_line(const CLI::App& app, int argc, const char* const* argv,
                             const CLI::ParseError& error) {
  // The subcommand is the first word that names one; global options (with values) may come first.
  const CLI::App* chosen = nullptr;
  for (int i = 1; i < argc && chosen == nullptr; ++i) chosen = find_subcommand(app, argv[i]);
  if (chosen == nullptr && argc > 1 && !looks_like_flag(argv[1])) {
    const std::string hint = did_you_mean(argv[1], subcommand_names(app));
    return std::string("command line: unknown subcommand '") + argv[1] + "'" +
           (hint.empty() ? " (rtmot --help lists them)" : hint);
  }
  std::vector<std::string> flags;
  add_flag_names(app, flags);
  if (chosen != nullptr) add_flag_names(*chosen, flags);
  const std::string command = chosen != nullptr ? "rtmot " + chosen->get_name() : "rtmot";
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    if (word == "--") break;
    if (!looks_like_flag(word)) continue;
    const std::string name(word.substr(0, word.find('=')));
    if (std::find(flags.begin(), flags.end(), name) != flags.end()) continue;
    const std::string hint = did_you_mean(name, flags);
    return "command line: unknown option '" + name + "' for '" + command + "'" +
           (hint.empty() ? " (" + command + " --help lists them)" : hint);
  }
  if (chosen == nullptr) return "command line: a subcommand is required (rtmot --help lists them)";
  std::string message = one_line(error.what());  // CLI11's sentences start with a capital
  if (!message.empty()) message[0] = static_cast<char>(std::tolower(message[0]));
  return "command line: " + message;
}

}  // namespace rtmot::app
