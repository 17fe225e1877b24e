// docs/config.md's tracker table is the tracker options' table (tracker/tracker_options.cpp: name,
// doc, accepted values) with each option's value in the configuration `rtmot run` and `rtmot
// track` start from (the default preset, tracker/presets.cpp), so that it cannot drift from them.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "docs_table.hpp"
#include "runner/run_config.hpp"
#include "runner/run_setup.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker_options.hpp"

namespace rtmot::runner {
namespace {

std::string code(const std::string& text) {
  return "`" + text + "`";
}

// Each option's default: its value in the configuration a run starts from (no tracker section),
// shown as its setter reads it. A value the run leaves to the source (the default preset's is
// replaced at start, unless the file sets it) says so, with what a source without one gives.
std::string default_text(const tracker::TrackerOption& option) {
  const tracker::TrackerConfig preset = *tracker::find_preset(tracker::default_preset_name());
  const RunConfig run = parse_run_config("tracker: {}\n", "defaults.yaml");
  if (option.show(run.tracker) == option.show(preset)) return code(option.show(run.tracker));
  platform::SourceInfo source;
  source.fps = 12.5;
  source.width = 640;
  source.height = 360;
  const tracker::TrackerConfig from_source = complete_tracker_config(run, source);
  const tracker::TrackerConfig without = complete_tracker_config(run, platform::SourceInfo{});
  EXPECT_NE(option.show(from_source), option.show(without))
      << option.name << ": neither the default preset's value nor the source's";
  return "the source's (without one: " + code(option.show(without)) + ")";
}

std::string markdown_table() {
  std::ostringstream text;
  text << "| key | default (preset " << code(std::string(tracker::default_preset_name()))
       << ") | accepted | meaning |\n| --- | --- | --- | --- |\n";
  text << "| `preset` | " << code(std::string(tracker::default_preset_name())) << " | "
       << tracker::preset_names()
       << " | the starting configuration, applied first: every other key overrides it, whatever "
          "the order in the file |\n";
  for (const auto& option : tracker::tracker_options()) {
    text << "| " << code(option.name) << " | " << default_text(option) << " | "
         << test::markdown_cell(option.expected) << " | " << test::markdown_cell(option.doc)
         << " |\n";
  }
  return text.str();
}

constexpr const char* kBegin =
    "<!-- tracker-table: generated from tracker/tracker_options.cpp and tracker/presets.cpp by "
    "tests/runner/tracker_docs_test.cpp (RTMOT_UPDATE_DOCS=1 rewrites it) -->\n";
constexpr const char* kEnd = "<!-- end tracker-table -->\n";

TEST(TrackerDocs, DocsShowTheTableAsItIs) {
  const test::DocsText docs = test::check_generated_table(test::source_path("docs/config.md"),
                                                          kBegin, kEnd, markdown_table());
  EXPECT_TRUE(docs.found);
}

// Each documented default, written in a file's tracker section, is the value a run starts with
// (`none` included); only the source's rate and size are left to the source.
TEST(TrackerDocs, DocumentedDefaultsReadBackUnchanged) {
  const RunConfig run = parse_run_config("tracker: {}\n", "defaults.yaml");
  const tracker::TrackerConfig preset = *tracker::find_preset(tracker::default_preset_name());
  int from_source = 0;
  for (const auto& option : tracker::tracker_options()) {
    SCOPED_TRACE(option.name);
    const std::string shown = default_text(option);
    if (shown.rfind("the source's", 0) == 0) {
      ++from_source;
      continue;
    }
    // Writing the documented default in the file, as the docs spell it, changes nothing.
    const RunConfig set = parse_run_config(
        "tracker:\n  " + option.name + ": " + option.show(preset) + "\n", "set.yaml");
    EXPECT_EQ(option.show(set.tracker), option.show(run.tracker));
  }
  EXPECT_EQ(from_source, 3) << "frame_rate, image_width and image_height";
}

}  // namespace
}  // namespace rtmot::runner
