#include "detector/activation_ranges.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/input_error.hpp"
#include "detector/model_files.hpp"

namespace rtmot::detector {

namespace {

constexpr int kMaxFrames = 1 << 20;

bool is_hex_sha256(const std::string& text) {
  if (text.size() != 64) return false;
  for (const char c : text) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

std::string number_text(float value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", static_cast<double>(value));
  return buffer;
}

}  // namespace

std::filesystem::path default_activation_ranges_path(const std::filesystem::path& model_path) {
  return std::filesystem::path("configs") / "int8" / (model_path.stem().string() + ".ranges");
}

ActivationRanges read_activation_ranges(const std::filesystem::path& path) {
  const std::string text =
      read_model_file(path, kMaxActivationRangesBytes, "int8 activation ranges",
                      "make them with scripts/calibrate_int8.sh MODEL: docs/cpu-detector.md");
  const std::string file = path.string();
  ActivationRanges ranges;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    const auto fail = [&](const std::string& field, const std::string& problem) {
      return InputError(file, number, field, problem, ExitCode::bad_model);
    };
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string key;
    words >> key;
    std::string rest;
    if (key == "model_sha256") {
      words >> ranges.model_sha256;
      if (!is_hex_sha256(ranges.model_sha256) || (words >> rest)) {
        throw fail(key, "expected 64 lower-case hex digits");
      }
    } else if (key == "frames") {
      long long frames = 0;
      if (!(words >> frames) || frames < 1 || frames > kMaxFrames || (words >> rest)) {
        throw fail(key, "expected a frame count 1.." + std::to_string(kMaxFrames));
      }
      ranges.frames = static_cast<int>(frames);
    } else if (key == "range") {
      std::string name;
      std::string low_text;
      std::string high_text;
      if (!(words >> name >> low_text >> high_text) || (words >> rest)) {
        throw fail(key, "expected: range TENSOR MIN MAX");
      }
      ActivationRange range;
      for (auto [text_value, value] :
           {std::pair{&low_text, &range.min}, {&high_text, &range.max}}) {
        std::size_t used = 0;
        try {
          *value = std::stof(*text_value, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != text_value->size() || !std::isfinite(*value)) {
          throw fail(name, "'" + *text_value + "' is not a finite number");
        }
      }
      if (range.min > range.max) throw fail(name, "min is above max");
      if (!ranges.tensors.emplace(name, range).second) throw fail(name, "listed twice");
    } else {
      throw fail(key, "unknown key (expected model_sha256, frames or range)");
    }
  }
  if (ranges.model_sha256.empty()) {
    throw InputError(file, 0, "model_sha256", "missing", ExitCode::bad_model);
  }
  if (ranges.tensors.empty()) {
    throw InputError(file, 0, "range", "no tensor ranges", ExitCode::bad_model);
  }
  return ranges;
}

void check_ranges_belong_to(const ActivationRanges& ranges, const std::filesystem::path& path,
                            const std::string& model_sha256) {
  if (ranges.model_sha256 != model_sha256) {
    throw InputError(path.string(), 0, "model_sha256",
                     "the ranges were measured on another model (" + ranges.model_sha256 +
                         ", the model is " + model_sha256 +
                         "): calibrate this one with scripts/calibrate_int8.sh",
                     ExitCode::bad_model);
  }
}

std::string activation_ranges_text(const ActivationRanges& ranges) {
  std::ostringstream text;
  text << "# rtmot int8 activation ranges: each tensor's min and max in fp32 over sample frames.\n"
          "# Made by scripts/calibrate_int8.sh (docs/cpu-detector.md, INT8); do not edit.\n"
       << "model_sha256 " << ranges.model_sha256 << "\n"
       << "frames " << ranges.frames << "\n";
  for (const auto& [name, range] : ranges.tensors) {
    text << "range " << name << " " << number_text(range.min) << " " << number_text(range.max)
         << "\n";
  }
  return text.str();
}

}  // namespace rtmot::detector
