#include "workspace.hpp"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "shared_data.hpp"

namespace rtmot::test {

namespace fs = std::filesystem;

Workspace::Workspace(const std::string& case_name)
    : dir_(fs::temp_directory_path() /
           ("rtmot-catalogue-" + std::to_string(getpid()) + "-" + case_name)) {
  fs::remove_all(dir_);
  fs::create_directories(dir_);
}

Workspace::~Workspace() {
  for (const int socket : held_sockets_) close(socket);
  std::error_code ignored;
  fs::remove_all(dir_, ignored);
}

void Workspace::write(const std::string& relative, const std::string& text) const {
  const auto file = path(relative);
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

void Workspace::copy_sequence(const std::string& name, const std::string& relative) const {
  const auto source = shared_path("data/mot15-train/" + name);
  if (!fs::exists(source / "seqinfo.ini"))
    throw std::runtime_error("missing test data: " + source.string());
  const auto target = path(relative);
  fs::create_directories(target / "det");
  fs::create_directories(target / "gt");
  fs::copy_file(source / "seqinfo.ini", target / "seqinfo.ini");
  fs::copy_file(source / "det/det.txt", target / "det/det.txt");
  fs::copy_file(source / "gt/gt.txt", target / "gt/gt.txt");
}

void Workspace::replace_line(const std::string& relative, int line_number,
                             const std::string& text) const {
  std::istringstream in(read_text(path(relative)));
  std::ostringstream out;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    out << (number == line_number ? text : line) << '\n';
  }
  write(relative, out.str());
}

void Workspace::truncate(const std::string& relative, std::uintmax_t bytes) const {
  fs::resize_file(path(relative), bytes);
}

int Workspace::occupy_udp_port() {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) throw std::runtime_error("socket() failed");
  held_sockets_.push_back(fd);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof address;
  if (bind(fd, reinterpret_cast<sockaddr*>(&address), length) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0)
    throw std::runtime_error("cannot bind a UDP port");
  return ntohs(address.sin_port);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::function<void(const Workspace&)> no_temporaries(const std::string& folder) {
  return [folder](const Workspace& ws) {
    if (!std::filesystem::exists(ws.path(folder))) return;
    for (const auto& entry : std::filesystem::directory_iterator(ws.path(folder))) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
          << "temporary left behind: " << entry.path();
    }
  };
}

}  // namespace rtmot::test
