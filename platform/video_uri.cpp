#include "platform/video_uri.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "common/frame_rate.hpp"
#include "common/input_error.hpp"
#include "platform/host_port.hpp"

namespace rtmot::platform {
namespace {

[[noreturn]] void fail(const std::string& uri, const std::string& part,
                       const std::string& problem) {
  throw InputError(uri, 0, part, problem, ExitCode::source_failed);
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool all_digits(const std::string& text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); });
}

int parse_int(const std::string& uri, const std::string& key, const std::string& value, int min,
              int max) {
  int parsed = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
  if (error != std::errc() || end != value.data() + value.size()) {
    fail(uri, key, "'" + value + "' is not an integer");
  }
  if (parsed < min || parsed > max) {
    fail(uri, key,
         std::to_string(parsed) + " is out of range [" + std::to_string(min) + ", " +
             std::to_string(max) + "]");
  }
  return parsed;
}

double parse_fps(const std::string& uri, const std::string& key, const std::string& value) {
  // strtod rather than from_chars<double>: g++ 9/10 on the boards lack the floating-point overload.
  char* end = nullptr;
  const double parsed = std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size()) {
    fail(uri, key, "'" + value + "' is not a number");
  }
  if (!is_frame_rate(parsed)) fail(uri, key, value + " is out of range " + frame_rate_range());
  return parsed;
}

bool parse_bool(const std::string& uri, const std::string& key, const std::string& value) {
  const std::string v = lowercase(value);
  if (v == "true" || v == "1" || v == "yes") return true;
  if (v == "false" || v == "0" || v == "no") return false;
  fail(uri, key, "'" + value + "' is not a boolean (true/false)");
}

// Calls `apply(key, value)` for each `key=value` of a URI's query (`a=1&b=2`); a pair without
// '=' or a key given twice is an error naming it.
template <typename Apply>
void for_each_query_pair(const std::string& uri, const std::string& query, Apply apply) {
  std::set<std::string> seen;
  std::size_t start = 0;
  while (start <= query.size()) {
    const auto amp = std::min(query.find('&', start), query.size());
    const std::string pair = query.substr(start, amp - start);
    start = amp + 1;
    if (pair.empty()) continue;
    const auto equals = pair.find('=');
    if (equals == std::string::npos) fail(uri, pair, "expected key=value");
    const std::string key = pair.substr(0, equals);
    if (!seen.insert(key).second) fail(uri, key, "given twice");
    apply(key, pair.substr(equals + 1));
  }
}

constexpr int max_frames = 1'000'000'000;

void apply_test_parameter(const std::string& uri, const std::string& key, const std::string& value,
                          TestSourceParams& params) {
  if (key == "width") {
    params.width = parse_int(uri, key, value, 16, 16384);
  } else if (key == "height") {
    params.height = parse_int(uri, key, value, 16, 16384);
  } else if (key == "fps") {
    params.fps = parse_fps(uri, key, value);
  } else if (key == "num-buffers") {
    params.num_buffers = parse_int(uri, key, value, 1, max_frames);
  } else if (key == "is-live") {
    params.is_live = parse_bool(uri, key, value);
  } else if (key == "error-after") {
    params.error_after = parse_int(uri, key, value, 0, max_frames);
  } else if (key == "stall-after") {
    params.stall_after = parse_int(uri, key, value, 0, max_frames);
  } else if (key == "stall-ms") {
    params.stall_ms = parse_int(uri, key, value, 1, 600'000);
  } else if (key == "eos-after") {
    params.eos_after = parse_int(uri, key, value, 0, max_frames);
  } else {
    fail(uri, key,
         "unknown test:// parameter (known: width, height, fps, num-buffers, is-live, "
         "error-after, stall-after, stall-ms, eos-after)");
  }
}

TestSourceParams parse_test(const std::string& uri, const std::string& rest) {
  TestSourceParams params;
  const auto question = rest.find('?');
  const std::string pattern = rest.substr(0, question);
  if (!pattern.empty()) {
    const bool valid = std::all_of(pattern.begin(), pattern.end(), [](unsigned char c) {
      return std::islower(c) || std::isdigit(c) || c == '-';
    });
    if (!valid) fail(uri, "pattern", "'" + pattern + "' is not a videotestsrc pattern name");
    params.pattern = pattern;
  }
  if (question == std::string::npos) return params;

  for_each_query_pair(uri, rest.substr(question + 1),
                      [&](const std::string& key, const std::string& value) {
                        apply_test_parameter(uri, key, value, params);
                      });
  if ((params.stall_after >= 0) != (params.stall_ms > 0)) {
    fail(uri, "stall-after", "stall-after and stall-ms go together");
  }
  return params;
}

ImageFolderParams parse_images_query(const std::string& uri, const std::string& query) {
  ImageFolderParams params;
  for_each_query_pair(uri, query, [&](const std::string& key, const std::string& value) {
    if (key == "fps") {
      params.fps = parse_fps(uri, key, value);
    } else if (key == "loop") {
      params.loop = parse_int(uri, key, value, 1, 1'000'000);
    } else {
      fail(uri, key, "unknown images:// parameter (known: fps, loop)");
    }
  });
  return params;
}

RecordingParams parse_recording_query(const std::string& uri, const std::string& query) {
  RecordingParams params;
  for_each_query_pair(uri, query, [&](const std::string& key, const std::string& value) {
    if (key != "fps") fail(uri, key, "unknown file:// parameter (known: fps)");
    params.fps = parse_fps(uri, key, value);
  });
  return params;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  const int lower = std::tolower(static_cast<unsigned char>(c));
  if (lower >= 'a' && lower <= 'f') return lower - 'a' + 10;
  return -1;
}

// file:// URIs may carry %XX escapes (e.g. %20 for a space); plain paths are taken literally.
std::string percent_decode(const std::string& uri, const std::string& text) {
  std::string decoded;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      decoded += text[i];
      continue;
    }
    const int high = i + 2 < text.size() ? hex_value(text[i + 1]) : -1;
    const int low = i + 2 < text.size() ? hex_value(text[i + 2]) : -1;
    if (high < 0 || low < 0) fail(uri, "path", "bad %-escape at position " + std::to_string(i));
    // A NUL cannot be in a path: decoded, it cut the path short and another file played.
    if (high == 0 && low == 0)
      fail(uri, "path", "%00 (a NUL byte) at position " + std::to_string(i));
    decoded += static_cast<char>(high * 16 + low);
    i += 2;
  }
  return decoded;
}

}  // namespace

VideoUri parse_video_uri(const std::string& text) {
  if (text.empty()) fail(text, "", "empty video source URI");
  VideoUri uri;
  uri.text = text;
  const auto separator = text.find("://");
  if (separator == std::string::npos) {
    std::error_code error;  // a path that cannot be examined is left to the file source to report
    uri.kind = std::filesystem::is_directory(text, error) ? SourceKind::images : SourceKind::file;
    uri.location = text;
    return uri;
  }
  const std::string scheme = lowercase(text.substr(0, separator));
  const std::string rest = text.substr(separator + 3);

  const auto kind = kSourceSchemes.parse(scheme);
  if (!kind) {
    fail(text, "scheme",
         "unknown scheme '" + scheme + "' (known: " + kSourceSchemes.alternatives() + ")");
  }
  uri.kind = *kind;
  switch (*kind) {
    case SourceKind::file: {
      // file://localhost/abs is the same file as file:///abs. A '?' starts the query, as in
      // every URI (RFC 8089); a file name holding one writes it %3F.
      const bool localhost = rest.rfind("localhost/", 0) == 0;
      const std::string path_and_query = localhost ? rest.substr(9) : rest;
      const auto question = path_and_query.find('?');
      uri.location = percent_decode(text, path_and_query.substr(0, question));
      if (uri.location.empty()) fail(text, "path", "no file path after file://");
      if (question != std::string::npos) {
        uri.recording = parse_recording_query(text, path_and_query.substr(question + 1));
      }
      break;
    }
    case SourceKind::v4l2: {
      if (all_digits(rest)) {
        uri.location = "/dev/video" + rest;
      } else if (rest.size() > 1 && rest[0] == '/') {
        uri.location = rest;
      } else {
        fail(text, "device", "expected v4l2:///dev/videoN or v4l2://N");
      }
      // A missing device is a camera not plugged in yet (a cold start, retried); a file or a
      // folder there never becomes a camera: retrying it forever hid the mistake.
      struct stat status {};
      if (::stat(uri.location.c_str(), &status) == 0 && !S_ISCHR(status.st_mode)) {
        fail(text, "device",
             "'" + uri.location + "' is " +
                 (S_ISDIR(status.st_mode) ? "a folder" : "not a device") +
                 ", expected a video device (/dev/videoN)");
      }
      break;
    }
    case SourceKind::csi:
      if (!all_digits(rest)) fail(text, "sensor-id", "expected csi://N with a sensor number");
      uri.sensor_id = parse_int(text, "sensor-id", rest, 0, 63);
      break;
    case SourceKind::rtsp: {
      std::string authority = rest.substr(0, rest.find('/'));
      authority = authority.substr(authority.rfind('@') == std::string::npos
                                       ? 0
                                       : authority.rfind('@') + 1);  // user:password@
      if (authority.empty() || authority[0] == ':') {
        fail(text, "host", "no host in the rtsp:// URL");
      }
      // The one HOST:PORT parser: [::1]:8554 works, a port out of range fails here, at once.
      std::string problem;
      if (!parse_host_port(authority, problem, scheme == "rtsps" ? 322 : 554)) {
        fail(text, "host", problem);
      }
      uri.location = text;
      break;
    }
    case SourceKind::images: {
      const auto question = rest.find('?');
      uri.location = percent_decode(text, rest.substr(0, question));
      if (uri.location.empty()) fail(text, "path", "no folder after images://");
      if (question != std::string::npos)
        uri.images = parse_images_query(text, rest.substr(question + 1));
      break;
    }
    case SourceKind::test:
      uri.test = parse_test(text, rest);
      break;
  }
  return uri;
}

bool is_live(const VideoUri& uri) {
  switch (uri.kind) {
    case SourceKind::file:
    case SourceKind::images:
      return false;
    case SourceKind::test:
      return uri.test.is_live;
    case SourceKind::v4l2:
    case SourceKind::csi:
    case SourceKind::rtsp:
      return true;
  }
  return true;
}

std::string source_uri_schemes() {
  std::string text;
  for (const auto& entry : kSourceSchemes.entries()) {
    text += (text.empty() ? "" : ", ") + std::string(entry.second) + "://";
  }
  return text;
}

const char* to_string(SourceKind kind) {
  // Every name in the table is a literal, so its view is NUL-terminated.
  return kSourceSchemes.name(kind).data();
}

}  // namespace rtmot::platform
