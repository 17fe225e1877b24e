// Round three of the catalogue (issue 23), the classes that belong to the settings surface: every
// number a user types goes through one checked parser (common/checked_number.hpp), every address
// through one address parser (platform/host_port.hpp). Each case failed on the build before the fix
// (RTMOT_CATALOGUE_BINARY=/path/to/old/rtmot shows it), and each checks that the run left the
// files as they were: the configuration unchanged, no output created.
#include <gtest/gtest.h>

#include <filesystem>

#include "catalogue.hpp"

namespace rtmot::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kOutputs = "out";

// A replay run of TUD-Campus on a short test source, writing JSON lines under out/.
std::string replay_yaml(const Workspace& ws, const std::string& extra) {
  return "source:\n  uri: test://ball?num-buffers=20\nplayback:\n  mode: every-frame\n"
         "detector:\n  kind: replay\n  det_file: " +
         ws.path("data/TUD-Campus/det/det.txt").string() + "\n" + extra;
}

std::function<void(Workspace&, Vars&)> run_yaml(const std::string& extra = "") {
  return [extra](Workspace& ws, Vars&) {
    ws.copy_sequence("TUD-Campus", "data/TUD-Campus");
    ws.write("run.yaml", replay_yaml(ws, extra));
  };
}

// The configuration is byte for byte what the setup wrote, and no output was created.
std::function<void(const Workspace&)> left_alone(const std::string& extra = "") {
  return [extra](const Workspace& ws) {
    EXPECT_EQ(read_text(ws.path("run.yaml")), replay_yaml(ws, extra)) << "run.yaml changed";
    EXPECT_FALSE(fs::exists(ws.path(kOutputs))) << "an output was created";
  };
}

std::function<void(const Workspace&)> nothing_written() {
  return [](const Workspace& ws) {
    EXPECT_FALSE(fs::exists(ws.path(kOutputs))) << "an output was created";
  };
}

// `rtmot run` on the replay configuration with one flag more, writing JSON lines under out/.
std::vector<std::string> run_with(const std::string& flag, const std::string& value) {
  return {"run", "--config", "{dir}/run.yaml", "--jsonl", "{dir}/out/t.jsonl", flag, value};
}

std::vector<std::string> soak_with(const std::string& flag, const std::string& value) {
  return {"soak", "--config", "{dir}/run.yaml", flag, value};
}

std::vector<std::string> listen_with(const std::string& flag, const std::string& value) {
  return {"listen", "--port", "0", "--jsonl", "{dir}/out/l.jsonl", flag, value};
}

CatalogueCase flag_case(std::string name, std::string what, std::vector<std::string> args,
                        const std::string& flag) {
  const bool run_or_soak = args.front() != "listen";
  return {std::move(name),
          std::move(what),
          run_or_soak ? run_yaml() : [](Workspace&, Vars&) {},
          std::move(args),
          ExitCode::usage,
          {flag},
          run_or_soak ? left_alone() : nothing_written()};
}

CatalogueCase yaml_case(std::string name, std::string what, const std::string& extra,
                        const std::string& field) {
  return {
      std::move(name),     std::move(what),
      run_yaml(extra),     {"run", "--config", "{dir}/run.yaml", "--jsonl", "{dir}/out/t.jsonl"},
      ExitCode::bad_input, {"run.yaml:", field},
      left_alone(extra)};
}

}  // namespace

std::vector<CatalogueCase> settings_cases() {
  return {
      // ---- 2. NaN and negative numbers through the command line's own validators ----------
      flag_case("run_threshold_nan", "run --threshold nan (silently kept 0.5)",
                run_with("--threshold", "nan"), "--threshold"),
      flag_case("run_threshold_negative", "run --threshold -0.5", run_with("--threshold", "-0.5"),
                "--threshold"),
      flag_case("run_latency_inf", "run --latency-ms inf", run_with("--latency-ms", "inf"),
                "--latency-ms"),
      flag_case("run_stats_interval_negative", "run --stats-interval -5",
                run_with("--stats-interval", "-5"), "--stats-interval"),
      flag_case("run_max_frames_negative", "run --max-frames -1", run_with("--max-frames", "-1"),
                "--max-frames"),
      flag_case("run_metrics_port_fraction", "run --metrics-port 9100.5",
                run_with("--metrics-port", "9100.5"), "--metrics-port"),
      flag_case("run_web_port_too_large", "run --web-port 70000", run_with("--web-port", "70000"),
                "--web-port"),
      flag_case("soak_duration_nan", "soak --duration nan (ran zero passes, exit 0)",
                soak_with("--duration", "nan"), "--duration"),
      flag_case("soak_duration_negative", "soak --duration -10", soak_with("--duration", "-10"),
                "--duration"),
      flag_case("soak_max_growth_nan", "soak --max-growth-mb nan (turned the leak check off)",
                soak_with("--max-growth-mb", "nan"), "--max-growth-mb"),
      flag_case("soak_max_growth_negative", "soak --max-growth-mb -1",
                soak_with("--max-growth-mb", "-1"), "--max-growth-mb"),
      flag_case("listen_count_negative", "listen --count -1 (meant \"no limit\")",
                listen_with("--count", "-1"), "--count"),
      flag_case("listen_count_nan", "listen --count nan", listen_with("--count", "nan"), "--count"),
      // ---- 5. Addresses not validated -----------------------------------------------------
      yaml_case("yaml_metrics_bind_bad_ipv4", "metrics_bind: 999.999.1.1 (listened on 231.231.1.1)",
                "output:\n  metrics_port: 9\n  metrics_bind: 999.999.1.1\n", "output.metrics_bind"),
      yaml_case("yaml_metrics_bind_name", "metrics_bind: a host name (not an address to bind)",
                "output:\n  metrics_port: 9\n  metrics_bind: example.com\n", "output.metrics_bind"),
      yaml_case("yaml_web_bind_name", "web_bind: a host name (not an address to bind)",
                "output:\n  web_port: 9\n  web_bind: example.com\n", "output.web_bind"),
      yaml_case("yaml_udp_bad_ipv4", "output.udp: 999.999.1.1:5600 (looked up as a name)",
                "output:\n  udp: 999.999.1.1:5600\n", "output.udp"),
      yaml_case("yaml_udp_bad_name", "output.udp: a host with a space",
                "output:\n  udp: 'ground station:5600'\n", "output.udp"),
      flag_case("run_udp_bad_ipv4", "run --udp 256.1.1.1:5600", run_with("--udp", "256.1.1.1:5600"),
                "--udp"),
      flag_case("listen_bind_bad_ipv4", "listen --bind 999.999.1.1",
                listen_with("--bind", "999.999.1.1"), "--bind"),
      flag_case("listen_bind_name", "listen --bind example.com (a name is not a local address)",
                listen_with("--bind", "example.com"), "--bind"),
      // ---- 11. A second YAML document was silently ignored ---------------------------------
      yaml_case("yaml_second_document",
                "a second document after '---' (its settings never applied)",
                "---\noutput:\n  udp: 127.0.0.1:5600\n", "second YAML document"),
      yaml_case("yaml_second_document_empty", "a trailing '---' with nothing after it", "---\n",
                "second YAML document"),
  };
}

}  // namespace rtmot::test
