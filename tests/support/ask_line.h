// One request on a line-based socket (the control socket): sends `line` and a
// newline, reads up to the next newline. "<send failed>" or "<no reply>" when
// the socket fails or closes (a receive timeout set on it bounds the wait).
#pragma once

#include <sys/socket.h>
#include <sys/types.h>

#include <string>

namespace candela::test {

inline std::string ask_line(int fd, const std::string& line) {
  const std::string msg = line + "\n";
  if (send(fd, msg.data(), msg.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(msg.size()))
    return "<send failed>";
  std::string reply;
  char c;
  while (recv(fd, &c, 1, 0) == 1) {
    if (c == '\n') return reply;
    reply += c;
  }
  return "<no reply>";
}

}  // namespace candela::test
