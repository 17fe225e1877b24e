// Issue 22: a mistyped flag, subcommand or configuration key is answered in one line of the error
// format (CLI11 printed two lines of its own), exit 2 for the command line and 3 for a file, and
// names the nearest valid name when one is close (common/nearest_name.hpp). Each case checks the
// whole line.
#include <gtest/gtest.h>

#include <filesystem>

#include "catalogue.hpp"

namespace rtmot::test {
namespace {

namespace fs = std::filesystem;

CatalogueCase usage_case(std::string name, std::string what, std::vector<std::string> args,
                         std::string message) {
  CatalogueCase c{std::move(name), std::move(what), [](Workspace&, Vars&) {},
                  std::move(args), ExitCode::usage, {}};
  c.message = std::move(message);
  return c;
}

// A run configuration with one mistyped key (`yaml`), its error line and what must be left alone.
CatalogueCase key_case(std::string name, std::string what, const std::string& yaml,
                       std::string message) {
  CatalogueCase c{std::move(name),
                  std::move(what),
                  [yaml](Workspace& ws, Vars&) { ws.write("run.yaml", yaml); },
                  {"run", "--config", "{dir}/run.yaml", "--jsonl", "{dir}/out/t.jsonl"},
                  ExitCode::bad_input,
                  {},
                  [](const Workspace& ws) {
                    EXPECT_FALSE(fs::exists(ws.path("out"))) << "an output was created";
                  }};
  c.message = std::move(message);
  return c;
}

const std::string kSource = "source:\n  uri: test://ball?num-buffers=5\n";

// --input-loop on a camera: a live source does not end, refused before anything opens.
CatalogueCase loop_live_case() {
  CatalogueCase c{"input_loop_of_a_live_source",
                  "--input-loop 2 on rtsp:// (a live source never ends)",
                  [](Workspace&, Vars&) {},
                  {"run", "--source", "rtsp://127.0.0.1:9/cam", "--input-loop", "2", "--jsonl",
                   "{dir}/out/t.jsonl"},
                  ExitCode::bad_input,
                  {},
                  [](const Workspace& ws) {
                    EXPECT_FALSE(fs::exists(ws.path("out"))) << "an output was created";
                  }};
  c.message =
      "(command line): field 'source.loop': loops a file, not 'rtsp://127.0.0.1:9/cam' (a live "
      "source or a mot-seq:// sequence)";
  return c;
}

// An encoder of the other codec: refused before the model loads and before any output exists.
CatalogueCase encoder_case() {
  CatalogueCase c{"video_encoder_of_another_codec",
                  "--video-codec h265 --video-encoder openh264enc (an H.264 encoder)",
                  [](Workspace&, Vars&) {},
                  {"run", "--source", "test://ball?num-buffers=5", "--video-codec", "h265",
                   "--video-encoder", "openh264enc", "--video-out", "{dir}/out/v.mp4"},
                  ExitCode::bad_input,
                  {},
                  [](const Workspace& ws) {
                    EXPECT_FALSE(fs::exists(ws.path("out"))) << "an output was created";
                  }};
  c.message =
      "{dir}/out/v.mp4: field 'output.video_encoder': openh264enc encodes H.264, not H.265 "
      "(output.video_codec, --video-codec)";
  return c;
}

}  // namespace

std::vector<CatalogueCase> usage_cases() {
  return {
      usage_case("usage_flag_part_of_a_name",
                 "rtmot run --threads 2 (the flag is --detector-threads)",
                 {"run", "--threads", "2"},
                 "command line: unknown option '--threads' for 'rtmot run' (did you mean "
                 "--detector-threads?)"),
      usage_case("usage_flag_misspelt_with_value", "rtmot listen --prot=5 (a typo of --port)",
                 {"listen", "--prot=5"},
                 "command line: unknown option '--prot' for 'rtmot listen' (did you mean --port?)"),
      usage_case("usage_global_flag_misspelt", "rtmot --log-levl debug run",
                 {"--log-levl", "debug", "run"},
                 "command line: unknown option '--log-levl' for 'rtmot run' (did you mean "
                 "--log-level?)"),
      usage_case("usage_flag_far_from_any", "rtmot run --zzzzzz (nothing close: no guess)",
                 {"run", "--zzzzzz"},
                 "command line: unknown option '--zzzzzz' for 'rtmot run' (rtmot run --help "
                 "lists them)"),
      usage_case("usage_track_frame_rate",
                 "rtmot track --frame-rate 25 (each sequence's seqinfo.ini sets it; the flag "
                 "changed nothing)",
                 {"track", "--dataset", "{dir}", "--out", "{dir}/out", "--frame-rate", "25"},
                 "command line: field '--frame-rate': rtmot track takes it from each sequence's "
                 "seqinfo.ini"),
      usage_case("usage_flag_without_value", "rtmot run --detector-threads (value missing)",
                 {"run", "--detector-threads"},
                 "command line: --detector-threads: 1 required TEXT missing"),
      usage_case("usage_subcommand_misspelt", "rtmot rn", {"rn"},
                 "command line: unknown subcommand 'rn' (did you mean run?)"),
      usage_case("usage_no_subcommand", "rtmot with nothing", {},
                 "command line: a subcommand is required (rtmot --help lists them)"),
      usage_case("usage_stray_argument", "rtmot run foo", {"run", "foo"},
                 "command line: the following argument was not expected: foo"),
      key_case("config_key_misspelt", "detector.score_treshold: 0.5 (a typo)",
               kSource + "detector:\n  score_treshold: 0.5\n",
               "{dir}/run.yaml:4: field 'detector.score_treshold': unknown key (did you mean "
               "score_threshold?)"),
      key_case("config_section_misspelt", "traker: (a typo of tracker)",
               kSource + "traker:\n  max_age: 3\n",
               "{dir}/run.yaml:3: field 'traker': unknown key (did you mean tracker?)"),
      key_case("config_tracker_key_misspelt",
               "tracker.max_ag (a typo, read by the tracker's table)",
               kSource + "tracker:\n  max_ag: 3\n",
               "{dir}/run.yaml:4: field 'tracker.max_ag': unknown key (did you mean max_age?)"),
      // The video's encoding (issue 22): a jetson-inference user's --bitrate in bit/s is refused,
      // not taken as 4 Gbit/s; an encoder name is checked with the nearest valid one.
      usage_case("usage_bitrate_in_bits_per_second",
                 "rtmot run --bitrate 4000000 (the flag is in kbit/s)",
                 {"run", "--bitrate", "4000000"},
                 "command line: field '--bitrate': '4000000': expected an integer in [64, 200000]"),
      key_case("config_video_encoder_misspelt", "output.video_encoder: openh264enk (a typo)",
               kSource + "output:\n  video_encoder: openh264enk\n",
               "{dir}/run.yaml:4: field 'output.video_encoder': 'openh264enk': expected auto, "
               "hardware, software or an encoder element (nvv4l2h264enc, v4l2h264enc, x264enc, "
               "openh264enc, nvv4l2h265enc, v4l2h265enc, x265enc) (did you mean openh264enc?)"),
      encoder_case(),
      // The source options of jetson-inference (issue 22): checked names, files only for loops.
      usage_case("usage_input_flip_unknown", "rtmot run --input-flip sideways",
                 {"run", "--input-flip", "sideways"},
                 "command line: field '--input-flip': 'sideways': expected none, clockwise, "
                 "rotate-180, counterclockwise, horizontal, vertical, upper-left-diagonal or "
                 "upper-right-diagonal"),
      loop_live_case(),
      key_case("config_key_far_from_any", "detector.zzzzzz (nothing close: no guess)",
               kSource + "detector:\n  zzzzzz: 1\n",
               "{dir}/run.yaml:4: field 'detector.zzzzzz': unknown key"),
  };
}

}  // namespace rtmot::test
