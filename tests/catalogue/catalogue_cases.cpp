// The table. Each case starts from real data (../shared) and breaks one thing.
#include <gtest/gtest.h>

#include "catalogue.hpp"
#include "shared_data.hpp"

namespace rtmot::test {

namespace {

constexpr const char* seq = "TUD-Campus";  // 71 frames: quick to track
constexpr const char* seq2 = "TUD-Stadtmitte";

// A sequence at {dir}/data/TUD-Campus whose file `relative` has line `line` replaced by `text`.
std::function<void(Workspace&, Vars&)> sequence_with_line(const std::string& relative, int line,
                                                          const std::string& text) {
  return [=](Workspace& ws, Vars&) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    ws.replace_line("data/TUD-Campus/" + relative, line, text);
  };
}

std::function<void(Workspace&, Vars&)> sequence_with_file(const std::string& relative,
                                                          const std::string& text) {
  return [=](Workspace& ws, Vars&) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    ws.write("data/TUD-Campus/" + relative, text);
  };
}

const std::vector<std::string> track_a = {"track", "--dataset", "{dir}/data", "--out", "{dir}/out"};

// A run configuration that is valid apart from what the case changes (`{model}` is the real model).
std::string run_config(const std::string& source, const std::string& extra = "") {
  return "source:\n  uri: " + source + "\ndetector:\n  kind: replay\n  det_file: {det}\n" + extra;
}

std::function<void(Workspace&, Vars&)> config_file(const std::string& text) {
  return [=](Workspace& ws, Vars& vars) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    std::string filled = text;
    const std::string det = ws.path("data/TUD-Campus/det/det.txt").string();
    for (auto at = filled.find("{det}"); at != std::string::npos; at = filled.find("{det}"))
      filled.replace(at, 5, det);
    ws.write("run.yaml", filled);
    vars["config"] = ws.path("run.yaml").string();
  };
}

const std::vector<std::string> run_yaml = {"run", "--config", "{dir}/run.yaml"};

// The first sequence's results must be whole: one line per reported track and frame, all numeric.
void first_results_complete(const Workspace& ws) {
  const auto results = ws.path("out/TUD-Campus.txt");
  ASSERT_TRUE(std::filesystem::exists(results)) << results;
  const std::string text = read_text(results);
  ASSERT_FALSE(text.empty()) << results;
  EXPECT_EQ(text.back(), '\n') << "last line cut short: " << results;
}

}  // namespace

std::vector<CatalogueCase> first_round();

const std::vector<CatalogueCase>& catalogue() {
  static const std::vector<CatalogueCase> cases = [] {
    std::vector<CatalogueCase> all = first_round();
    for (auto& c : hostile_cases()) all.push_back(std::move(c));
    for (auto& c : round_three_cases()) all.push_back(std::move(c));
    for (auto& c : settings_cases()) all.push_back(std::move(c));
    for (auto& c : round_four_files_cases()) all.push_back(std::move(c));
    for (auto& c : detector_file_cases()) all.push_back(std::move(c));
    for (auto& c : usage_cases()) all.push_back(std::move(c));
    for (auto& c : round_four_streams_cases()) all.push_back(std::move(c));
    return all;
  }();
  return cases;
}

std::vector<CatalogueCase> first_round() {
  return {
      // ---- MOTChallenge sequences: `rtmot track` -------------------------------------------
      {"track_missing_sequence_folder",
       "sequence folder does not exist",
       [](Workspace&, Vars&) {},
       track_a,
       ExitCode::bad_input,
       {"data"}},
      {"track_missing_seqinfo",
       "seqinfo.ini missing",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         std::filesystem::remove(ws.path("data/TUD-Campus/seqinfo.ini"));
       },
       {"track", "--dataset", "{dir}/data/TUD-Campus", "--out", "{dir}/out"},
       ExitCode::bad_input,
       {"TUD-Campus"}},
      {"track_seqinfo_zero_frame_rate",
       "seqinfo.ini frameRate=0",
       sequence_with_file("seqinfo.ini",
                          "[Sequence]\nname=TUD-Campus\nimDir=img1\nframeRate=0\nseqLength=71\n"
                          "imWidth=640\nimHeight=480\nimExt=.jpg\n"),
       track_a,
       ExitCode::bad_input,
       {"seqinfo.ini", "frameRate"}},
      {"track_seqinfo_negative_length",
       "seqinfo.ini seqLength=-5",
       sequence_with_file("seqinfo.ini",
                          "[Sequence]\nname=TUD-Campus\nimDir=img1\nframeRate=25\nseqLength=-5\n"
                          "imWidth=640\nimHeight=480\nimExt=.jpg\n"),
       track_a,
       ExitCode::bad_input,
       {"seqinfo.ini", "seqLength"}},
      {"track_seqinfo_absurd_width",
       "seqinfo.ini imWidth=99999999999",
       sequence_with_file("seqinfo.ini",
                          "[Sequence]\nname=TUD-Campus\nimDir=img1\nframeRate=25\nseqLength=71\n"
                          "imWidth=99999999999\nimHeight=480\nimExt=.jpg\n"),
       track_a,
       ExitCode::bad_input,
       {"seqinfo.ini", "imWidth"}},
      {"track_seqinfo_empty",
       "seqinfo.ini empty",
       sequence_with_file("seqinfo.ini", ""),
       track_a,
       ExitCode::bad_input,
       {"seqinfo.ini"}},
      {"track_det_missing",
       "det/det.txt missing",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         std::filesystem::remove(ws.path("data/TUD-Campus/det/det.txt"));
       },
       track_a,
       ExitCode::bad_input,
       {"det.txt"}},
      {"track_det_wrong_column_count",
       "det.txt row with 4 columns",
       sequence_with_line("det/det.txt", 7, "3,-1,10,20"),
       track_a,
       ExitCode::bad_input,
       {"det.txt:7"}},
      {"track_det_nan",
       "det.txt width NaN",
       sequence_with_line("det/det.txt", 5, "2,-1,10,20,nan,40,0.9,-1,-1,-1"),
       track_a,
       ExitCode::bad_input,
       {"det.txt:5", "w"}},
      {"track_det_inf",
       "det.txt score inf",
       sequence_with_line("det/det.txt", 5, "2,-1,10,20,30,40,inf,-1,-1,-1"),
       track_a,
       ExitCode::bad_input,
       {"det.txt:5"}},
      {"track_det_negative_size",
       "det.txt negative width",
       sequence_with_line("det/det.txt", 3, "1,-1,10,20,-30,40,0.9,-1,-1,-1"),
       track_a,
       ExitCode::bad_input,
       {"det.txt:3", "w"}},
      {"track_det_zero_height",
       "det.txt zero height",
       sequence_with_line("det/det.txt", 3, "1,-1,10,20,30,0,0.9,-1,-1,-1"),
       track_a,
       ExitCode::bad_input,
       {"det.txt:3", "h"}},
      {"track_det_frame_zero",
       "det.txt frame 0 (frames are 1-based)",
       sequence_with_line("det/det.txt", 2, "0,-1,10,20,30,40,0.9,-1,-1,-1"),
       track_a,
       ExitCode::bad_input,
       {"det.txt:2", "frame"}},
      {"track_det_frame_beyond_length",
       "det.txt frame 5000 in a 71-frame sequence",
       sequence_with_line("det/det.txt", 2, "5000,-1,10,20,30,40,0.9,-1,-1,-1"),
       track_a,
       ExitCode::bad_input,
       {"det.txt:2", "frame"}},
      {"track_det_text_in_number",
       "det.txt x = 'abc'",
       sequence_with_line("det/det.txt", 4, "2,-1,abc,20,30,40,0.9,-1,-1,-1"),
       track_a,
       ExitCode::bad_input,
       {"det.txt:4", "x"}},
      {"track_det_binary_garbage",
       "det.txt is binary garbage",
       sequence_with_file("det/det.txt", std::string("\x7f"
                                                     "ELF\x01\x02\x00\xff\xfe",
                                                     9)),
       track_a,
       ExitCode::bad_input,
       {"det.txt:1"}},
      {"track_later_sequence_bad_keeps_earlier_results",
       "two sequences, the second has a bad det.txt row: the first's results are complete",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.copy_sequence(seq2, "data/TUD-Stadtmitte");
         ws.replace_line("data/TUD-Stadtmitte/det/det.txt", 10, "1,-1,10,20,30");
       },
       track_a,
       ExitCode::bad_input,
       {"det.txt:10"},
       first_results_complete},
      {"track_bad_interval",
       "--interval 0",
       [](Workspace& ws, Vars&) { ws.copy_sequence(seq, "data/TUD-Campus"); },
       {"track", "--dataset", "{dir}/data", "--out", "{dir}/out", "--interval", "0"},
       ExitCode::usage,
       {"interval"}},

      // ---- Evaluation: `rtmot eval` ----------------------------------------------------------
      {"eval_results_wrong_columns",
       "results row with 3 columns",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.write("res/TUD-Campus.txt", "1,1,10,20,30,40,1,-1,-1,-1\n1,2,3\n");
       },
       {"eval", "--gt", "{dir}/data", "--results", "{dir}/res"},
       ExitCode::bad_input,
       {"TUD-Campus.txt:2"}},
      {"eval_results_missing",
       "results file missing",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         std::filesystem::create_directories(ws.path("res"));
       },
       {"eval", "--gt", "{dir}/data", "--results", "{dir}/res"},
       ExitCode::bad_input,
       {"TUD-Campus.txt"}},
      {"eval_gt_nan",
       "gt.txt visibility NaN",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.replace_line("data/TUD-Campus/gt/gt.txt", 3, "1,1,10,20,30,40,1,nan,-1,-1");
         ws.write("res/TUD-Campus.txt", "1,1,10,20,30,40,1,-1,-1,-1\n");
       },
       {"eval", "--gt", "{dir}/data", "--results", "{dir}/res"},
       ExitCode::bad_input,
       {"gt.txt:3"}},

      // ---- Run configuration, model, video: `rtmot run` -----------------------------------
      {"run_config_missing",
       "config file does not exist",
       [](Workspace&, Vars&) {},
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml"}},
      {"run_config_empty",
       "config file empty",
       config_file(""),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml"}},
      {"run_config_not_yaml",
       "config is not YAML",
       config_file("source: [unclosed\n  : :\n"),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml"}},
      {"run_config_unknown_key",
       "unknown key detector.treshold",
       config_file(run_config("test://ball?num-buffers=5", "  treshold: 0.5\n")),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:", "treshold"}},
      {"run_config_wrong_type",
       "detector.score_threshold: high",
       config_file(run_config("test://ball?num-buffers=5", "  score_threshold: high\n")),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:", "score_threshold"}},
      {"run_config_out_of_range",
       "detector.score_threshold: 7",
       config_file(run_config("test://ball?num-buffers=5", "  score_threshold: 7\n")),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:", "score_threshold"}},
      {"run_config_complex_key",
       "a YAML key that is not a name ('? [a]'; found by fuzz_run_config)",
       config_file("? [a]\n: 1\n"),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:1"}},
      {"run_model_missing",
       "SSD model file does not exist",
       config_file("source:\n  uri: test://ball?num-buffers=5\ndetector:\n  kind: ssd\n"
                   "  model: no-such-model.onnx\n"),
       run_yaml,
       ExitCode::bad_model,
       {"no-such-model.onnx"}},
      {"run_model_truncated",
       "SSD model cut to 1000 bytes",
       [](Workspace& ws, Vars& vars) {
         const auto model = source_path("models/ssdlite_mobilenet_v2_coco.onnx");
         if (std::filesystem::exists(model)) {
           std::filesystem::copy_file(model, ws.path("cut.onnx"));
           ws.truncate("cut.onnx", 1000);
         } else {  // no fetched model: a file of the right name with bytes that are no model
           ws.write("cut.onnx", std::string(1000, '\x08'));
         }
         config_file(
             "source:\n  uri: test://ball?num-buffers=5\ndetector:\n  kind: ssd\n"
             "  model: " +
             ws.path("cut.onnx").string() + "\n")(ws, vars);
       },
       run_yaml,
       ExitCode::bad_model,
       {"cut.onnx"}},
      {"run_video_missing",
       "video file does not exist",
       config_file(run_config("{det}.missing.avi")),
       run_yaml,
       ExitCode::source_failed,
       {"missing.avi"}},
      {"run_video_undecodable",
       "a text file named .avi",
       [](Workspace& ws, Vars& vars) {
         ws.write("fake.avi", "this is not a video\n");
         config_file(run_config(ws.path("fake.avi").string()))(ws, vars);
       },
       run_yaml,
       ExitCode::source_failed,
       {"fake.avi"}},
      // An absent camera is no longer an error (cold start: it is retried as an outage, see
      // tests/outputs/cold_start_test.cpp); a camera URI that cannot be right still fails at once.
      {"run_camera_bad_port",
       "rtsp://camera.local:99999/stream: port out of range",
       config_file(run_config("rtsp://camera.local:99999/stream")),
       run_yaml,
       ExitCode::source_failed,
       {"rtsp://camera.local:99999/stream", "99999"}},
      {"run_uri_unknown_scheme",
       "source uri gopher://x",
       config_file(run_config("gopher://x")),
       run_yaml,
       ExitCode::source_failed,
       {"gopher://x", "scheme"}},
      {"run_uri_bad_test_param",
       "test://ball?fps=-3",
       config_file(run_config("test://ball?fps=-3")),
       run_yaml,
       ExitCode::source_failed,
       {"fps"}},

      // ---- Messages: `rtmot listen` --------------------------------------------------------
      {"listen_port_in_use",
       "UDP port already bound by another process",
       [](Workspace& ws, Vars& vars) { vars["port"] = std::to_string(ws.occupy_udp_port()); },
       {"listen", "--port", "{port}", "--bind", "127.0.0.1", "--duration", "1"},
       ExitCode::network,
       {"{port}"}},
      {"listen_port_out_of_range",
       "--port 70000",
       [](Workspace&, Vars&) {},
       {"listen", "--port", "70000"},
       ExitCode::usage,
       {"port"}},
      {"listen_port_not_a_number",
       "--port abc",
       [](Workspace&, Vars&) {},
       {"listen", "--port", "abc"},
       ExitCode::usage,
       {"port"}},
      {"listen_negative_duration",
       "--duration -1",
       [](Workspace&, Vars&) {},
       {"listen", "--port", "5600", "--duration", "-1"},
       ExitCode::usage,
       {"duration"}},
      {"listen_message_file_missing",
       "--read of a file that does not exist",
       [](Workspace&, Vars&) {},
       {"listen", "--read", "{dir}/none.bin"},
       ExitCode::bad_input,
       {"none.bin"}},
      {"listen_message_file_garbage",
       "--read of a file whose length prefix is absurd",
       [](Workspace& ws, Vars&) {
         ws.write("junk.bin", std::string("\xff\xff\xff\x7f"
                                          "abc",
                                          7));
       },
       {"listen", "--read", "{dir}/junk.bin", "--quiet"},
       ExitCode::bad_input,
       {"junk.bin"}},

      // ---- Command line ----------------------------------------------------------------------
      {"cli_unknown_subcommand",
       "rtmot frobnicate",
       [](Workspace&, Vars&) {},
       {"frobnicate"},
       ExitCode::usage,
       {"subcommand"}},
      {"cli_bad_log_level",
       "--log-level loud",
       [](Workspace&, Vars&) {},
       {"--log-level", "loud", "listen", "--port", "5600"},
       ExitCode::usage,
       {"loud"}},
  };
}

}  // namespace rtmot::test
