#pragma once
// What the two pages' servers share (docs/web.md): `rtmot run`'s operator page
// (outputs/web_server.hpp) and `rtmot listen`'s ground-station page
// (outputs/listen_web_server.hpp). The same civetweb bounds (workers, queue, request head, time
// to send a request), the same response headers, and the page's files read once from one folder
// and served by exact name only, so that no request can name a file outside that folder.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

struct mg_context;
struct mg_connection;

namespace rtmot::outputs {

/// The headers every answer carries: what it is, that the browser must not guess it or frame it
/// elsewhere, that it is not cached, and that the connection ends with it (no keep-alive).
extern const char* const kSafeHeaders;

/// Answers `body` of `type` with `status`; returns `status` (what civetweb's handlers return).
int respond(mg_connection* connection, int status, const char* reason, const char* type,
            const std::string& body);
/// Answers JSON {"error": why}.
int respond_error(mg_connection* connection, int status, const char* reason,
                  const std::string& why);
/// The request's path as sent, undecoded ("" when the request names none).
std::string request_path(mg_connection* connection);

/// The folder of the pages' files: next to an installed binary (<prefix>/share/rtmot/web), else
/// the source tree's web/ (a build folder's binary). Throws InputError naming `field` if neither
/// holds `page`.
std::filesystem::path find_page_dir(const std::string& page, const std::string& field);

/// The page's files (.html, .js, .css, .png of one folder), read once at start; "/" is `index`.
class StaticFiles {
 public:
  /// Throws InputError naming `field` if `index` is not in `folder`.
  StaticFiles(const std::filesystem::path& folder, const std::string& index,
              const std::string& field);

  /// GET of one of the files by its exact name ("/app.js"): 200 with it. Another path: 404 (a
  /// path with "..", "%2e%2e", a slash or a link inside names nothing); another method: 405.
  int serve(mg_connection* connection) const;
  const std::filesystem::path& folder() const { return folder_; }

 private:
  struct File {
    std::string type;
    std::string body;
  };
  std::map<std::string, File> files_;  // by request path
  std::filesystem::path folder_;
};

/// A civetweb server with the pages' bounds, listening from construction until destruction (which
/// waits for its workers: a handler that loops must watch a flag its owner sets before).
class PageServer {
 public:
  using Handler = int (*)(mg_connection* connection, void* data);
  /// Most connections served at once (civetweb's workers); more wait in a queue of 16, then in
  /// the kernel's backlog of 32.
  static constexpr int kWorkers = 8;
  /// The largest request head (request line and headers) accepted.
  static constexpr int kMaxRequestHead = 8192;

  /// Throws InputError (ExitCode::network) naming `field` if it cannot listen.
  PageServer(const std::string& bind_address, std::uint16_t port, const std::string& field);
  ~PageServer();
  PageServer(const PageServer&) = delete;
  PageServer& operator=(const PageServer&) = delete;

  /// Requests for `uri` (civetweb's matching: exact first, then as a prefix; "**" anything) go to
  /// `handler` with `data`.
  void handle(const char* uri, Handler handler, void* data);
  /// "http://ADDRESS:PORT/", for the start-up log.
  const std::string& url() const { return url_; }

 private:
  std::string url_;
  mg_context* context_{nullptr};
};

}  // namespace rtmot::outputs
