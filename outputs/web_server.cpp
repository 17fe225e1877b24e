#include "outputs/web_server.hpp"

#include <civetweb.h>
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>

namespace rtmot::outputs {
namespace {

// Compares without stopping at the first difference: the time taken says nothing about how much of
// a guessed token was right.
bool same_secret(const std::string& given, const std::string& expected) {
  unsigned char difference = given.size() == expected.size() ? 0 : 1;
  for (std::size_t i = 0; i < given.size(); ++i) {
    difference |= static_cast<unsigned char>(given[i] ^ expected[i % expected.size()]);
  }
  return difference == 0;
}

}  // namespace

std::filesystem::path find_static_dir() {
  return find_page_dir("index.html", "output.web_port");
}

WebServer::WebServer(WebContent content, const std::string& bind_address, std::uint16_t port,
                     const std::filesystem::path& static_dir)
    : content_(std::move(content)),
      files_(static_dir, "index.html", "output.web_port"),
      server_(bind_address, port, "output.web_port") {
  // civetweb tries exact URIs first, then "/video" as a prefix ("/video/..."), then the pattern.
  server_.handle("/api/status", &WebServer::serve_status, this);
  server_.handle("/api/events", &WebServer::serve_events, this);
  server_.handle("/api/settings", &WebServer::serve_settings, this);
  server_.handle("/video", &WebServer::serve_video, this);
  server_.handle("**", &WebServer::serve_static, this);
}

WebServer::~WebServer() {
  // The MJPEG workers see this within one wait for a picture and end; server_ joins them.
  stopping_.store(true, std::memory_order_relaxed);
}

int WebServer::serve_static(mg_connection* connection, void* self) {
  return static_cast<WebServer*>(self)->files_.serve(connection);
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
  nlohmann::json watchers = nlohmann::json::array();
  for (const LivePicture* picture : server.content_.pictures) {
    encoded.push_back(picture->pictures_encoded());
    watchers.push_back(picture->watchers());
  }
  status["pictures_encoded"] = std::move(encoded);
  // Per source, the MJPEG clients streaming now (a client that went away counts until its worker's
  // next write fails: one picture later).
  status["watchers"] = std::move(watchers);
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
