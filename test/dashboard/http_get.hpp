// Plain sockets to the dashboard for its tests: a loopback connection, and one HTTP/1.0 GET (Host 127.0.0.1:PORT
// unless `headers`, each ending in \r\n, has one) giving the status code and the body.
#pragma once

#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace lcm_control::dashboard {

struct HttpReply {
  int status = -1;
  std::string body;
};

// A TCP socket connected to 127.0.0.1:port with a 5 s read timeout (and SO_RCVBUF rcvbuf, if > 0); -1 if refused.
inline int connect_loopback(int port, int rcvbuf = 0) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (rcvbuf > 0) setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  timeval tv{5, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

inline HttpReply http_get(int port, const std::string& path, const std::string& headers = "") {
  HttpReply r;
  const int fd = connect_loopback(port);
  if (fd < 0) return r;
  const std::string host = headers.find("Host:") == std::string::npos
                               ? "Host: 127.0.0.1:" + std::to_string(port) + "\r\n"
                               : "";
  const std::string req = "GET " + path + " HTTP/1.0\r\n" + host + headers + "\r\n";
  (void)!::write(fd, req.data(), req.size());
  std::string all;
  char buf[4096];
  ssize_t n;
  while ((n = ::read(fd, buf, sizeof buf)) > 0) all.append(buf, size_t(n));
  ::close(fd);
  if (all.size() >= 12 && all.compare(0, 5, "HTTP/") == 0) r.status = std::atoi(all.c_str() + 9);
  const size_t head_end = all.find("\r\n\r\n");
  if (head_end != std::string::npos) r.body = all.substr(head_end + 4);
  return r;
}

}  // namespace lcm_control::dashboard
