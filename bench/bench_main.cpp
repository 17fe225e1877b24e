// The one main() of the Google Benchmark executables: logs go where rtmot's go, to stderr, set up
// by the one logging set-up (platform/log_setup), so that stdout holds the benchmark's own output
// alone (--benchmark_format=json is read by tools; an info line there broke them: issue 30).
#include <benchmark/benchmark.h>

#include "platform/log_setup.hpp"

int main(int argc, char** argv) {
  rtmot::platform::configure_logging(rtmot::platform::LogFormat::text, "");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
