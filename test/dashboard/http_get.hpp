// Plain sockets to the dashboard for its tests: a loopback connection, one HTTP/1.0 GET (Host 127.0.0.1:PORT unless
// `headers`, each ending in \r\n, has one) giving the status code and the body, and a WebSocket client's frames.
#pragma once

#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
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

// A WebSocket client socket after the handshake on /ws (-1 if refused); rcvbuf > 0 makes a client whose receive
// buffer fills at once when it does not read.
inline int ws_connect(int port, int rcvbuf = 0) {
  const int fd = connect_loopback(port, rcvbuf);
  if (fd < 0) return -1;
  const std::string req = "GET /ws HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                          "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                          "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";
  (void)!::write(fd, req.data(), req.size());
  std::string head;
  char c;
  while (head.find("\r\n\r\n") == std::string::npos && ::read(fd, &c, 1) == 1) head += c;
  if (head.find(" 101 ") == std::string::npos) return ::close(fd), -1;
  return fd;
}

// A client frame's header (FIN, opcode, masked with a zero key) declaring `length` bytes of payload.
inline std::string ws_frame_header(uint64_t length, int opcode = 1) {
  std::string h(1, char(0x80 | opcode));
  if (length < 126) {
    h += char(0x80 | length);
  } else if (length <= 0xffff) {
    h += char(0x80 | 126);
    for (int k = 1; k >= 0; --k) h += char((length >> (8 * k)) & 0xff);
  } else {
    h += char(0x80 | 127);
    for (int k = 7; k >= 0; --k) h += char((length >> (8 * k)) & 0xff);
  }
  return h + std::string(4, '\0');  // a zero mask leaves the payload as it is
}

inline bool ws_send_text(int fd, const std::string& text) {
  const std::string frame = ws_frame_header(text.size()) + text;
  return ::write(fd, frame.data(), frame.size()) == ssize_t(frame.size());
}

inline bool read_exactly(int fd, void* to, size_t n) {
  auto* p = static_cast<char*>(to);
  while (n > 0) {
    const ssize_t got = ::read(fd, p, n);
    if (got <= 0) return false;
    p += got;
    n -= size_t(got);
  }
  return true;
}

struct WsFrame {
  int opcode = -1;  // -1: the connection ended (or the read timed out) before a whole frame
  std::string payload;
};

// The server's next frame (servers do not mask).
inline WsFrame ws_read(int fd) {
  WsFrame f;
  unsigned char h[2];
  if (!read_exactly(fd, h, 2)) return f;
  uint64_t length = h[1] & 0x7f;
  if (length >= 126) {
    unsigned char ext[8];
    const size_t n = length == 126 ? 2 : 8;
    if (!read_exactly(fd, ext, n)) return f;
    length = 0;
    for (size_t k = 0; k < n; ++k) length = (length << 8) | ext[k];
  }
  f.payload.resize(length);
  if (length > 0 && !read_exactly(fd, f.payload.data(), length)) return f;
  f.opcode = h[0] & 0x0f;
  return f;
}

}  // namespace lcm_control::dashboard
