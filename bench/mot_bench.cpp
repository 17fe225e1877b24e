// How fast MOTChallenge files load and how fast the scorer runs, on ../shared's MOT15-train.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "mot/evaluation.hpp"
#include "mot/prepared_sequence.hpp"
#include "mot/scorer.hpp"
#include "motio/mot_files.hpp"
#include "motio/sequence_folders.hpp"

namespace {

namespace fs = std::filesystem;
using namespace rtmot::motio;
using namespace rtmot::mot;

fs::path shared_dir() {
  const char* env = std::getenv("RTMOT_SHARED_DIR");
  return env != nullptr ? fs::path(env) : fs::path(RTMOT_SHARED_DIR);
}

// All 11 sequences: seqinfo.ini, gt.txt and det.txt (78k rows).
void BM_LoadMot15Train(benchmark::State& state) {
  const auto sequences = find_sequence_dirs(shared_dir() / "data/mot15-train");
  std::size_t rows = 0;
  for (auto _ : state) {
    rows = 0;
    for (const auto& dir : sequences) {
      const SequenceInfo info = read_seqinfo(dir / "seqinfo.ini");
      rows += read_mot_file(dir / "gt/gt.txt", MotFileKind::ground_truth, info.length).size();
      rows += read_mot_file(dir / "det/det.txt", MotFileKind::detections, info.length).size();
    }
    benchmark::DoNotOptimize(rows);
  }
  state.counters["rows/s"] = benchmark::Counter(static_cast<double>(rows) * state.iterations(),
                                                benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LoadMot15Train)->Unit(benchmark::kMillisecond);

// Every metric (CLEAR, identity, HOTA) of the devkit fixture's two sequences, files excluded.
void BM_ScoreFixture(benchmark::State& state) {
  std::vector<PreparedSequence> prepared;
  for (const char* name : {"TUD-Campus", "TUD-Stadtmitte"}) {
    const fs::path dir = shared_dir() / "data/metrics-fixtures" / name;
    const SequenceInfo info = read_seqinfo(dir / "seqinfo.ini");
    PrepareOptions options;
    options.sequence_length = info.length;
    prepared.push_back(prepare_sequence(
        read_mot_file(dir / "gt/gt.txt", MotFileKind::ground_truth, info.length),
        read_mot_file(dir / "result-CEM.txt", MotFileKind::results, info.length), options));
  }
  for (auto _ : state) {
    for (const auto& sequence : prepared) benchmark::DoNotOptimize(count_all(sequence));
  }
}
BENCHMARK(BM_ScoreFixture)->Unit(benchmark::kMillisecond);

}  // namespace
