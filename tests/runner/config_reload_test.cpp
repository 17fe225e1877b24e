// SIGHUP's re-read and the page's settings (runner/config_reloader.hpp, settings_editor.hpp,
// config_document.hpp, events_editor.hpp): what is applied live, what is refused, what is written.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "runner/config_reloader.hpp"
#include "scratch_folder.hpp"

namespace rtmot::runner {
namespace {

void write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

std::string config_text(const std::string& events, const std::string& model = "model.onnx",
                        const std::string& score = "0.3") {
  return "source:\n  uri: video.avi\n  events:\n    " + events + "\ndetector:\n  model: " + model +
         "\n  score_threshold: " + score + "\n";
}

const std::string kDoor = "lines: [{name: door, from: [380, 0], to: [380, 576]}]";
const std::string kHall = "lines: [{name: hall, from: [400, 0], to: [400, 576], in: right}]";

TEST(SettingsNeedingRestart, NamesWhatChangedButTheLiveSettings) {
  const YAML::Node before = YAML::Load(config_text(kDoor));
  EXPECT_TRUE(settings_needing_restart(before, YAML::Load(config_text(kHall, "model.onnx", "0.6")))
                  .empty());
  EXPECT_EQ(settings_needing_restart(before, YAML::Load(config_text(kDoor, "other.onnx"))),
            std::vector<std::string>{"detector.model"});
  const YAML::Node added = YAML::Load(config_text(kDoor) + "tracker: {preset: sort}\n");
  EXPECT_EQ(settings_needing_restart(before, added), std::vector<std::string>{"tracker"});
  const YAML::Node listed_before = YAML::Load("sources: [{uri: a, events: {}}, {uri: b}]\n");
  const YAML::Node listed_after =
      YAML::Load("sources: [{uri: a, events: {lines: []}}, {uri: c}]\n");
  EXPECT_EQ(settings_needing_restart(listed_before, listed_after),
            std::vector<std::string>{"sources[1].uri"});
}

struct Fixture {
  test::ScratchFolder folder{"reload"};
  std::filesystem::path file = folder.path() / "run.yaml";
  pipeline::EventsMailbox mailbox;
  pipeline::ScoreCut cut{0.3F};
  std::unique_ptr<ConfigDocument> document;
  std::unique_ptr<EventsEditor> events;
  std::unique_ptr<SettingsEditor> settings;
  CLI::App app;
  RunFlags flags;
  std::unique_ptr<ConfigReloader> reloader;

  explicit Fixture(const std::string& save_to = "") {
    flags.add_to(app);
    app.parse(std::string(), false);  // no flags: the file alone
    write(file, config_text(kDoor));
    document = std::make_unique<ConfigDocument>(file.string(), save_to);
    events::EventsConfig running;
    running.lines.push_back({"door", {{380, 0}, {380, 576}}, true});
    events = std::make_unique<EventsEditor>(
        std::vector<EventsEditor::Source>{{0, "video.avi", 768, 576, running, &mailbox, nullptr}},
        nullptr, *document, false);
    settings = std::make_unique<SettingsEditor>(cut, *document);
    reloader =
        std::make_unique<ConfigReloader>(file.string(), flags, *events, *settings, cut, *document);
  }
};

TEST(ConfigReloader, AnUnchangedFileAppliesNothing) {
  Fixture f;
  f.reloader->reload();
  EXPECT_EQ(f.mailbox.take(), nullptr);
  EXPECT_FLOAT_EQ(f.cut.get(), 0.3F);
}

TEST(ConfigReloader, NewEventsAndScoreAreApplied) {
  Fixture f;
  write(f.file, config_text(kHall, "model.onnx", "0.5"));
  f.reloader->reload();
  const pipeline::PostedEvents* posted = f.mailbox.take();
  ASSERT_NE(posted, nullptr);
  EXPECT_EQ(posted->generation, 1U);
  ASSERT_EQ(posted->config.lines.size(), 1U);
  EXPECT_EQ(posted->config.lines[0].name, "hall");
  EXPECT_FLOAT_EQ(f.cut.get(), 0.5F);
  // Read again: the same, so nothing restarts.
  f.reloader->reload();
  EXPECT_EQ(f.mailbox.take(), nullptr);
}

TEST(ConfigReloader, ABrokenFileKeepsTheRunningConfiguration) {
  Fixture f;
  write(f.file,
        config_text("zones: [{name: bow, points: [[0, 0], [100, 100], [100, 0], [0, 100]]}]",
                    "model.onnx", "0.5"));
  f.reloader->reload();
  EXPECT_EQ(f.mailbox.take(), nullptr);
  EXPECT_FLOAT_EQ(f.cut.get(), 0.3F);  // the valid part of a broken file is not applied either
  write(f.file, "source: [\n");        // not YAML
  f.reloader->reload();
  EXPECT_EQ(f.mailbox.take(), nullptr);
}

TEST(ConfigReloader, ARestartOnlyChangeAppliesNothingAndALowerCutIsRefused) {
  Fixture f;
  write(f.file, config_text(kDoor, "other.onnx", "0.1"));
  f.reloader->reload();
  EXPECT_EQ(f.mailbox.take(), nullptr);
  EXPECT_FLOAT_EQ(f.cut.get(), 0.3F);
}

TEST(SettingsEditor, RefusesBadValuesAndUnknownSettingsAndWritesNothing) {
  Fixture f;
  const std::string before = read_text_file(f.file);
  for (const std::string body :
       {"{\"score_threshold\": 1.5}", "{\"score_threshold\": 0}", "{\"score_threshold\": 0.1}",
        "{\"score_threshold\": \"x\"}", "{\"score_threshold\": [1]}", "{\"nms_threshold\": 0.5}",
        "{\"colour\": 1}", "[1]", "{", "{\"score_threshold\": 0.6, \"tracker.max_age\": 3}"}) {
    const outputs::SaveAnswer answer = f.settings->save(body);
    EXPECT_EQ(answer.status, 400) << body;
    EXPECT_TRUE(answer.body.contains("field")) << body;
  }
  EXPECT_EQ(f.settings->save("{\"nms_threshold\": 0.5}")
                .body["problem"]
                .get<std::string>()
                .find("needs a restart"),
            0U);
  EXPECT_EQ(f.settings->save("{\"score_threshold\": 1.5}").body["field"], "score_threshold");
  EXPECT_FLOAT_EQ(f.cut.get(), 0.3F);
  EXPECT_EQ(read_text_file(f.file), before);
}

TEST(SettingsEditor, AValidCutIsAppliedAndWrittenToTheFile) {
  Fixture f;
  const outputs::SaveAnswer answer = f.settings->save("{\"score_threshold\": 0.6}");
  EXPECT_EQ(answer.status, 200) << answer.body.dump();
  EXPECT_FLOAT_EQ(f.cut.get(), 0.6F);
  EXPECT_FLOAT_EQ(f.settings->current()["score_threshold"].get<float>(), 0.6F);
  const RunConfig saved = parse_run_config(read_text_file(f.file), f.file.string());
  EXPECT_FLOAT_EQ(saved.detector.score_threshold, 0.6F);
  EXPECT_EQ(saved.source.events.written.lines.size(), 1U);  // the rest of the file kept
}

TEST(SettingsEditor, SavesGoToTheFileNamedAndTheConfigurationStays) {
  test::ScratchFolder other("reload-to");
  const std::filesystem::path save_to = other.path() / "saved.yaml";
  Fixture f(save_to.string());
  const std::string before = read_text_file(f.file);
  ASSERT_EQ(f.settings->save("{\"score_threshold\": 0.6}").status, 200);
  ASSERT_EQ(f.events->save(0, kHall).status, 200);
  EXPECT_EQ(read_text_file(f.file), before);
  const RunConfig saved = parse_run_config(read_text_file(save_to), save_to.string());
  EXPECT_FLOAT_EQ(saved.detector.score_threshold, 0.6F);  // both saves, in one whole file
  ASSERT_EQ(saved.source.events.written.lines.size(), 1U);
  EXPECT_EQ(saved.source.uri, "video.avi");
}

TEST(SettingsEditor, AFileThatCannotBeWrittenAppliesNothing) {
  Fixture f((std::filesystem::path("/proc/no-such-folder") / "saved.yaml").string());
  const outputs::SaveAnswer answer = f.settings->save("{\"score_threshold\": 0.6}");
  EXPECT_EQ(answer.status, 500);
  EXPECT_FLOAT_EQ(f.cut.get(), 0.3F);
  EXPECT_EQ(f.events->save(0, kHall).status, 500);
  EXPECT_EQ(f.mailbox.take(), nullptr);
}

TEST(ConfigReloader, WithoutAFileNothingIsRead) {
  Fixture f;
  ConfigReloader nothing("", f.flags, *f.events, *f.settings, f.cut, *f.document);
  nothing.reload();
  EXPECT_EQ(f.mailbox.take(), nullptr);
}

TEST(WebSaveTo, NeedsAConfigurationFileToCopy) {
  RunConfig config = default_run_config();
  config.source.uri = "video.avi";
  config.output.web_save_to = "saved.yaml";
  try {
    validate(config);
    FAIL() << "--web-save-to without --config was accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "output.web_save_to");
    EXPECT_EQ(error.exit_code(), ExitCode::bad_input);
  }
  config.file = config.loaded_from = "run.yaml";  // as load_run_config sets them
  EXPECT_NO_THROW(validate(config));
}

}  // namespace
}  // namespace rtmot::runner
