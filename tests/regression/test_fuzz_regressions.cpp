// Inputs the fuzzers (tests/fuzz) found to crash a parser, kept as bytes so they never come back.
// Each must now be refused with rtmot::InputError naming the file and line, never anything else.
#include <gtest/gtest.h>

#include <string>

#include "common/input_error.hpp"
#include "runner/run_config.hpp"

namespace rtmot {
namespace {

// fuzz_run_config, 2026-11-22: a YAML map key that is not a plain scalar (a "? [a]" complex key)
// made Section::find/check_known call as<std::string>() on it: YAML::TypedBadConversion escaped as
// an internal error (exit 1) instead of a bad-input error. Fix: pipeline/run_config.cpp.
TEST(FuzzRegression, RunConfigComplexKeyIsABadInputError) {
  const std::string inputs[] = {
      "? [a]\n: 1\n",                    // at the top level
      "source:\n  ? {uri: x}\n  : 1\n",  // inside a section
  };
  for (const auto& text : inputs) {
    try {
      runner::parse_run_config(text, "fuzz.yaml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& error) {
      EXPECT_EQ(error.exit_code(), ExitCode::bad_input) << error.what();
      EXPECT_EQ(error.file(), "fuzz.yaml");
      EXPECT_GT(error.line(), 0) << error.what();
    } catch (const std::exception& error) {
      ADD_FAILURE() << "escaped as " << typeid(error).name() << ": " << error.what()
                    << "\ninput: " << text;
    }
  }
}

// fuzz_run_config, 2026-11-23: validate() asked stream_id_of() for every source, which kept a
// reference into the temporary vector source_list() returned: a heap use-after-free on any valid
// configuration (ASan; the plain build read freed memory silently). Fix: runner/run_config.cpp.
// fuzz_run_config, 2026-11-25: a stray ',' at the top level made yaml-cpp 0.7's LoadAll() (the
// second-document check) read empty documents without end, memory growing: a hang. Fix:
// runner/yaml_document.cpp counts at most two documents. Each input is refused, in bounded time.
TEST(FuzzRegression, RunConfigStrayCommaIsRefusedNotAnEndlessParse) {
  const std::string inputs[] = {
      ",so:\n  caputre: {cpupriority: 45}\n  sink: {cpu: -1}\ndete.tor:\n  kin$: replay\n",
      ",",
      ",\nsource:\n  uri: test://ball\n",
  };
  for (const auto& text : inputs) {
    try {
      runner::parse_run_config(text, "fuzz.yaml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& error) {
      EXPECT_EQ(error.exit_code(), ExitCode::bad_input) << error.what();
      EXPECT_EQ(error.file(), "fuzz.yaml");
    } catch (const std::exception& error) {
      ADD_FAILURE() << "escaped as " << typeid(error).name() << ": " << error.what();
    }
  }
}

TEST(FuzzRegression, StreamIdsOfAValidConfigurationReadNoFreedMemory) {
  const std::string text =
      "source:\n  uri: test://ball\ndetector:\n  kind: ssd\n  model: models/x.onnx\n"
      "stream_id: 7\n";
  const auto config = runner::parse_run_config(text, "fuzz.yaml");
  runner::validate(config);
  EXPECT_EQ(runner::stream_id_of(config, 0), 7U);
  const auto two = runner::parse_run_config(
      "sources:\n  - test://ball\n  - {uri: test://snow, stream_id: 42}\ndetector:\n  kind: ssd\n"
      "  model: models/x.onnx\nstream_id: 7\n",
      "fuzz.yaml");
  runner::validate(two);
  EXPECT_EQ(runner::stream_id_of(two, 0), 7U);
  EXPECT_EQ(runner::stream_id_of(two, 1), 42U);
}

}  // namespace
}  // namespace rtmot
