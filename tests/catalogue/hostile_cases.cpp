// Round two of the catalogue: the classes a hostile tester found (issue 11), each with cases of
// our own. Every case failed on the build before the fix (run the catalogue with
// RTMOT_CATALOGUE_BINARY=/path/to/old/rtmot to see it); docs/reliability.md lists them.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "catalogue.hpp"
#include "messages/binary_file_sink.hpp"
#include "shared_data.hpp"

namespace rtmot::test {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

constexpr const char* seq = "TUD-Campus";

const std::vector<std::string> track_a = {"track", "--dataset", "{dir}/data", "--out", "{dir}/out"};
const std::vector<std::string> eval_a = {"eval", "--gt", "{dir}/data", "--results", "{dir}/res"};
const std::vector<std::string> run_yaml = {"run", "--config", "{dir}/run.yaml"};

std::string seqinfo(const std::string& name) {
  return "[Sequence]\nname=" + name +
         "\nimDir=img1\nframeRate=25\nseqLength=71\nimWidth=640\nimHeight=480\nimExt=.jpg\n";
}

std::function<void(Workspace&, Vars&)> campus() {
  return [](Workspace& ws, Vars&) { ws.copy_sequence(seq, "data/TUD-Campus"); };
}

// TUD-Campus, and results that are its own ground truth (a perfect tracker).
std::function<void(Workspace&, Vars&)> campus_with_results() {
  return [](Workspace& ws, Vars&) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    ws.write("res/TUD-Campus.txt", read_text(ws.path("data/TUD-Campus/gt/gt.txt")));
  };
}

// A run configuration on the replay detector (TUD-Campus's det.txt) and a short test source.
std::string replay_config(const std::string& det_file, const std::string& extra = "",
                          const std::string& source = "test://ball?num-buffers=20") {
  return "source:\n  uri: " + source +
         "\nplayback:\n  mode: every-frame\ndetector:\n  kind: replay\n" +
         "  det_file: " + det_file + "\n" + extra;
}

std::function<void(Workspace&, Vars&)> config(
    const std::string& extra, const std::string& source = "test://ball?num-buffers=20") {
  return [=](Workspace& ws, Vars&) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    ws.write("run.yaml",
             replay_config(ws.path("data/TUD-Campus/det/det.txt").string(), extra, source));
  };
}

ProcessConditions with_time_limit(int seconds) {
  ProcessConditions conditions;
  conditions.time_limit = std::chrono::seconds(seconds);
  return conditions;
}

ProcessConditions with_signals(std::vector<TimedSignal> signals) {
  ProcessConditions conditions;
  conditions.signals = std::move(signals);
  return conditions;
}

ProcessConditions with_memory_of(std::uint64_t bytes) {
  ProcessConditions conditions;
  conditions.time_limit = std::chrono::seconds(20);
  conditions.address_space_limit = bytes;
  return conditions;
}

ProcessConditions with_disk_of(std::uint64_t bytes) {
  ProcessConditions conditions;
  conditions.file_size_limit = bytes;
  return conditions;
}

// Every line of a text output is whole: it ends with a newline.
void whole_lines(const fs::path& file) {
  const std::string text = read_text(file);
  EXPECT_TRUE(text.empty() || text.back() == '\n') << "last line cut: " << file;
}

// No output folder holds a leftover temporary, and every results file in it is whole.
std::function<void(const Workspace&)> results_whole(const std::string& folder) {
  return [folder](const Workspace& ws) {
    if (!fs::exists(ws.path(folder))) return;
    for (const auto& entry : fs::directory_iterator(ws.path(folder))) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
          << "temporary left behind: " << entry.path();
      whole_lines(entry.path());
    }
  };
}

std::function<void(const Workspace&)> nothing_at(const std::string& relative) {
  return [relative](const Workspace& ws) {
    EXPECT_FALSE(fs::exists(ws.path(relative))) << "written outside its folder: " << relative;
  };
}

// Messages as a binary message file, as `rtmot run` writes it.
void write_messages(const Workspace& ws, const std::string& relative,
                    const std::vector<messages::FrameResult>& frames) {
  messages::BinaryFileSink sink(ws.path(relative));
  for (const auto& frame : frames) sink.write(frame);
  sink.flush();
}

messages::FrameResult frame(std::uint32_t stream, std::uint64_t sequence, std::int64_t pts_ns) {
  messages::FrameResult result;
  result.stream_id = stream;
  result.sequence = sequence;
  result.frame_number = static_cast<std::int64_t>(sequence % 1'000'000) + 1;
  result.pts_ns = pts_ns;
  result.times.captured_ns = 1'000'000'000 + pts_ns;
  result.times.sent_ns = result.times.captured_ns + 5'000'000;
  return result;
}

// `copies` copies of every gt row as result rows, each shifted by half a pixel more and with an id
// of its own: many ids, all matching their gt box.
std::string shifted_copies(const std::string& gt, int copies) {
  std::vector<std::string> rows;
  std::istringstream in(gt);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) rows.push_back(line);
  }
  std::ostringstream results;
  int id = 1;
  for (int copy = 0; copy < copies; ++copy) {
    for (const auto& row : rows) {
      std::istringstream fields(row);
      std::string field[6];
      for (auto& value : field) std::getline(fields, value, ',');
      results << field[0] << ',' << id++ << ',' << std::stod(field[2]) + 0.5 * copy << ','
              << field[3] << ',' << field[4] << ',' << field[5] << ",1,-1,-1,-1\n";
    }
  }
  return results.str();
}

std::function<void(const Workspace&)> stdout_has(const std::string& text) {
  return [text](const Workspace& ws) {
    EXPECT_NE(read_text(ws.path(".stdout")).find(text), std::string::npos) << "no '" << text << "'";
  };
}

}  // namespace

std::vector<CatalogueCase> hostile_cases() {
  return {
      // ---- 1. Arithmetic on user numbers: ranges where parsed, no overflow -----------------
      {"track_interval_int_max",
       "track --interval 2147483647 (frame += interval overflowed: SIGSEGV)",
       campus(),
       {"track", "--dataset", "{dir}/data", "--out", "{dir}/out", "--interval", "2147483647"},
       ExitCode::usage,
       {"interval"}},
      {"study_intervals_int_max",
       "study --intervals 2147483647 (SIGSEGV)",
       campus(),
       {"study", "--dataset", "{dir}/data", "--out", "{dir}/study", "--quick", "--only",
        "kalman-iou", "--intervals", "2147483647"},
       ExitCode::usage,
       {"intervals"}},
      {"eval_interval_int_max",
       "eval --interval 2147483647",
       campus_with_results(),
       {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--interval", "2147483647"},
       ExitCode::usage,
       {"interval"}},
      {"track_threshold_nan",
       "track --threshold nan (NaN passed every < and > check)",
       campus(),
       {"track", "--dataset", "{dir}/data", "--out", "{dir}/out", "--threshold", "nan"},
       ExitCode::usage,
       {"threshold"}},
      {"track_max_age_huge",
       "track --max-age 2147483647",
       campus(),
       {"track", "--dataset", "{dir}/data", "--out", "{dir}/out", "--max-age", "2147483647"},
       ExitCode::usage,
       {"max-age"}},
      {"listen_duration_nan",
       "listen --duration nan (listened forever)",
       [](Workspace&, Vars&) {},
       {"listen", "--port", "0", "--bind", "127.0.0.1", "--duration", "nan"},
       ExitCode::usage,
       {"duration"},
       {},
       with_time_limit(10)},
      {"run_stats_interval_nan",
       "run --stats-interval nan",
       config(""),
       {"run", "--config", "{dir}/run.yaml", "--stats-interval", "nan"},
       ExitCode::usage,
       {"stats-interval"}},

      // ---- 2. Output paths built from input data ---------------------------------------------
      {"track_sequence_name_escapes_out",
       "seqinfo.ini name=../escaped (wrote outside --out)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.write("data/TUD-Campus/seqinfo.ini", seqinfo("../escaped"));
       },
       track_a,
       ExitCode::bad_input,
       {"seqinfo.ini:2", "name"},
       nothing_at("escaped.txt")},
      {"track_sequence_name_absolute",
       "seqinfo.ini name=/absolute/path (wrote anywhere)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.write("data/TUD-Campus/seqinfo.ini", seqinfo(ws.path("absolute").string()));
       },
       track_a,
       ExitCode::bad_input,
       {"seqinfo.ini:2", "name"},
       nothing_at("absolute.txt")},
      {"track_two_sequences_one_name",
       "two sequence folders whose seqinfo.ini say the same name (one overwrote the other)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/A");
         ws.copy_sequence(seq, "data/B");
       },
       track_a,
       ExitCode::bad_input,
       {"B/seqinfo.ini", "name", "TUD-Campus"},
       nothing_at("out/TUD-Campus.txt")},
      {"eval_sequence_name_escapes_results",
       "eval: seqinfo.ini name=../elsewhere (read a file outside --results)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.write("data/TUD-Campus/seqinfo.ini", seqinfo("../elsewhere"));
         ws.write("elsewhere.txt", read_text(ws.path("data/TUD-Campus/gt/gt.txt")));
         fs::create_directories(ws.path("res"));
       },
       eval_a,
       ExitCode::bad_input,
       {"seqinfo.ini:2", "name"}},

      // ---- 3. A failed read taken for empty input ----------------------------------------------
      {"track_det_is_a_folder",
       "det/det.txt is a folder (gave empty results, exit 0)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         fs::remove(ws.path("data/TUD-Campus/det/det.txt"));
         fs::create_directories(ws.path("data/TUD-Campus/det/det.txt"));
       },
       track_a,
       ExitCode::bad_input,
       {"det.txt", "is a folder"}},
      {"eval_results_is_a_folder",
       "results/<seq>.txt is a folder (MOTA 0, exit 0)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         fs::create_directories(ws.path("res/TUD-Campus.txt"));
       },
       eval_a,
       ExitCode::bad_input,
       {"TUD-Campus.txt", "is a folder"}},
      {"track_det_read_error",
       "det.txt whose read fails with EIO (/proc/self/mem: was empty results, exit 0)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         fs::remove(ws.path("data/TUD-Campus/det/det.txt"));
         fs::create_symlink("/proc/self/mem", ws.path("data/TUD-Campus/det/det.txt"));
       },
       track_a,
       ExitCode::io_error,
       {"det.txt", "read error"}},
      {"track_det_is_a_fifo",
       "det.txt is a FIFO (hung)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         fs::remove(ws.path("data/TUD-Campus/det/det.txt"));
         ::mkfifo(ws.path("data/TUD-Campus/det/det.txt").c_str(), 0600);
       },
       track_a,
       ExitCode::bad_input,
       {"det.txt", "FIFO"},
       {},
       with_time_limit(10)},
      {"run_config_is_a_fifo",
       "run --config FIFO (hung)",
       [](Workspace& ws, Vars&) { ::mkfifo(ws.path("run.yaml").c_str(), 0600); },
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml", "FIFO"},
       {},
       with_time_limit(10)},
      {"listen_read_fifo",
       "listen --read FIFO (hung)",
       [](Workspace& ws, Vars&) { ::mkfifo(ws.path("messages.bin").c_str(), 0600); },
       {"listen", "--read", "{dir}/messages.bin"},
       ExitCode::bad_input,
       {"messages.bin", "FIFO"},
       {},
       with_time_limit(10)},
      {"run_config_is_a_folder",
       "run --config FOLDER",
       [](Workspace& ws, Vars&) { fs::create_directories(ws.path("run.yaml")); },
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml", "is a folder"}},
      {"track_det_endless_device",
       "det.txt is /dev/zero (read until bad_alloc)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         fs::remove(ws.path("data/TUD-Campus/det/det.txt"));
         fs::create_symlink("/dev/zero", ws.path("data/TUD-Campus/det/det.txt"));
       },
       track_a,
       ExitCode::bad_input,
       {"det.txt", "device"},
       {},
       with_memory_of(3ULL << 30),
       400},
      {"track_det_line_of_20mb",
       "det.txt whose one line is 20 MB of commas (cost 600 MB)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.write("data/TUD-Campus/det/det.txt", "1,-1" + std::string(20 << 20, ',') + "\n");
       },
       track_a,
       ExitCode::bad_input,
       {"det.txt:1", "bytes"},
       {},
       {},
       150},
      {"track_det_sparse_600mb",
       "det.txt of 600 MB (a sparse file: read whole before)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         fs::resize_file(ws.path("data/TUD-Campus/det/det.txt"), 600ULL << 20);
       },
       track_a,
       ExitCode::bad_input,
       {"det.txt", "limit"},
       {},
       with_memory_of(3ULL << 30),
       150},
      {"eval_unreadable_sub_folder",
       "a dataset sub-folder that cannot be read (a symlink loop: was an internal error)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         fs::create_symlink("loop", ws.path("data/loop"));
         fs::create_directories(ws.path("res"));
       },
       eval_a,
       ExitCode::bad_input,
       {"loop", "cannot read"}},

      // ---- 4. Memory that grows with the input's ids --------------------------------------------
      {"eval_60k_result_ids",
       "a 2.3 MB results file with 60,000 ids on ETH-Bahnhof (dense matrices: 1.8 GB)",
       [](Workspace& ws, Vars&) {
         const auto source = shared_path("data/mot15-train/ETH-Bahnhof");
         fs::create_directories(ws.path("data/ETH-Bahnhof/gt"));
         fs::copy_file(source / "seqinfo.ini", ws.path("data/ETH-Bahnhof/seqinfo.ini"));
         fs::copy_file(source / "gt/gt.txt", ws.path("data/ETH-Bahnhof/gt/gt.txt"));
         std::vector<std::string> rows;
         std::istringstream gt(read_text(source / "gt/gt.txt"));
         for (std::string line; std::getline(gt, line);) rows.push_back(line);
         std::ostringstream results;
         int id = 1;
         for (int copy = 0; id <= 60'000; ++copy) {
           for (const auto& row : rows) {
             if (id > 60'000) break;
             std::istringstream fields(row);
             std::string field[6];
             for (auto& value : field) std::getline(fields, value, ',');
             // Shifted copies of the gt boxes, each copy of each box its own id.
             results << field[0] << ',' << id++ << ',' << std::stod(field[2]) + 0.5 * copy << ','
                     << field[3] << ',' << field[4] << ',' << field[5] << ",1,-1,-1,-1\n";
           }
         }
         ws.write("res/ETH-Bahnhof.txt", results.str());
       },
       eval_a,
       ExitCode::ok,
       {},
       {},
       {},
       300},
      {"listen_100k_stream_ids",
       "a message file with 100,000 stream ids (kept ~0.7 KB each forever, 100k summary lines)",
       [](Workspace& ws, Vars&) {
         std::vector<messages::FrameResult> frames;
         for (std::uint32_t stream = 0; stream < 100'000; ++stream) {
           frames.push_back(frame(stream, 0, 0));
         }
         write_messages(ws, "spoofed.bin", frames);
       },
       {"listen", "--read", "{dir}/spoofed.bin", "--quiet"},
       ExitCode::ok,
       {},
       [](const Workspace& ws) {
         const std::string out = read_text(ws.path(".stdout"));
         EXPECT_LT(std::count(out.begin(), out.end(), '\n'), 1100) << "summary lines unbounded";
         EXPECT_NE(out.find("98976 more streams"), std::string::npos) << "evictions not reported";
       },
       {},
       100},
      {"listen_names_observed_frames",
       "a full-rate message file: a processed frame, a predicted one, one the image followed",
       [](Workspace& ws, Vars&) {
         std::vector<messages::FrameResult> frames{frame(0, 0, 0), frame(0, 1, 100'000'000),
                                                   frame(0, 2, 200'000'000)};
         frames[1].predicted = true;
         frames[2].predicted = true;
         frames[2].observed = true;
         write_messages(ws, "full_rate.bin", frames);
       },
       {"listen", "--read", "{dir}/full_rate.bin"},
       ExitCode::ok,
       {},
       [](const Workspace& ws) {
         const std::string out = read_text(ws.path(".stdout"));
         EXPECT_NE(out.find("seq 0 frame 1: 0 tracks, latency"), std::string::npos) << out;
         EXPECT_NE(out.find("seq 1 frame 2: 0 tracks predicted, latency"), std::string::npos)
             << out;
         EXPECT_NE(out.find("seq 2 frame 3: 0 tracks predicted, observed, latency"),
                   std::string::npos)
             << out;
       }},

      // ---- 5. Config values without ranges (outside tracker:) -----------------------------------
      {"run_config_nan_value",
       "tracker.affinity_threshold: .nan (was exit 1, internal error)",
       config("tracker:\n  affinity_threshold: .nan\n"),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:9", "affinity_threshold", "finite"}},
      {"run_config_inf_fps",
       "source.fps: .inf",
       config("", "test://ball?num-buffers=20\n  fps: .inf"),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:3", "source.fps"}},
      {"run_config_latency_huge",
       "playback.latency_ms: 1e300",
       [](Workspace& ws, Vars&) {
         ws.write("run.yaml",
                  "source:\n  uri: test://ball?num-buffers=20\nplayback:\n"
                  "  latency_ms: 1e300\n");
       },
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:4", "latency_ms"}},
      {"run_config_duplicate_key",
       "detector.score_threshold given twice (silently took one)",
       config("  score_threshold: 0.3\n  score_threshold: 0.9\n"),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:9", "score_threshold", "twice"}},
      {"run_config_duplicate_section",
       "two 'detector:' sections",
       config("detector:\n  kind: replay\n"),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:8", "detector", "twice"}},
      {"run_config_port_out_of_range",
       "output.udp: 127.0.0.1:70000 (no line, found only when the sinks were made)",
       config("output:\n  udp: 127.0.0.1:70000\n"),
       run_yaml,
       ExitCode::bad_input,
       {"run.yaml:9", "output.udp", "65535"}},
      {"run_udp_override_port_out_of_range",
       "--udp 127.0.0.1:99999 (exit 3, docs say a bad override is 2)",
       config(""),
       {"run", "--config", "{dir}/run.yaml", "--udp", "127.0.0.1:99999"},
       ExitCode::usage,
       {"--udp", "65535"}},

      // ---- 7. Stopping -------------------------------------------------------------------------
      {"track_sigterm_results_whole",
       "SIGTERM to track over MOT15 after its first sequence (killed it: exit 143, results cut)",
       [](Workspace& ws, Vars& vars) {
         vars["mot15"] = shared_path("data/mot15-train").string();
         (void)ws;
       },
       {"track", "--dataset", "{mot15}", "--out", "{dir}/out"},
       ExitCode::ok,
       {},
       results_whole("out"),
       with_signals({{SIGTERM, milliseconds(0), "ADL-Rundle-6 "}})},
      {"eval_sigterm_stops_cleanly",
       "SIGTERM to eval over MOT15 after its second sequence (killed it)",
       [](Workspace& ws, Vars& vars) {
         const auto dataset = shared_path("data/mot15-train");
         vars["mot15"] = dataset.string();
         for (const auto& entry : fs::directory_iterator(dataset)) {
           ws.write("res/" + entry.path().filename().string() + ".txt",
                    shifted_copies(read_text(entry.path() / "gt/gt.txt"), 6));
         }
         fs::create_directories(ws.path("out"));
       },
       {"eval", "--gt", "{mot15}", "--results", "{dir}/res", "--csv", "{dir}/out/table.csv"},
       ExitCode::ok,
       {},
       results_whole("out"),
       // The build before printed nothing per sequence: it got its SIGTERM after 2 s (of its 3 s
       // idle, 9 s loaded, on these results); ours gets it as it reports its second sequence.
       with_signals({{SIGTERM, milliseconds(0), "ADL-Rundle-8: scored", milliseconds(2000)}})},

      {"study_sigterm_stops_cleanly",
       "SIGTERM to study over MOT15 during its runs (killed it: exit 143)",
       [](Workspace& ws, Vars& vars) {
         vars["mot15"] = shared_path("data/mot15-train").string();
         (void)ws;
       },
       {"study", "--dataset", "{mot15}", "--out", "{dir}/out", "--quick", "--jobs", "2"},
       ExitCode::ok,
       {},
       nothing_at("out"),  // the tables need every run: nothing, not a part
       with_signals({{SIGTERM, milliseconds(0), "[20/"}})},

      // ---- 8. Failures of outputs and odd sources ---------------------------------------------
      {"track_results_disk_full",
       "track with 5 KB of disk left (was exit 3, a malformed input; results cut)",
       campus(),
       track_a,
       ExitCode::io_error,
       {"TUD-Campus.txt", "cannot write"},
       nothing_at("out/TUD-Campus.txt"),
       with_disk_of(5'000)},
      {"run_jsonl_disk_full",
       "run writing JSON lines with 30 KB of disk left (last line cut)",
       config("", "test://ball?num-buffers=300"),
       {"run", "--config", "{dir}/run.yaml", "--jsonl", "{dir}/out.jsonl"},
       ExitCode::io_error,
       {"out.jsonl", "cannot write"},
       [](const Workspace& ws) { whole_lines(ws.path("out.jsonl")); },
       with_disk_of(30'000)},
      {"run_replay_frame_10m",
       "replayed det file with a row at frame 10,000,000 (a vector per frame: +240 MB)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.write("det10m.txt", read_text(ws.path("data/TUD-Campus/det/det.txt")) +
                                    "10000000,-1,10,20,30,40,0.9,-1,-1,-1\n");
         ws.write("run.yaml", replay_config(ws.path("det10m.txt").string()));
       },
       run_yaml,
       ExitCode::ok,
       {},
       {},
       {},
       170},
      {"track_tiny_box_reads_back",
       "a detection 0.0001 wide: its results row read '0.00', which eval refused",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         std::string det;
         for (int f = 1; f <= 71; ++f)
           det += std::to_string(f) + ",-1,100,100,0.0001,0.004,0.99,-1,-1,-1\n";
         ws.write("data/TUD-Campus/det/det.txt", det);
       },
       {"track", "--dataset", "{dir}/data", "--out", "{dir}/out", "--preset", "sort"},
       ExitCode::ok,
       {},
       [](const Workspace& ws) {
         const auto eval = run_process({rtmot_binary(), "eval", "--gt", ws.path("data").string(),
                                        "--results", ws.path("out").string()},
                                       ws.dir(), std::chrono::seconds(60));
         EXPECT_TRUE(eval.exited && eval.exit_code == 0) << "eval of our own results: " << eval.err;
       }},
      {"track_frame_beyond_max_detections",
       "a frame of 1,100 detections, above the tracker's 1,024 (cut silently)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         std::string det = read_text(ws.path("data/TUD-Campus/det/det.txt"));
         for (int box = 0; box < 1100; ++box) {
           det += "5,-1," + std::to_string(box % 100 * 6) + "," + std::to_string(box / 100 * 40) +
                  ",5,30,0.9,-1,-1,-1\n";
         }
         ws.write("data/TUD-Campus/det/det.txt", det);
       },
       track_a,
       ExitCode::ok,
       {},
       [](const Workspace& ws) {
         const std::string err = read_text(ws.path(".stderr"));
         EXPECT_NE(err.find("max_detections (1024, up to 1"), std::string::npos) << err;
       }},
      {"listen_sequence_near_2_64",
       "sequences up to 2^64 - 1, one late and one twice, then 0, 1 (reported ~2^64 lost)",
       [](Workspace& ws, Vars&) {
         const std::uint64_t top = std::numeric_limits<std::uint64_t>::max();
         std::vector<messages::FrameResult> frames;
         const auto at = [&](std::uint64_t s) {
           frames.push_back(frame(7, s, static_cast<std::int64_t>(s - (top - 9)) * 40'000'000));
         };
         for (std::uint64_t s = top - 9; s != top - 1; ++s) at(s);
         at(top);
         at(top - 1);  // late
         at(top);      // twice
         at(0);        // the sequence wraps (serial-number arithmetic: after 2^64 - 1)
         at(1);
         write_messages(ws, "wrap.bin", frames);
       },
       {"listen", "--read", "{dir}/wrap.bin", "--quiet"},
       ExitCode::ok,
       {},
       stdout_has("stream 7: received 13, lost 0, reordered 1, duplicated 1, restarts 0")},
      {"listen_two_senders_one_stream_id",
       "two senders with stream id 3, interleaved (reported as 'duplicated')",
       [](Workspace& ws, Vars&) {
         std::vector<messages::FrameResult> frames;
         for (std::uint64_t s = 0; s < 50; ++s) {
           frames.push_back(frame(3, s, static_cast<std::int64_t>(s) * 40'000'000));
           frames.push_back(frame(3, s, 7'000'000'000 + static_cast<std::int64_t>(s) * 33'000'000));
         }
         write_messages(ws, "two.bin", frames);
       },
       {"listen", "--read", "{dir}/two.bin", "--quiet"},
       ExitCode::ok,
       {},
       stdout_has("CLASH")},
  };
}

}  // namespace rtmot::test
