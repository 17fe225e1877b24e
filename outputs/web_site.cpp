#include "outputs/web_site.hpp"

#include <civetweb.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/input_path.hpp"
#include "outputs/civetweb_library.hpp"
#include "platform/host_port.hpp"

namespace rtmot::outputs {
namespace {

// The types of the files the pages are made of; another file in the folder is not served.
const char* content_type(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".js") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".png") return "image/png";
  return nullptr;
}

}  // namespace

const char* const kSafeHeaders =
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

std::string request_path(mg_connection* connection) {
  const char* path = mg_get_request_info(connection)->local_uri_raw;
  return path != nullptr ? path : "";
}

std::filesystem::path find_page_dir(const std::string& page, const std::string& field) {
  std::vector<std::filesystem::path> candidates;
  const std::filesystem::path installed = installed_data_dir();
  if (!installed.empty()) candidates.push_back(installed / "web");
  candidates.emplace_back(RTMOT_WEB_SOURCE_DIR);
  std::string tried;
  for (const auto& folder : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(folder / page, error)) return folder;
    tried += (tried.empty() ? "" : ", ") + folder.string();
  }
  throw InputError("", 0, field, "the page's files are missing (looked in " + tried + ")");
}

StaticFiles::StaticFiles(const std::filesystem::path& folder, const std::string& index,
                         const std::string& field)
    : folder_(folder) {
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const char* type = content_type(entry.path());
    if (type == nullptr || !entry.is_regular_file()) continue;
    files_["/" + entry.path().filename().string()] = File{type, read_text_file(entry.path())};
  }
  const auto page = files_.find("/" + index);
  if (page == files_.end()) throw InputError(folder.string(), 0, field, "no " + index);
  files_["/"] = page->second;
}

int StaticFiles::serve(mg_connection* connection) const {
  const mg_request_info* request = mg_get_request_info(connection);
  if (request->request_method == nullptr || std::strcmp(request->request_method, "GET") != 0) {
    return respond_error(connection, 405, "Method Not Allowed", "only GET here");
  }
  // By name only: the request path must be one of the files read at start ("/app.js"), so a path
  // with "..", "%2e%2e", a slash or a link inside leads nowhere.
  const auto file = files_.find(request_path(connection));
  if (file == files_.end()) return respond_error(connection, 404, "Not Found", "no such page");
  return respond(connection, 200, "OK", file->second.type.c_str(), file->second.body);
}

PageServer::PageServer(const std::string& bind_address, std::uint16_t port,
                       const std::string& field)
    : url_("http://" + platform::format_host_port(bind_address, port) + "/") {
  ensure_civetweb_library();
  const std::string ports = platform::format_host_port(bind_address, port);
  const std::string workers = std::to_string(kWorkers);
  const std::string head = std::to_string(kMaxRequestHead);
  // Beyond the workers, connections wait in a bounded queue, then in the kernel's bounded
  // backlog. 5 s for a request: a page over a slow link; a client that stops reading is dropped
  // when a write waits longer than that.
  const char* options[] = {"listening_ports",
                           ports.c_str(),
                           "num_threads",
                           workers.c_str(),
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
                           head.c_str(),
                           nullptr};
  mg_callbacks callbacks{};
  context_ = mg_start(&callbacks, nullptr, options);
  if (context_ == nullptr) {
    throw InputError(url_, 0, field, "cannot listen (port in use?)", ExitCode::network);
  }
}

PageServer::~PageServer() {
  mg_stop(context_);
}

void PageServer::handle(const char* uri, Handler handler, void* data) {
  mg_set_request_handler(context_, uri, handler, data);
}

}  // namespace rtmot::outputs
