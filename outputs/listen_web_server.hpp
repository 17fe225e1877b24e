#pragma once
// The ground station's page (`rtmot listen --web-port`, docs/web.md): read-only, so no token.
//   GET /              the page (listen.html), and the other files of the pages' folder by their
//                      names only (listen.js, style.css; outputs/web_site.hpp)
//   GET /api/listen    JSON: per stream heard its tracks, frame size, loss statistics, counts,
//                      rate and age (outputs/listen_board.hpp)
// Every other method is 405: nothing is written through it.
#include <cstdint>
#include <filesystem>
#include <string>

#include "outputs/listen_board.hpp"
#include "outputs/web_site.hpp"

namespace rtmot::outputs {

class ListenWebServer {
 public:
  /// Reads the pages' folder and listens on `bind_address`:`port` at once; throws InputError
  /// naming --web-port (ExitCode::network if it cannot listen). `board` outlives the server.
  ListenWebServer(const ListenBoard& board, const std::string& bind_address, std::uint16_t port,
                  const std::filesystem::path& static_dir);

  const std::string& url() const { return server_.url(); }
  const std::filesystem::path& static_dir() const { return files_.folder(); }

  /// The pages' folder holding listen.html (outputs/web_site.hpp: find_page_dir).
  static std::filesystem::path find_static_dir();

 private:
  static int serve_static(mg_connection* connection, void* self);
  static int serve_listen(mg_connection* connection, void* self);

  const ListenBoard& board_;
  StaticFiles files_;  // "/" is listen.html
  PageServer server_;  // last: stopped (its workers joined) before the members they use go
};

}  // namespace rtmot::outputs
