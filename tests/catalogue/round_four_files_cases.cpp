// Round four of the catalogue (issue 32), the files' classes: temporaries opened through planted
// links, the log file as an output like any other, outputs that are FIFOs no process reads, two
// writers of one file, an empty list of processed frames, `count`'s lines file as strict as a run
// configuration, and the JSON log. docs/reliability.md lists them.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "catalogue.hpp"
#include "shared_data.hpp"

namespace rtmot::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* seq = "TUD-Campus";
const std::string kVictim = "a file outside the output folder\n";

std::string shared_det() {
  return read_text(shared_path(std::string("data/mot15-train/") + seq + "/det/det.txt"));
}
std::string shared_gt() {
  return read_text(shared_path(std::string("data/mot15-train/") + seq + "/gt/gt.txt"));
}

std::string replay_run(const Workspace& ws) {
  return "source:\n  uri: mot-seq://" + ws.path("data/TUD-Campus").string() +
         "\nplayback:\n  mode: every-frame\ndetector:\n  kind: replay\n  det_file: " +
         ws.path("data/TUD-Campus/det/det.txt").string() + "\n";
}

void replay_config(Workspace& ws, Vars&) {
  ws.copy_sequence(seq, "data/TUD-Campus");
  ws.write("run.yaml", replay_run(ws));
}

// A sequence, a victim file elsewhere, and the output folder.
void sequence_and_victim(Workspace& ws, Vars& vars) {
  replay_config(ws, vars);
  ws.write("victim", kVictim);
  fs::create_directories(ws.path("out"));
}

// A sequence with results (its ground truth) and the list of frames `frames_text`.
std::function<void(Workspace&, Vars&)> results_with_frames(const std::string& frames_text) {
  return [=](Workspace& ws, Vars&) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    ws.write("res/TUD-Campus.txt", shared_gt());
    ws.write("res/TUD-Campus.frames", frames_text);
  };
}

const std::string kLines =
    "sequences:\n  TUD-Campus:\n    lines:\n      - name: middle\n        from: [320, 0]\n"
    "        to: [320, 480]\n        in: left\n";

std::function<void(Workspace&, Vars&)> lines_file(const std::string& text) {
  return [=](Workspace& ws, Vars&) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    ws.write("lines.yaml", text);
  };
}

const std::vector<std::string> count_args = {"count", "--dataset", "{dir}/data", "--lines",
                                             "{dir}/lines.yaml"};
const std::vector<std::string> run_yaml = {"run", "--config", "{dir}/run.yaml"};
const std::vector<std::string> track_args = {"track", "--dataset", "{dir}/data", "--out",
                                             "{dir}/out"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

std::vector<std::string> after(std::vector<std::string> global,
                               const std::vector<std::string>& command) {
  global.insert(global.end(), command.begin(), command.end());
  return global;
}

using Check = std::function<void(const Workspace&)>;

Check all_of(std::vector<Check> checks) {
  return [checks](const Workspace& ws) {
    for (const auto& check : checks) check(ws);
  };
}

Check unchanged(const std::string& relative, std::function<std::string()> text) {
  return [=](const Workspace& ws) {
    ASSERT_TRUE(fs::exists(ws.path(relative))) << relative << " was removed";
    EXPECT_EQ(read_text(ws.path(relative)), text()) << relative << " was changed";
  };
}

Check victim_unchanged() {
  return unchanged("victim", [] { return kVictim; });
}

Check absent(const std::string& relative) {
  return [relative](const Workspace& ws) {
    EXPECT_FALSE(fs::exists(fs::symlink_status(ws.path(relative)))) << relative << " exists";
  };
}

// A published file: a regular file (not a link), whole lines, not empty.
Check published(const std::string& relative) {
  return [relative](const Workspace& ws) {
    const auto status = fs::symlink_status(ws.path(relative));
    ASSERT_TRUE(fs::is_regular_file(status)) << relative << " is not a regular file";
    const std::string text = read_text(ws.path(relative));
    EXPECT_FALSE(text.empty()) << relative;
    EXPECT_EQ(text.back(), '\n') << relative << ": last line cut";
  };
}

Check still_a_fifo(const std::string& relative) {
  return [relative](const Workspace& ws) {
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(ws.path(relative)))) << relative;
  };
}

void make_fifo(const Workspace& ws, const std::string& relative) {
  fs::create_directories(ws.path(relative).parent_path());
  ASSERT_EQ(::mkfifo(ws.path(relative).c_str(), 0644), 0) << relative;
}

ProcessConditions with_time_limit(int seconds) {
  ProcessConditions conditions;
  conditions.time_limit = std::chrono::seconds(seconds);
  return conditions;
}

CatalogueCase planted(std::string name, std::string what, std::vector<std::string> args,
                      std::string shell, Check check,
                      std::function<void(Workspace&, Vars&)> setup = sequence_and_victim) {
  CatalogueCase c{std::move(name), std::move(what), std::move(setup),
                  std::move(args), ExitCode::ok,    {},
                  std::move(check)};
  c.shell_before = std::move(shell);
  return c;
}

}  // namespace

std::vector<CatalogueCase> round_four_files_cases() {
  std::vector<CatalogueCase> cases;

  // ---- 1. Temporaries opened through planted links (common/output_open.cpp) ------------------
  // The name PATH.tmp-PID is rtmot's own: what is found there is removed (never followed, never
  // truncated) and the temporary created exclusively.
  cases.push_back(
      planted("track_results_temporary_is_a_link_to_a_victim",
              "track: out/TUD-Campus.txt.tmp-PID planted as a symbolic link to a file elsewhere",
              track_args, "ln -s {dir}/victim {dir}/out/TUD-Campus.txt.tmp-$$",
              all_of({victim_unchanged(), published("out/TUD-Campus.txt"),
                      published("out/TUD-Campus.frames"), no_temporaries("out")})));
  cases.push_back(planted(
      "track_frames_temporary_is_a_dangling_link",
      "track: out/TUD-Campus.frames.tmp-PID planted as a link to a file that does not exist",
      track_args, "ln -s {dir}/created-elsewhere {dir}/out/TUD-Campus.frames.tmp-$$",
      all_of({absent("created-elsewhere"), published("out/TUD-Campus.txt"),
              published("out/TUD-Campus.frames"), no_temporaries("out")})));
  cases.push_back(planted(
      "track_results_temporary_is_a_hard_link_to_a_victim",
      "track: out/TUD-Campus.txt.tmp-PID planted as a hard link to a file elsewhere", track_args,
      "ln {dir}/victim {dir}/out/TUD-Campus.txt.tmp-$$",
      all_of({victim_unchanged(), published("out/TUD-Campus.txt"), no_temporaries("out")})));
  cases.push_back(planted(
      "eval_csv_temporary_is_a_link_to_a_victim",
      "eval --csv: table.csv.tmp-PID planted as a symbolic link to a file elsewhere",
      {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--csv", "{dir}/out/table.csv"},
      "ln -s {dir}/victim {dir}/out/table.csv.tmp-$$",
      all_of({victim_unchanged(), published("out/table.csv"), no_temporaries("out")}),
      [](Workspace& ws, Vars& vars) {
        sequence_and_victim(ws, vars);
        ws.write("res/TUD-Campus.txt", shared_gt());
      }));
  cases.push_back(
      planted("run_mot_results_temporary_is_a_link_to_a_victim",
              "run --mot-results: the results' temporary planted as a link to a file elsewhere",
              with(run_yaml, {"--mot-results", "{dir}/out"}),
              "ln -s {dir}/victim {dir}/out/TUD-Campus.txt.tmp-$$",
              all_of({victim_unchanged(), published("out/TUD-Campus.txt"),
                      published("out/TUD-Campus.frames"), no_temporaries("out")})));
  cases.push_back(planted(
      "run_video_temporary_is_a_link_to_a_victim",
      "run --video-out: the video's temporary planted as a link to a file elsewhere",
      with(run_yaml, {"--source", "test://ball?width=64&height=48&num-buffers=10", "--video-out",
                      "{dir}/out/video.mp4"}),
      "ln -s {dir}/victim {dir}/out/video.mp4.tmp-$$",
      all_of({victim_unchanged(), no_temporaries("out"), [](const Workspace& ws) {
                ASSERT_TRUE(fs::is_regular_file(fs::symlink_status(ws.path("out/video.mp4"))));
                EXPECT_NE(read_text(ws.path("out/video.mp4")).find("moov"), std::string::npos);
              }})));
  {
    CatalogueCase folder{
        "track_results_temporary_is_a_folder",
        "track: a folder planted under out/TUD-Campus.txt.tmp-PID (cannot be removed: refused)",
        sequence_and_victim,
        track_args,
        ExitCode::bad_input,
        {"TUD-Campus.txt.tmp-", "is a folder"},
        [](const Workspace& ws) {
          EXPECT_FALSE(fs::exists(ws.path("out/TUD-Campus.txt")));
          EXPECT_FALSE(fs::exists(ws.path("out/TUD-Campus.frames")));
        }};
    folder.shell_before = "mkdir {dir}/out/TUD-Campus.txt.tmp-$$";
    cases.push_back(std::move(folder));
  }

  // ---- 2. The log file is an output: it may not name an input --------------------------------
  cases.push_back({"run_log_file_names_the_config",
                   "--log-file naming the configuration of the run (lines appended to it)",
                   replay_config,
                   after({"--log-file", "{dir}/run.yaml"}, run_yaml),
                   ExitCode::bad_input,
                   {"run.yaml", "same file", "--log-file"},
                   [](const Workspace& ws) {
                     const std::string text = read_text(ws.path("run.yaml"));
                     EXPECT_EQ(text.find("[info]"), std::string::npos) << "log lines in it";
                     EXPECT_EQ(text.find("[error]"), std::string::npos) << "log lines in it";
                   }});
  cases.push_back({"run_log_file_names_the_det_file",
                   "--log-file naming the det file the configuration replays",
                   replay_config,
                   after({"--log-file", "{dir}/data/TUD-Campus/det/det.txt"}, run_yaml),
                   ExitCode::bad_input,
                   {"det.txt", "same file", "--log-file"},
                   unchanged("data/TUD-Campus/det/det.txt", shared_det)});
  cases.push_back(
      {"run_log_file_names_the_jsonl_output",
       "--log-file and --jsonl naming one file (log lines inside the JSON lines)",
       replay_config,
       after({"--log-file", "{dir}/out.jsonl"}, with(run_yaml, {"--jsonl", "{dir}/out.jsonl"})),
       ExitCode::bad_input,
       {"out.jsonl", "same file", "--log-file"},
       absent("out.jsonl")});
  cases.push_back({"track_log_file_names_the_ground_truth_through_a_link",
                   "--log-file naming a symbolic link to a sequence's det.txt (track)",
                   [](Workspace& ws, Vars& vars) {
                     replay_config(ws, vars);
                     fs::create_symlink(ws.path("data/TUD-Campus/det/det.txt"), ws.path("log"));
                   },
                   after({"--log-file", "{dir}/log"}, track_args),
                   ExitCode::bad_input,
                   {"same file", "--log-file"},
                   all_of({unchanged("data/TUD-Campus/det/det.txt", shared_det),
                           absent("out/TUD-Campus.txt")})});
  cases.push_back({"eval_log_file_names_the_ground_truth",
                   "--log-file naming the ground truth eval scores against",
                   results_with_frames("1\n"),
                   {"--log-file", "{dir}/data/TUD-Campus/gt/gt.txt", "eval", "--gt", "{dir}/data",
                    "--results", "{dir}/res"},
                   ExitCode::bad_input,
                   {"gt.txt", "same file", "--log-file"},
                   unchanged("data/TUD-Campus/gt/gt.txt", shared_gt)});
  cases.push_back({"count_log_file_names_the_lines_file",
                   "--log-file naming count's lines file",
                   lines_file(kLines),
                   after({"--log-file", "{dir}/lines.yaml"}, count_args),
                   ExitCode::bad_input,
                   {"lines.yaml", "same file", "--log-file"},
                   unchanged("lines.yaml", [] { return kLines; })});
  cases.push_back({"listen_log_file_names_the_read_file",
                   "--log-file naming the message file listen --read reads",
                   [](Workspace& ws, Vars&) { ws.write("tracks.bin", "not read"); },
                   {"listen", "--read", "{dir}/tracks.bin", "--log-file", "{dir}/tracks.bin"},
                   ExitCode::bad_input,
                   {"tracks.bin", "same file", "--log-file"},
                   unchanged("tracks.bin", [] { return std::string("not read"); })});
  cases.push_back(
      {"run_log_file_written_once_checked",
       "--log-file of a run that succeeds: opened after the check, its lines written",
       replay_config,
       after({"--log-file", "{dir}/run.log"}, with(run_yaml, {"--jsonl", "{dir}/out.jsonl"})),
       ExitCode::ok,
       {},
       [](const Workspace& ws) {
         const std::string log = read_text(ws.path("run.log"));
         EXPECT_NE(log.find("[info]"), std::string::npos) << log;
         EXPECT_EQ(log.back(), '\n');
       }});

  // ---- 3. Outputs that are FIFOs no process reads (refused at open, not waited for) ----------
  const auto fifo_case = [](std::string name, std::string what, std::string fifo,
                            std::vector<std::string> args, std::vector<std::string> mentions) {
    return CatalogueCase{std::move(name),
                         std::move(what),
                         [fifo](Workspace& ws, Vars& vars) {
                           replay_config(ws, vars);
                           ws.write("res/TUD-Campus.txt", shared_gt());  // for eval
                           make_fifo(ws, fifo);
                         },
                         std::move(args),
                         ExitCode::bad_input,
                         std::move(mentions),
                         still_a_fifo(fifo),
                         with_time_limit(30)};
  };
  cases.push_back(fifo_case(
      "run_jsonl_is_a_fifo_without_reader", "run --jsonl naming a FIFO no process reads", "t.jsonl",
      with(run_yaml, {"--jsonl", "{dir}/t.jsonl"}), {"t.jsonl", "FIFO with no reader"}));
  cases.push_back(fifo_case("run_report_is_a_fifo_without_reader", "run --report naming a FIFO",
                            "report.json", with(run_yaml, {"--report", "{dir}/report.json"}),
                            {"report.json", "FIFO with no reader"}));
  cases.push_back(fifo_case("run_mot_results_file_is_a_fifo_without_reader",
                            "run --mot-results where NAME.txt is a FIFO", "out/TUD-Campus.txt",
                            with(run_yaml, {"--mot-results", "{dir}/out"}),
                            {"TUD-Campus.txt", "FIFO with no reader"}));
  cases.push_back(fifo_case(
      "run_video_out_is_a_fifo", "run --video-out naming a FIFO", "video.mp4",
      with(run_yaml, {"--source", "test://ball?num-buffers=5", "--video-out", "{dir}/video.mp4"}),
      {"video.mp4", "FIFO"}));
  cases.push_back(fifo_case(
      "eval_csv_is_a_fifo_without_reader", "eval --csv naming a FIFO", "table.csv",
      {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--csv", "{dir}/table.csv"},
      {"table.csv", "FIFO with no reader"}));
  cases.push_back(fifo_case("track_log_file_is_a_fifo_without_reader",
                            "--log-file naming a FIFO (blocked before the signal watcher existed)",
                            "log.fifo", after({"--log-file", "{dir}/log.fifo"}, track_args),
                            {"log.fifo", "FIFO with no reader"}));
  cases.push_back(
      {"run_jsonl_to_dev_null",
       "run --jsonl /dev/null: a character device is still written in place",
       replay_config,
       with(run_yaml, {"--jsonl", "/dev/null", "--mot-results", "{dir}/out"}),
       ExitCode::ok,
       {},
       all_of({published("out/TUD-Campus.txt"), no_temporaries("out"),
               [](const Workspace&) { EXPECT_TRUE(fs::is_character_file("/dev/null")); }})});

  // ---- Two writers of one file: the second is refused (flock), the first's file intact --------
  {
    CatalogueCase locked{
        "run_jsonl_locked_by_another_writer",
        "run --jsonl naming a file another process holds locked while writing",
        [](Workspace& ws, Vars& vars) {
          replay_config(ws, vars);
          ws.write("t.jsonl", "{\"the other writer\":1}\n");
        },
        with(run_yaml, {"--jsonl", "{dir}/t.jsonl"}),
        ExitCode::bad_input,
        {"t.jsonl", "another process"},
        unchanged("t.jsonl", [] { return std::string("{\"the other writer\":1}\n"); })};
    locked.shell_before = "exec 9>>{dir}/t.jsonl && flock 9";
    cases.push_back(std::move(locked));
  }

  // ---- Log write failures: a command that succeeded says so, exit 7 ----------------------------
  cases.push_back(
      {"run_log_file_on_a_full_device",
       "--log-file /dev/full: every log line fails (was exit 0, no word)",
       replay_config,
       after({"--log-file", "/dev/full"}, with(run_yaml, {"--mot-results", "{dir}/out"})),
       ExitCode::io_error,
       {"/dev/full", "No space left", "log lines after it are lost"},
       published("out/TUD-Campus.txt")});

  // ---- 8. An empty list of processed frames is an error, not "every frame" -------------------
  cases.push_back({"eval_processed_frames_only_its_comment",
                   "eval --processed-frames of a .frames file with its '#' line only (was: 71 "
                   "frames scored)",
                   results_with_frames("# frames processed, one per line\n"),
                   {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--processed-frames"},
                   ExitCode::bad_input,
                   {"TUD-Campus.frames", "lists no frame"},
                   unchanged("res/TUD-Campus.txt", shared_gt)});
  cases.push_back({"eval_processed_frames_empty_file",
                   "eval --processed-frames of an empty .frames file",
                   results_with_frames(""),
                   {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--processed-frames",
                    "--csv", "{dir}/table.csv"},
                   ExitCode::bad_input,
                   {"TUD-Campus.frames", "lists no frame"},
                   absent("table.csv")});
  cases.push_back({"eval_processed_frames_blank_lines",
                   "eval --processed-frames of a .frames file of blank lines and comments",
                   results_with_frames("\n# a\n\r\n\n# b\n"),
                   {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--processed-frames"},
                   ExitCode::bad_input,
                   {"TUD-Campus.frames", "lists no frame"}});

  // ---- 11. The JSON log is JSON whatever bytes a file name holds -----------------------------
  cases.push_back(
      {"track_json_log_names_a_latin1_folder",
       "--log-format json and a dataset folder named in Latin-1 (raw byte 0xE9)",
       [](Workspace&, Vars&) {},
       {"--log-format", "json", "track", "--dataset", "{dir}/caf\xE9", "--out", "{dir}/out"},
       ExitCode::bad_input,
       {"\"level\":\"error\"", "caf\\\\xE9"}});
  cases.push_back({"cli_error_under_json_log_format",
                   "--log-format json and an unknown option: the command-line error is JSON too",
                   [](Workspace&, Vars&) {},
                   {"--log-format", "json", "track", "--dataset", "x", "--bogus"},
                   ExitCode::usage,
                   {"{\"time\":", "\"level\":\"error\"", "command line", "--bogus"}});

  // ---- 13. count's lines file, as strict as a run configuration ------------------------------
  cases.push_back({"count_lines_sequence_twice",
                   "count: a sequence given twice in the lines file (one was silently ignored)",
                   lines_file(kLines + "  TUD-Campus:\n    lines: []\n"),
                   count_args,
                   ExitCode::bad_input,
                   {"lines.yaml:8", "sequences.TUD-Campus", "appears twice"}});
  cases.push_back({"count_lines_unknown_top_level_key",
                   "count: a top-level key other than sequences (a typo: 'sequence:')",
                   lines_file(kLines + "sequence:\n  TUD-Campus: {}\n"),
                   count_args,
                   ExitCode::bad_input,
                   {"lines.yaml:8", "sequence", "unknown key"}});
  cases.push_back({"count_lines_sequences_twice",
                   "count: the key sequences given twice",
                   lines_file(kLines + "sequences:\n  TUD-Campus: {}\n"),
                   count_args,
                   ExitCode::bad_input,
                   {"lines.yaml:8", "appears twice"}});
  cases.push_back({"count_lines_second_document",
                   "count: a second YAML document in the lines file (never read)",
                   lines_file(kLines + "---\nsequences:\n  TUD-Campus: {}\n"),
                   count_args,
                   ExitCode::bad_input,
                   {"lines.yaml:9", "second YAML document"}});
  cases.push_back({"count_tracks_id_twice_in_a_frame",
                   "count --tracks: a results file with id 1 twice in frame 1",
                   [](Workspace& ws, Vars& vars) {
                     lines_file(kLines)(ws, vars);
                     ws.write("res/TUD-Campus.txt",
                              "1,1,10,10,20,40,1,-1,-1,-1\n1,1,50,10,20,40,1,-1,-1,-1\n");
                   },
                   with(count_args, {"--tracks", "{dir}/res"}),
                   ExitCode::bad_input,
                   {"TUD-Campus.txt", "id 1 appears twice in frame 1"}});
  cases.push_back({"count_lines_point_1e308",
                   "count: a line's point at x = 1e308 (printed as 309 digits before)",
                   lines_file("sequences:\n  TUD-Campus:\n    lines:\n      - name: far\n"
                              "        from: [1e308, 0]\n        to: [320, 480]\n"),
                   count_args,
                   ExitCode::bad_input,
                   {"lines.yaml", "[1e+308, 0]", "outside the 640x480 frame"}});
  return cases;
}

}  // namespace rtmot::test
