#include "detector/ssd_anchors.hpp"

#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "common/input_error.hpp"
#include "detector/model_files.hpp"

namespace rtmot::detector {
namespace {

constexpr std::array<const char*, 4> kFields{"ycenter", "xcenter", "height", "width"};

float parse_field(const std::string& text, const std::filesystem::path& path, int line, int index) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const float value = std::strtof(begin, &end);
  if (end == begin || *end != '\0' || !std::isfinite(value)) {
    throw InputError(path.string(), line, kFields[static_cast<std::size_t>(index)],
                     "expected a number, got '" + text + "'", ExitCode::bad_model);
  }
  return value;
}

}  // namespace

std::vector<Anchor> read_anchors(const std::filesystem::path& path) {
  std::istringstream in(read_model_file(path, kMaxAnchorsBytes, "anchors file"));
  std::vector<Anchor> anchors;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (text.empty() || text[0] == '#') continue;
    std::array<float, 4> values{};
    std::size_t start = 0;
    for (int i = 0; i < 4; ++i) {
      const std::size_t comma = text.find(',', start);
      const bool last = i == 3;
      if (last != (comma == std::string::npos)) {
        throw InputError(path.string(), line, "", "expected 4 comma-separated numbers",
                         ExitCode::bad_model);
      }
      values[static_cast<std::size_t>(i)] =
          parse_field(text.substr(start, last ? std::string::npos : comma - start), path, line, i);
      start = comma + 1;
    }
    if (values[2] <= 0.F || values[3] <= 0.F) {
      throw InputError(path.string(), line, values[2] <= 0.F ? "height" : "width",
                       "anchor sizes must be > 0", ExitCode::bad_model);
    }
    anchors.push_back({values[0], values[1], values[2], values[3]});
  }
  if (anchors.empty()) {
    throw InputError(path.string(), 0, "", "the anchors file holds no anchors",
                     ExitCode::bad_model);
  }
  return anchors;
}

}  // namespace rtmot::detector
