#include "outputs/web_server.hpp"

#include <civetweb.h>
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/input_path.hpp"
#include "outputs/civetweb_library.hpp"
#include "platform/host_port.hpp"

namespace rtmot::outputs {
namespace {

// The types of the files the page is made of; another file in the folder is not served.
const char* content_type(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".js") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".png") return "image/png";
  return nullptr;
}

// Each response says what it is and that the browser must not guess it or frame it elsewhere.
constexpr const char* kSafeHeaders =
    "X-Content-Type-Options: nosniff\r\nX-Frame-Options: DENY\r\n"
    "Cache-Control: no-store\r\nConnection: close\r\n";

int respond(mg_connection* connection, int status, const char* reason, const char* type,
            const std::string& body) {
  mg_printf(connection, "HTTP/1.1 %d %s\r\nContent-Type: %s\r\nContent-Length: %zu\r\n%s\r\n",
            status, reason, type, body.size(), kSafeHeaders);
  mg_write(connection, body.data(), body.size());
  return status;
}

int respond_error(mg_connection* connection, int status, const char* reason,
                  const std::string& why) {
  return respond(connection, status, reason, "application/json",
                 nlohmann::json{{"error", why}}.dump());
}

// Compares without stopping at the first difference: the time taken says nothing about how much of
// a guessed token was right.
bool same_secret(const std::string& given, const std::string& expected) {
  unsigned char difference = given.size() == expected.size() ? 0 : 1;
  for (std::size_t i = 0; i < given.size(); ++i) {
    difference |= static_cast<unsigned char>(given[i] ^ expected[i % expected.size()]);
  }
  return difference == 0;
}

// The request's path, decoded ("" when the request names no path on this server).
std::string request_path(mg_connection* connection) {
  const char* path = mg_get_request_info(connection)->local_uri_raw;
  return path != nullptr ? path : "";
}

}  // namespace

std::filesystem::path find_static_dir() {
  std::vector<std::filesystem::path> candidates;
  const std::filesystem::path installed = installed_data_dir();
  if (!installed.empty()) candidates.push_back(installed / "web");
  candidates.emplace_back(RTMOT_WEB_SOURCE_DIR);
  std::string tried;
  for (const auto& folder : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(folder / "index.html", error)) return folder;
    tried += (tried.empty() ? "" : ", ") + folder.string();
  }
  throw InputError("", 0, "output.web_port",
                   "the page's files are missing (looked in " + tried + ")");
}

WebServer::WebServer(WebContent content, const std::string& bind_address, std::uint16_t port,
                     const std::filesystem::path& static_dir)
    : content_(std::move(content)),
      url_("http://" + platform::format_host_port(bind_address, port) + "/"),
      static_dir_(static_dir) {
  for (const auto& entry : std::filesystem::directory_iterator(static_dir)) {
    const char* type = content_type(entry.path());
    if (type == nullptr || !entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    files_["/" + name] = StaticFile{type, read_text_file(entry.path())};
  }
  if (files_.count("/index.html") == 0) {
    throw InputError(static_dir.string(), 0, "output.web_port", "no index.html");
  }
  files_["/"] = files_["/index.html"];
  ensure_civetweb_library();
  const std::string ports = platform::format_host_port(bind_address, port);
  // 8 workers: kMaxWatchers MJPEG clients hold one each; the others serve the page and its status
  // polls (one request a second per open page). Beyond them, connections wait in a bounded queue,
  // then in the kernel's bounded backlog. 5 s for a request: a page over a slow link. A client
  // that stops reading its MJPEG stream is dropped when a write waits longer than that.
  const char* options[] = {"listening_ports",
                           ports.c_str(),
                           "num_threads",
                           "8",
                           "request_timeout_ms",
                           "5000",
                           "enable_keep_alive",
                           "no",
                           "linger_timeout_ms",
                           "0",
                           "connection_queue",
                           "16",
                           "listen_backlog",
                           "32",
                           "max_request_size",
                           "8192",
                           nullptr};
  mg_callbacks callbacks{};
  context_ = mg_start(&callbacks, nullptr, options);
  if (context_ == nullptr) {
    throw InputError(url_, 0, "output.web_port", "cannot listen (port in use?)", ExitCode::network);
  }
  // civetweb tries exact URIs first, then "/video" as a prefix ("/video/..."), then the pattern.
  mg_set_request_handler(context_, "/api/status", &WebServer::serve_status, this);
  mg_set_request_handler(context_, "/api/events", &WebServer::serve_events, this);
  mg_set_request_handler(context_, "/api/settings", &WebServer::serve_settings, this);
  mg_set_request_handler(context_, "/video", &WebServer::serve_video, this);
  mg_set_request_handler(context_, "**", &WebServer::serve_static, this);
}

WebServer::~WebServer() {
  // The MJPEG workers see this within one wait for a picture and end; mg_stop joins them.
  stopping_.store(true, std::memory_order_relaxed);
  if (context_ != nullptr) mg_stop(context_);
}

int WebServer::serve_static(mg_connection* connection, void* self) {
  const auto& server = *static_cast<WebServer*>(self);
  const mg_request_info* request = mg_get_request_info(connection);
  if (request->request_method == nullptr || std::strcmp(request->request_method, "GET") != 0) {
    return respond_error(connection, 405, "Method Not Allowed", "only GET here");
  }
  // By name only: the request path must be one of the files read at start ("/app.js"), so a path
  // with "..", "%2e%2e", a slash or a link inside leads nowhere.
  const auto file = server.files_.find(request_path(connection));
  if (file == server.files_.end()) {
    return respond_error(connection, 404, "Not Found", "no such page");
  }
  return respond(connection, 200, "OK", file->second.type.c_str(), file->second.body);
}

int WebServer::serve_status(mg_connection* connection, void* self) {
  auto& server = *static_cast<WebServer*>(self);
  nlohmann::json status = server.content_.metrics->status();
  status["detector"] = server.content_.detector;
  if (server.content_.geometry) {
    status["geometry"] = server.content_.geometry();
  } else {
    const std::lock_guard<std::mutex> lock(server.geometry_mutex_);
    status["geometry"] = server.content_.sources;
  }
  status["writes"] = !server.content_.token.empty() && server.content_.save_events != nullptr;
  if (server.content_.settings) status["settings"] = server.content_.settings();
  // Per source, the pictures encoded so far: 0 until someone first watches (nobody watching costs
  // nothing; the system test checks it).
  nlohmann::json encoded = nlohmann::json::array();
  for (const LivePicture* picture : server.content_.pictures) {
    encoded.push_back(picture->pictures_encoded());
  }
  status["pictures_encoded"] = std::move(encoded);
  return respond(connection, 200, "OK", "application/json", status.dump());
}

int WebServer::serve_video(mg_connection* connection, void* self) {
  auto& server = *static_cast<WebServer*>(self);
  // "/video/N.mjpg", N the source's place in the run (0, 1, ...).
  const std::string path = request_path(connection);
  const std::string prefix = "/video/";
  if (path.compare(0, prefix.size(), prefix) != 0) {
    return respond_error(connection, 404, "Not Found", "no such source");
  }
  const char* name = path.c_str() + prefix.size();
  char* end = nullptr;
  const unsigned long index = std::strtoul(name, &end, 10);
  if (end == name || std::strcmp(end, ".mjpg") != 0 || index >= server.content_.pictures.size()) {
    return respond_error(connection, 404, "Not Found", "no such source");
  }
  if (server.watchers_.fetch_add(1, std::memory_order_relaxed) >= kMaxWatchers) {
    server.watchers_.fetch_sub(1, std::memory_order_relaxed);
    return respond_error(connection, 503, "Service Unavailable",
                         fmt::format("at most {} pictures are watched at once", kMaxWatchers));
  }
  const int status = server.stream_video(connection, *server.content_.pictures[index]);
  server.watchers_.fetch_sub(1, std::memory_order_relaxed);
  return status;
}

int WebServer::stream_video(mg_connection* connection, LivePicture& picture) {
  mg_printf(connection,
            "HTTP/1.1 200 OK\r\nContent-Type: multipart/x-mixed-replace; boundary=frame\r\n%s\r\n",
            kSafeHeaders);
  const LivePicture::Watcher watching(picture);
  std::uint64_t sequence = 0;
  // Ends when the client goes (a write fails) or the server stops; a source that sends nothing
  // (its end, an outage) sends the client nothing either.
  while (!stopping_.load(std::memory_order_relaxed)) {
    const Jpeg jpeg = picture.next_jpeg(sequence, std::chrono::milliseconds(200));
    if (!jpeg) continue;
    const std::string head = fmt::format(
        "--frame\r\nContent-Type: image/jpeg\r\nContent-Length: {}\r\n\r\n", jpeg->size());
    if (mg_write(connection, head.data(), head.size()) <= 0 ||
        mg_write(connection, jpeg->data(), jpeg->size()) <= 0 ||
        mg_write(connection, "\r\n", 2) <= 0) {
      break;
    }
  }
  return 200;
}

int WebServer::read_write(mg_connection* connection, bool enabled, std::string& body) const {
  const mg_request_info* request = mg_get_request_info(connection);
  if (request->request_method == nullptr || std::strcmp(request->request_method, "POST") != 0) {
    return respond_error(connection, 405, "Method Not Allowed", "POST here");
  }
  // The token before anything else is looked at: without it nothing of the request is read.
  if (content_.token.empty() || !enabled) {
    return respond_error(connection, 403, "Forbidden",
                         "writes are off: start rtmot run with --web-token-file (docs/web.md)");
  }
  const char* authorization = mg_get_header(connection, "Authorization");
  const std::string bearer = "Bearer ";
  if (authorization == nullptr || std::strncmp(authorization, bearer.c_str(), bearer.size()) != 0) {
    return respond_error(connection, 401, "Unauthorized",
                         "a write needs the header Authorization: Bearer TOKEN");
  }
  if (!same_secret(authorization + bearer.size(), content_.token)) {
    return respond_error(connection, 403, "Forbidden", "wrong token");
  }
  if (request->content_length < 0) {
    return respond_error(connection, 411, "Length Required", "the body's length is required");
  }
  if (request->content_length > kMaxBody) {
    return respond_error(connection, 413, "Payload Too Large",
                         fmt::format("the body may be at most {} bytes", kMaxBody));
  }
  body.assign(static_cast<std::size_t>(request->content_length), '\0');
  std::size_t got = 0;
  while (got < body.size()) {
    const int n = mg_read(connection, body.data() + got, body.size() - got);
    if (n <= 0) return respond_error(connection, 400, "Bad Request", "the body was cut short");
    got += static_cast<std::size_t>(n);
  }
  return 0;
}

namespace {

int respond_answer(mg_connection* connection, const SaveAnswer& answer) {
  const char* reason = answer.status == 200   ? "OK"
                       : answer.status == 400 ? "Bad Request"
                       : answer.status == 404 ? "Not Found"
                                              : "Internal Server Error";
  return respond(connection, answer.status, reason, "application/json", answer.body.dump());
}

}  // namespace

int WebServer::serve_settings(mg_connection* connection, void* self) {
  auto& server = *static_cast<WebServer*>(self);
  std::string body;
  if (const int refused =
          server.read_write(connection, server.content_.save_settings != nullptr, body)) {
    return refused;
  }
  return respond_answer(connection, server.content_.save_settings(body));
}

int WebServer::serve_events(mg_connection* connection, void* self) {
  auto& server = *static_cast<WebServer*>(self);
  std::string body;
  if (const int refused =
          server.read_write(connection, server.content_.save_events != nullptr, body)) {
    return refused;
  }
  const mg_request_info* request = mg_get_request_info(connection);
  const char* query = request->query_string;
  char number[16] = {};
  if (query == nullptr ||
      mg_get_var(query, std::strlen(query), "source", number, sizeof number) <= 0) {
    return respond_error(connection, 400, "Bad Request", "which source: ?source=N");
  }
  char* end = nullptr;
  const unsigned long index = std::strtoul(number, &end, 10);
  if (end == number || *end != '\0') {
    return respond_error(connection, 400, "Bad Request", "source: not a number");
  }
  SaveAnswer answer = server.content_.save_events(index, body);
  if (answer.status == 200 && index < server.content_.sources.size()) {
    const std::lock_guard<std::mutex> lock(server.geometry_mutex_);
    server.content_.sources[index] = std::move(answer.geometry);
  }
  return respond_answer(connection, answer);
}

}  // namespace rtmot::outputs
