// Round four of the catalogue, the streams' classes (issue 32: 4, 5, 9, 10, 12 and the arguable
// ones decided in docs/reliability.md): the video when the disk fills, H.265 at small sizes, the
// listener's event counts, event names that are not UTF-8, --input-flip on a mot-seq:// source,
// zones of many points, soak's outputs and a looping folder's log. Each case checks the exit
// code, the one error line and every file involved; docs/reliability.md lists them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "catalogue.hpp"
#include "messages/binary_file_sink.hpp"
#include "messages/frame_result.hpp"
#include "shared_data.hpp"

namespace rtmot::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* seq = "TUD-Campus";
using Check = std::function<void(const Workspace&)>;

std::string shared_det() {
  return read_text(shared_path(std::string("data/mot15-train/") + seq + "/det/det.txt"));
}

// A run of the replay detector over TUD-Campus's det.txt, timed by its seqinfo.ini (no images);
// `source` replaces the source section, `extra` is appended.
std::string replay_run(const Workspace& ws, const std::string& extra = "",
                       const std::string& source = "") {
  const std::string sequence = ws.path("data/TUD-Campus").string();
  return (source.empty() ? "source:\n  uri: mot-seq://" + sequence + "\n" : source) +
         "playback:\n  mode: every-frame\ndetector:\n  kind: replay\n  det_file: " + sequence +
         "/det/det.txt\n" + extra;
}

std::function<void(Workspace&, Vars&)> replay_config(const std::string& extra = "",
                                                     const std::string& source = "") {
  return [=](Workspace& ws, Vars&) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    ws.write("run.yaml", replay_run(ws, extra, source));
  };
}

const std::vector<std::string> run_yaml = {"run", "--config", "{dir}/run.yaml"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

Check all_of(std::vector<Check> checks) {
  return [checks](const Workspace& ws) {
    for (const auto& check : checks) check(ws);
  };
}

Check absent(const std::string& relative) {
  return [relative](const Workspace& ws) {
    EXPECT_FALSE(fs::exists(ws.path(relative))) << relative << " was created";
  };
}

// The configuration and the det file it replays are as they were.
Check inputs_unchanged() {
  return [](const Workspace& ws) {
    EXPECT_EQ(read_text(ws.path("data/TUD-Campus/det/det.txt")), shared_det());
    EXPECT_TRUE(fs::exists(ws.path("run.yaml")));
  };
}

// Nothing but the temporaries of other processes: the folder holds no file at all.
Check empty_folder(const std::string& folder) {
  return [folder](const Workspace& ws) {
    if (!fs::exists(ws.path(folder))) return;
    for (const auto& entry : fs::directory_iterator(ws.path(folder))) {
      ADD_FAILURE() << "left behind: " << entry.path();
    }
  };
}

Check stderr_has(const std::string& text) {
  return [text](const Workspace& ws) {
    EXPECT_NE(read_text(ws.path(".stderr")).find(text), std::string::npos) << "no '" << text << "'";
  };
}

// A video file that was finished: there, more than headers, its temporary gone.
Check finished_video(const std::string& relative) {
  return [relative](const Workspace& ws) {
    ASSERT_TRUE(fs::exists(ws.path(relative))) << relative;
    EXPECT_GT(fs::file_size(ws.path(relative)), 1000U) << relative;
    no_temporaries(fs::path(relative).parent_path().string())(ws);
  };
}

ProcessConditions with_disk_of(std::uint64_t bytes) {
  ProcessConditions conditions;
  conditions.file_size_limit = bytes;
  return conditions;
}

// A 24-bit BMP of width x height (rows bottom-up, padded to 4 bytes), a grey ramp.
std::string bmp(int width, int height) {
  const auto le32 = [](std::uint32_t v) {
    std::string bytes(4, '\0');
    for (int i = 0; i < 4; ++i) bytes[i] = static_cast<char>((v >> (8 * i)) & 0xFF);
    return bytes;
  };
  const int row = (width * 3 + 3) / 4 * 4;
  const auto pixels = static_cast<std::uint32_t>(row * height);
  std::string image = "BM" + le32(54 + pixels) + le32(0) + le32(54) + le32(40) +
                      le32(static_cast<std::uint32_t>(width)) +
                      le32(static_cast<std::uint32_t>(height)) +
                      std::string("\x01\x00\x18\x00", 4) + le32(0) + le32(pixels) + le32(2835) +
                      le32(2835) + le32(0) + le32(0);
  for (int y = 0; y < height; ++y) {
    std::string line(static_cast<std::size_t>(row), '\0');
    for (int x = 0; x < width * 3; ++x) line[x] = static_cast<char>((x * 7 + y * 13) & 0xFF);
    image += line;
  }
  return image;
}

// `count` images of width x height in frames/, beside the replay configuration.
std::function<void(Workspace&, Vars&)> image_folder(int width, int height, int count) {
  return [=](Workspace& ws, Vars& vars) {
    replay_config()(ws, vars);
    for (int i = 1; i <= count; ++i) {
      ws.write(
          "frames/" + std::string(5 - std::to_string(i).size(), '0') + std::to_string(i) + ".bmp",
          bmp(width, height));
    }
  };
}

// One stream whose messages name `pairs` distinct (kind, index) event pairs, 1000 to a message.
std::function<void(Workspace&, Vars&)> events_of_many_pairs(std::size_t pairs) {
  return [pairs](Workspace& ws, Vars&) {
    messages::BinaryFileSink sink(ws.path("spoofed.bin"));
    messages::FrameResult frame;
    frame.stream_id = 4;
    for (std::size_t first = 0; first < pairs; first += 1000) {
      frame.sequence = first / 1000;
      frame.frame_number = static_cast<std::int64_t>(frame.sequence) + 1;
      frame.pts_ns = static_cast<std::int64_t>(frame.sequence) * 40'000'000;
      frame.times.captured_ns = 1'000'000'000 + frame.pts_ns;
      frame.times.sent_ns = frame.times.captured_ns + 5'000'000;
      frame.events.clear();
      for (std::size_t pair = first; pair < std::min(pairs, first + 1000); ++pair) {
        events::Event event;
        event.kind = static_cast<events::EventKind>(pair % 5);
        event.index = static_cast<std::uint16_t>(pair / 5);
        event.track_id = 1;
        frame.events.push_back(event);
      }
      sink.write(frame);
    }
    sink.flush();
  };
}

std::string zone_of(std::size_t points) {
  // A convex polygon: corners on an ellipse inside the 640x480 frame.
  std::string text = "  events:\n    zones:\n      - name: plaza\n        points: [";
  for (std::size_t i = 0; i < points; ++i) {
    const double angle = 6.283185307179586 * static_cast<double>(i) / static_cast<double>(points);
    // Whole pixels: 57,000 corners must fit in the 1 MiB a configuration may have.
    text += (i == 0 ? "" : ", ") + std::string("[") +
            std::to_string(std::lround(320 + 300 * std::cos(angle))) + ", " +
            std::to_string(std::lround(240 + 200 * std::sin(angle))) + "]";
  }
  return text + "]\n";
}

std::string sequence_source(const Workspace& ws, const std::string& more) {
  return "source:\n  uri: mot-seq://" + ws.path("data/TUD-Campus").string() + "\n" + more;
}

}  // namespace

std::vector<CatalogueCase> round_four_streams_cases() {
  std::vector<CatalogueCase> cases;

  // ---- 4. The video when the disk fills: every container and codec ------------------------------
  // A file-size limit stands for the full disk: the write that crosses it fails (EFBIG) exactly
  // where a full disk's fails (ENOSPC), through the same filesink error; mounting a small tmpfs
  // needs privileges CI does not have. Before, the .mkv runs hung (no error line, every thread
  // waiting, SIGTERM ignored): filesink's error stopped the pipeline and appsrc's blocking push
  // waited for room for ever.
  // Sizes where the old build hung every time (320x240 H.265, 1280x720 H.264: x264 at 320x240
  // kept up with the source and often wrote its error while nothing waited), written in ~10 s by
  // a loaded machine.
  const std::vector<std::pair<std::string, std::string>> snow = {
      {"h265", "test://snow?num-buffers=60&width=320&height=240"},
      {"h264", "test://snow?num-buffers=100&width=1280&height=720"}};
  for (const std::string container : {"mkv", "mp4"}) {
    for (const auto& [codec, source] : snow) {
      const std::string video = "out/v." + container;
      cases.push_back({"run_" + container + "_" + codec + "_video_disk_full",
                       "an annotated ." + container + " (" + codec +
                           ") of snow with 200 KB of disk (the .mkv hung)",
                       replay_config(),
                       with(run_yaml, {"--source", source, "--video-out", "{dir}/" + video,
                                       "--video-codec", codec, "--jsonl", "{dir}/out/t.jsonl"}),
                       ExitCode::io_error,
                       {"{dir}/" + video, "output.video_file"},
                       all_of({absent(video), no_temporaries("out"), inputs_unchanged()}),
                       with_disk_of(200 * 1024)});
    }
  }

  // ---- 5. H.265 at small frame sizes: padded to what x265 takes -------------------------------
  cases.push_back({"run_h265_video_of_34x18",
                   "an H.265 .mkv of a 34x18 source (x265 corrupted the heap: SIGABRT)",
                   replay_config(),
                   with(run_yaml, {"--source", "test://ball?width=34&height=18&num-buffers=20",
                                   "--video-out", "{dir}/out/v.mkv", "--video-codec", "h265"}),
                   ExitCode::ok,
                   {},
                   all_of({finished_video("out/v.mkv"), stderr_has("to 64x64"),
                           stderr_has("H.265 encoder x265enc"), inputs_unchanged()})});
  cases.push_back(
      {"run_h265_video_of_33x17_images",
       "an H.265 .mp4 of a folder of 33x17 images (SIGABRT, a .tmp-PID left)",
       image_folder(33, 17, 3),
       with(run_yaml, {"--source", "images://{dir}/frames", "--video-out", "{dir}/out/v.mp4",
                       "--video-codec", "h265"}),
       ExitCode::ok,
       {},
       all_of({finished_video("out/v.mp4"), stderr_has("33x17"), stderr_has("to 64x64")})});
  cases.push_back(
      {"run_h265_video_of_40x18_after_input_flip",
       "an H.265 .mkv of an 18x40 source turned clockwise to 40x18 (SIGABRT)",
       replay_config(),
       with(run_yaml, {"--source", "test://ball?width=18&height=40&num-buffers=20", "--input-flip",
                       "clockwise", "--video-out", "{dir}/out/v.mkv", "--video-codec", "h265"}),
       ExitCode::ok,
       {},
       all_of({finished_video("out/v.mkv"), stderr_has("40x18")})});
  cases.push_back({"run_h265_video_of_62x100",
                   "an H.265 .mkv of a 62x100 source (one side below x265's 64-pixel CTU)",
                   replay_config(),
                   with(run_yaml, {"--source", "test://ball?width=62&height=100&num-buffers=20",
                                   "--video-out", "{dir}/out/v.mkv", "--video-codec", "h265"}),
                   ExitCode::ok,
                   {},
                   all_of({finished_video("out/v.mkv"), stderr_has("to 64x100")})});

  // ---- 9. The listener's event counts of one stream: bounded, the rest counted ----------------
  cases.push_back(
      {"listen_one_stream_with_40k_event_pairs",
       "a message file of one stream naming 40,000 distinct (kind, index) event pairs (a map "
       "node and a summary line each)",
       events_of_many_pairs(40'000),
       {"listen", "--read", "{dir}/spoofed.bin", "--quiet"},
       ExitCode::ok,
       {},
       [](const Workspace& ws) {
         const std::string out = read_text(ws.path(".stdout"));
         EXPECT_LT(std::count(out.begin(), out.end(), '\n'), 300) << "summary lines unbounded";
         EXPECT_NE(out.find("stream 4: 39744 more events of other kinds and indexes"),
                   std::string::npos)
             << "the events beyond the bound are not counted";
         EXPECT_NE(out.find("stream 4: received 40, lost 0"), std::string::npos);
       },
       {},
       100});

  // ---- 10. Event names that are not UTF-8 ------------------------------------------------------
  cases.push_back({"run_events_line_name_latin1",
                   "a line named 'Entr\\xE9e' (Latin-1: the metrics page became unreadable)",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("run.yaml", replay_run(ws, "",
                                                     sequence_source(ws,
                                                                     "  events:\n    lines:\n"
                                                                     "      - {name: Entr\xE9"
                                                                     "e, from: [320, 0], to: "
                                                                     "[320, 480]}\n")));
                   },
                   with(run_yaml, {"--jsonl", "{dir}/out/t.jsonl"}),
                   ExitCode::bad_input,
                   {"run.yaml:5", "lines[0].name", "not valid UTF-8", "0xE9"},
                   all_of({absent("out"), inputs_unchanged()})});
  cases.push_back({"run_events_zone_name_cut_utf8",
                   "a zone named 'caf\\xC3' (a two-byte sequence cut short)",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("run.yaml",
                              replay_run(ws, "",
                                         sequence_source(ws,
                                                         "  events:\n    zones:\n      - name: "
                                                         "\"caf\xC3\"\n        points: [[0, 0], "
                                                         "[100, 0], [100, 100]]\n")));
                   },
                   with(run_yaml, {"--jsonl", "{dir}/out/t.jsonl"}),
                   ExitCode::bad_input,
                   {"run.yaml:5", "zones[0].name", "byte 4"},
                   all_of({absent("out"), inputs_unchanged()})});
  cases.push_back(
      {"run_events_flag_name_surrogate",
       "--events naming a line with an encoded surrogate (\\xED\\xA0\\x80, not UTF-8)",
       replay_config(),
       with(run_yaml,
            {"--events", "{lines: [{name: \"a\xED\xA0\x80\", from: [0, 0], to: [10, 10]}]}",
             "--jsonl", "{dir}/out/t.jsonl"}),
       ExitCode::usage,
       {"--events", "not valid UTF-8"},
       all_of({absent("out"), inputs_unchanged()})});

  // ---- 12. --input-flip on a mot-seq:// source: refused -----------------------------------------
  cases.push_back({"run_input_flip_on_a_sequence",
                   "--input-flip clockwise on a mot-seq:// source (boxes not turned, its size "
                   "turned, events checked against that)",
                   replay_config(),
                   with(run_yaml, {"--input-flip", "clockwise", "--jsonl", "{dir}/out/t.jsonl",
                                   "--mot-results", "{dir}/out/res"}),
                   ExitCode::usage,
                   {"--input-flip", "mot-seq://", "no frames to turn"},
                   all_of({absent("out"), inputs_unchanged()})});
  cases.push_back({"run_input_flip_on_a_sequence_source_flag",
                   "--source mot-seq://S --det-file S/det/det.txt --input-flip horizontal",
                   [](Workspace& ws, Vars&) { ws.copy_sequence(seq, "data/TUD-Campus"); },
                   {"run", "--source", "mot-seq://{dir}/data/TUD-Campus", "--det-file",
                    "{dir}/data/TUD-Campus/det/det.txt", "--input-flip", "horizontal", "--jsonl",
                    "{dir}/out/t.jsonl"},
                   ExitCode::usage,
                   {"--input-flip", "mot-seq://"},
                   all_of({absent("out")})});
  cases.push_back({"run_config_flip_on_a_sequence",
                   "source.flip: rotate-180 on a mot-seq:// source, in the file",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("run.yaml",
                              replay_run(ws, "", sequence_source(ws, "  flip: rotate-180\n")));
                   },
                   with(run_yaml, {"--jsonl", "{dir}/out/t.jsonl"}),
                   ExitCode::bad_input,
                   {"run.yaml", "source.flip", "mot-seq://"},
                   all_of({absent("out"), inputs_unchanged()})});
  cases.push_back({"run_config_flip_on_the_second_of_two_sequences",
                   "sources: two mot-seq:// sources, the second with flip: clockwise",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     const std::string uri = "mot-seq://" + ws.path("data/TUD-Campus").string();
                     ws.write("run.yaml", replay_run(ws, "",
                                                     "sources:\n  - uri: " + uri + "\n  - uri: " +
                                                         uri + "\n    flip: clockwise\n"));
                   },
                   with(run_yaml, {"--jsonl", "{dir}/out/t.jsonl"}),
                   ExitCode::bad_input,
                   {"run.yaml", "sources[1].flip"},
                   all_of({absent("out"), inputs_unchanged()})});

  // ---- Arguable, decided: zones of many points -------------------------------------------------
  for (const std::size_t points : {std::size_t{1001}, std::size_t{57'000}}) {
    cases.push_back(
        {"run_zone_of_" + std::to_string(points) + "_points",
         "a zone of " + std::to_string(points) +
             " points (57,000 were checked for crossing edges for 24 s)",
         [points](Workspace& ws, Vars&) {
           ws.copy_sequence(seq, "data/TUD-Campus");
           ws.write("run.yaml", replay_run(ws, "", sequence_source(ws, zone_of(points))));
         },
         with(run_yaml, {"--jsonl", "{dir}/out/t.jsonl"}),
         ExitCode::bad_input,
         {"run.yaml:6", "zones[0].points", "at most 1000 points, got " + std::to_string(points)},
         all_of({absent("out"), inputs_unchanged()})});
  }

  // ---- Arguable, decided: soak refuses the outputs of a run ------------------------------------
  const std::vector<std::pair<std::string, std::string>> run_outputs = {
      {"mot_results", "  mot_results: OUT/res\n"},
      {"report_file", "  report_file: OUT/report.json\n"},
      {"metrics_port", "  metrics_port: 9\n"},
      {"web_port", "  web_port: 9\n"}};
  for (const auto& [field, yaml] : run_outputs) {
    cases.push_back({"soak_with_" + field,
                     "soak over a configuration with output." + field + " (silently not written)",
                     [yaml = yaml](Workspace& ws, Vars&) {
                       ws.copy_sequence(seq, "data/TUD-Campus");
                       std::string text = yaml;
                       const auto at = text.find("OUT");
                       if (at != std::string::npos) text.replace(at, 3, ws.path("out").string());
                       ws.write("run.yaml",
                                replay_run(ws, "output:\n  jsonl_file: " +
                                                   ws.path("out/t.jsonl").string() + "\n" + text));
                     },
                     {"soak", "--config", "{dir}/run.yaml", "--duration", "1"},
                     ExitCode::bad_input,
                     {"run.yaml", "output." + field, "soak writes message outputs only"},
                     all_of({empty_folder("out"), inputs_unchanged()})});
  }
  cases.push_back(
      {"soak_with_video_file",
       "soak over a configuration with output.video_file (silently not written)",
       [](Workspace& ws, Vars&) {
         ws.copy_sequence(seq, "data/TUD-Campus");
         ws.write("run.yaml",
                  replay_run(ws, "output:\n  video_file: " + ws.path("out/v.mp4").string() + "\n",
                             "source:\n  uri: test://ball?num-buffers=10\n"));
       },
       {"soak", "--config", "{dir}/run.yaml", "--duration", "1"},
       ExitCode::bad_input,
       {"run.yaml", "output.video_file"},
       all_of({empty_folder("out"), inputs_unchanged()})});

  // ---- Arguable, decided: a folder looping for ever logs its restarts sparingly ----------------
  cases.push_back({"run_three_images_looping_for_ever",
                   "a folder of 3 images looped for ever, 3000 frames (a log line per pass: 999)",
                   image_folder(64, 48, 3),
                   with(run_yaml, {"--source", "images://{dir}/frames", "--input-loop", "-1",
                                   "--max-frames", "3000", "--jsonl", "{dir}/out/t.jsonl"}),
                   ExitCode::ok,
                   {},
                   [](const Workspace& ws) {
                     const std::string err = read_text(ws.path(".stderr"));
                     std::size_t restarts = 0;
                     for (auto at = err.find("playing it again"); at != std::string::npos;
                          at = err.find("playing it again", at + 1)) {
                       ++restarts;
                     }
                     // Passes 2..10, 20..100, 200..1000: 27 lines for 1000 passes.
                     EXPECT_EQ(restarts, 27U) << err;
                     EXPECT_NE(err.find("(pass 1000, looping for ever)"), std::string::npos) << err;
                     const std::string jsonl = read_text(ws.path("out/t.jsonl"));
                     EXPECT_EQ(std::count(jsonl.begin(), jsonl.end(), '\n'), 3000);
                   }});
  return cases;
}

}  // namespace rtmot::test
