#include "outputs/listen_web_server.hpp"

#include <civetweb.h>

#include <cstring>

#include "platform/clock.hpp"

namespace rtmot::outputs {
namespace {

constexpr const char* kPage = "listen.html";
constexpr const char* kField = "--web-port";

}  // namespace

std::filesystem::path ListenWebServer::find_static_dir() {
  return find_page_dir(kPage, kField);
}

ListenWebServer::ListenWebServer(const ListenBoard& board, const std::string& bind_address,
                                 std::uint16_t port, const std::filesystem::path& static_dir)
    : board_(board), files_(static_dir, kPage, kField), server_(bind_address, port, kField) {
  server_.handle("/api/listen", &ListenWebServer::serve_listen, this);
  server_.handle("**", &ListenWebServer::serve_static, this);
}

int ListenWebServer::serve_static(mg_connection* connection, void* self) {
  return static_cast<ListenWebServer*>(self)->files_.serve(connection);
}

int ListenWebServer::serve_listen(mg_connection* connection, void* self) {
  const auto& server = *static_cast<ListenWebServer*>(self);
  const mg_request_info* request = mg_get_request_info(connection);
  if (request->request_method == nullptr || std::strcmp(request->request_method, "GET") != 0) {
    return respond_error(connection, 405, "Method Not Allowed", "the ground station only reads");
  }
  return respond(connection, 200, "OK", "application/json",
                 server.board_.to_json(platform::steady_now_ns()).dump());
}

}  // namespace rtmot::outputs
