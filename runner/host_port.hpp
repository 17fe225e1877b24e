#pragma once
// HOST:PORT as the run configuration and `--udp` take it, with the error a user sees (file, line,
// field, exit code). The parsing itself is platform/host_port.hpp's, the one parser of addresses:
// a name or an IPv4 address, or an IPv6 address in brackets ([::1]:5600), and a port in 1..65535.
#include <string>

#include "common/exit_codes.hpp"
#include "platform/host_port.hpp"

namespace rtmot::runner {

using HostPort = platform::HostPort;

/// Throws InputError naming `file`, `line` and `field`, with `code` (bad_input for a configuration
/// file, usage for the command line), if `text` is not HOST:PORT.
HostPort parse_host_port(const std::string& text, const std::string& file, int line,
                         const std::string& field, ExitCode code);

}  // namespace rtmot::runner
