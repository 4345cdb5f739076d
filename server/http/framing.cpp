#include "server/http/framing.h"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <vector>

#include "server/http/byte_ranges.h"

namespace spinfold::server {

namespace {

thread_local const std::string* tl_request_bytes = nullptr;

// [bytes] kept of a request beyond twice the body limit: room for its head (httplib reads lines of
// any length; the front bounds them at 8 KiB).
constexpr std::size_t kKeptHead = std::size_t{1} << 20;

constexpr std::uint64_t kSaturated = ~std::uint64_t{0};

bool is_tchar(unsigned char c) {
  return std::isalnum(c) ||
         std::string_view("!#$%&'*+-.^_`|~").find(static_cast<char>(c)) != std::string_view::npos;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Elements of a comma-separated list, trimmed (empty elements kept: the caller refuses them).
std::vector<std::string_view> elements(std::string_view list) {
  std::vector<std::string_view> out;
  while (true) {
    const std::size_t comma = list.find(',');
    out.push_back(trimmed(list.substr(0, comma)));
    if (comma == std::string_view::npos) return out;
    list.remove_prefix(comma + 1);
  }
}

// 1*DIGIT, saturated; nullopt for anything else (a sign, a space, an empty value).
std::optional<std::uint64_t> digits(std::string_view s) {
  if (s.empty()) return std::nullopt;
  std::uint64_t n = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    const std::uint64_t d = static_cast<std::uint64_t>(c - '0');
    n = n > (kSaturated - d) / 10 ? kSaturated : n * 10 + d;
  }
  return n;
}

// RFC 3986's host [":" port]: a reg-name (unreserved, pct-encoded, sub-delims but the comma) or an
// IPv4 address, or an IP literal in brackets. The comma (a sub-delim) is refused too: "a,b" is what
// a list of two Host values looks like once folded, and no name served here has one.
bool valid_authority(std::string_view v) {
  std::string_view host = v, port;
  if (v.starts_with('[')) {
    const std::size_t close = v.find(']');
    if (close == std::string_view::npos) return false;
    const std::string_view literal = v.substr(1, close - 1);
    if (literal.empty() || literal.find_first_not_of("0123456789abcdefABCDEF:.") != std::string_view::npos)
      return false;
    host = v.substr(0, close + 1);
    const std::string_view rest = v.substr(close + 1);
    if (!rest.empty() && rest.front() != ':') return false;
    port = rest.empty() ? rest : rest.substr(1);
    if (!rest.empty() && port.empty()) return true;  // "[::1]:" (an empty port is allowed)
  } else {
    const std::size_t colon = v.rfind(':');
    if (colon != std::string_view::npos) host = v.substr(0, colon), port = v.substr(colon + 1);
    if (host.empty()) return false;
    for (const char c : host)
      if (!std::isalnum(static_cast<unsigned char>(c)) &&
          std::string_view("-._~!$&'()*+;=%").find(c) == std::string_view::npos)
        return false;
  }
  return port.find_first_not_of("0123456789") == std::string_view::npos && port.size() <= 5;
}

Framing refused(int status, std::string field, std::string_view value, std::string reason) {
  Framing f;
  f.status = status;
  f.field = std::move(field);
  f.value = std::string(value.substr(0, 200));
  f.reason = std::move(reason);
  return f;
}

// A line of `bytes` from `at`: its text without the line ending, and the offset after it; nullopt
// when no LF follows.
struct Line {
  std::string_view text;
  std::size_t next;
  bool crlf;
};
std::optional<Line> line_at(std::string_view bytes, std::size_t at) {
  const std::size_t lf = bytes.find('\n', at);
  if (lf == std::string_view::npos) return std::nullopt;
  const bool crlf = lf > at && bytes[lf - 1] == '\r';
  return Line{bytes.substr(at, lf - at - (crlf ? 1 : 0)), lf + 1, crlf};
}

}  // namespace

Framing read_framing(std::string_view bytes) {
  const auto request_line = line_at(bytes, 0);
  if (!request_line) return refused(400, "", "", "the request head is incomplete");
  if (!request_line->crlf) return refused(400, "", "", "the request line ends in LF alone: CRLF is required");
  const std::string_view target = [&] {
    const std::string_view line = request_line->text;
    const std::size_t first = line.find(' ');
    if (first == std::string_view::npos) return std::string_view();
    const std::size_t second = line.find(' ', first + 1);
    return line.substr(first + 1,
                       second == std::string_view::npos ? std::string_view::npos : second - first - 1);
  }();
  const std::string path = lower(target.substr(0, target.find('?')));
  const std::string method(request_line->text.substr(0, request_line->text.find(' ')));

  std::optional<std::uint64_t> length;
  std::string length_text;
  std::vector<std::string_view> codings;
  bool has_coding = false;
  std::vector<std::string_view> hosts;
  std::size_t at = request_line->next;
  while (true) {
    const auto line = line_at(bytes, at);
    if (!line) return refused(400, "", "", "the request head is incomplete");
    if (!line->crlf)
      return refused(400, "", line->text, "a header line ends in LF alone: CRLF is required (RFC 9112 §2.2)");
    at = line->next;
    if (line->text.empty()) break;
    const std::string_view text = line->text;
    if (text.front() == ' ' || text.front() == '\t')
      return refused(400, "", text,
                     "a header line folded onto the one before (obs-fold) is refused (RFC 9112 §5.2)");
    const std::size_t colon = text.find(':');
    if (colon == std::string_view::npos) return refused(400, "", text, "a header line has no colon");
    const std::string_view name = text.substr(0, colon);
    if (name.empty() || !std::all_of(name.begin(), name.end(),
                                     [](char c) { return is_tchar(static_cast<unsigned char>(c)); }))
      return refused(400, std::string(name), text,
                     "is not a header name (a token; no whitespace before the colon, RFC 9112 §5.1)");
    const std::string_view value = trimmed(text.substr(colon + 1));
    if (value.find_first_of(std::string_view("\0\r", 2)) != std::string_view::npos)
      return refused(400, std::string(name), value, "a header value holds NUL or CR");
    const std::string key = lower(name);
    if (key == "content-length") {
      for (const std::string_view v : elements(value)) {
        const auto n = digits(v);
        if (!n)
          return refused(400, "Content-Length", value,
                         "must be decimal digits only, without sign or space (RFC 9112 §6.3)");
        if (length && *length != *n)
          return refused(400, "Content-Length", length_text + ", " + std::string(value),
                         "differing Content-Length values: the body's length is ambiguous");
        length = n;
        length_text = std::string(value);
      }
    } else if (key == "transfer-encoding") {
      has_coding = true;
      for (const std::string_view v : elements(value)) codings.push_back(v);
    } else if (key == "host") {
      hosts.push_back(value);
    }
  }

  if (path.find("%2f") != std::string::npos)
    return refused(
        404, "path", target,
        "an encoded slash (%2F) is part of a path segment, not a separator (RFC 3986): no resource "
        "has such a name");
  Framing f;
  f.head_bytes = at;
  if (has_coding) {
    if (length)
      return refused(
          400, "Transfer-Encoding", length_text,
          "Transfer-Encoding together with Content-Length: the body's length is ambiguous (RFC 9112 §6.1)");
    if (codings.size() != 1 || lower(codings[0]) != "chunked") {
      std::string list;
      for (const std::string_view c : codings) list += (list.empty() ? "" : ", ") + std::string(c);
      return refused(501, "Transfer-Encoding", list, "only chunked is implemented");
    }
    f.body = Framing::Body::chunked;
  } else if (length) {
    f.body = *length > 0 ? Framing::Body::length : Framing::Body::none;
    f.length = *length;
  }
  if ((method == "GET" || method == "HEAD") && f.body != Framing::Body::none)
    return refused(400, "method", method, "a " + method + " has no body here");
  // RFC 9112 §3.2: an HTTP/1.1 request has exactly one Host, a valid authority (host[:port]).
  if (request_line->text.ends_with(" HTTP/1.1")) {
    if (hosts.size() != 1)
      return refused(400, "Host", hosts.empty() ? "" : std::string(hosts[0]),
                     hosts.empty() ? "is required in an HTTP/1.1 request (RFC 9112 §3.2)"
                                   : "is given " + std::to_string(hosts.size()) +
                                         " times: an HTTP/1.1 request has exactly one (RFC 9112 §3.2)");
    if (!valid_authority(hosts[0]))
      return refused(400, "Host", hosts[0],
                     "is not a host with an optional port (RFC 9112 §3.2; RFC 3986 §3.2.2: no spaces, "
                     "commas or slashes)");
  }
  return f;
}

ChunkedBody read_chunked(std::string_view bytes) {
  ChunkedBody result;
  const auto malformed = [&](std::string reason) {
    result.verdict = ChunkedBody::Verdict::malformed;
    result.reason = std::move(reason);
    return result;
  };
  std::size_t at = 0;
  while (true) {
    const auto line = line_at(bytes, at);
    if (!line) return result;  // incomplete
    if (!line->crlf) return malformed("a chunk-size line ends in LF alone: CRLF is required");
    const std::string_view text = line->text;
    std::size_t hex = 0;
    while (hex < text.size() && std::isxdigit(static_cast<unsigned char>(text[hex]))) ++hex;
    const std::string_view rest = trimmed(text.substr(hex));
    if (hex == 0 || (!rest.empty() && rest.front() != ';'))
      return malformed("a chunk size must be hexadecimal digits (got '" + std::string(text.substr(0, 40)) +
                       "')");
    if (hex > 15) return malformed("a chunk size of more than 15 hexadecimal digits");
    const std::uint64_t size = std::stoull(std::string(text.substr(0, hex)), nullptr, 16);
    at = line->next;
    if (size == 0) {
      while (true) {  // the trailer section, through the empty line
        const auto trailer = line_at(bytes, at);
        if (!trailer) return result;
        if (!trailer->crlf) return malformed("a trailer line ends in LF alone: CRLF is required");
        at = trailer->next;
        if (trailer->text.empty()) break;
      }
      result.verdict = ChunkedBody::Verdict::complete;
      result.bytes = at;
      return result;
    }
    if (bytes.size() - at < size + 2) {
      // Incomplete, unless what is there already shows the chunk's end is not CRLF.
      if (bytes.size() - at > size && bytes[at + size] != '\r')
        return malformed("a chunk of " + std::to_string(size) + " bytes is not followed by CRLF");
      return result;
    }
    if (bytes.compare(at + size, 2, "\r\n") != 0)
      return malformed("a chunk of " + std::to_string(size) + " bytes is not followed by CRLF");
    at += size + 2;
  }
}

const std::string* current_request_bytes() {
  return tl_request_bytes;
}

namespace {

// One connection's socket: reads are buffered across its requests (httplib's own stream is made
// per request and drops what it read ahead), and the current request's bytes are kept.
class ConnectionStream final : public httplib::Stream {
 public:
  ConnectionStream(socket_t sock, std::chrono::microseconds read_timeout,
                   std::chrono::microseconds write_timeout, std::size_t kept)
      : sock_(sock), read_timeout_(read_timeout), write_timeout_(write_timeout), kept_(kept) {}

  bool is_readable() const override { return pending() > 0 || ready(POLLIN, read_timeout_); }
  bool is_writable() const override { return ready(POLLOUT, write_timeout_); }

  ssize_t read(char* ptr, size_t size) override {
    if (pending() == 0) {
      buffer_.erase(0, offset_);
      offset_ = 0;
      line_end_ = std::string::npos;
      if (const ssize_t got = fill(); got <= 0) return got;
    }
    std::size_t n = std::min(size, pending());
    if (in_head_) {
      // The head goes out no further than a line's end, each line looked at (look_at_line) once,
      // when its first byte is asked for (httplib reads the head a byte at a time: the line's end
      // is found once per line, not per byte).
      if (at_line_start_) {
        line_end_ = line_end();
        if (line_end_ != std::string::npos) line_end_ = look_at_line(line_end_);
      }
      if (line_end_ != std::string::npos && line_end_ >= offset_) n = std::min(size, line_end_ + 1 - offset_);
      at_line_start_ = buffer_[offset_ + n - 1] == '\n';
    }
    std::copy_n(buffer_.data() + offset_, n, ptr);
    // Kept up to a bound: a longer request is cut short there, which the checks read as incomplete
    // (refused), rather than held twice (httplib holds what it reads of it too).
    if (request_.size() + n <= kept_) request_.append(buffer_.data() + offset_, n);
    offset_ += n;
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, size_t size) override {
    if (!is_writable()) return -1;
    ssize_t sent = 0;
    do {
      sent = ::send(sock_, ptr, size, MSG_NOSIGNAL);
    } while (sent < 0 && errno == EINTR);
    return sent;
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override { address(::getpeername, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address(::getsockname, ip, port); }
  socket_t socket() const override { return sock_; }

  // Waits (in slices, so that a stopping server is noticed) for the next request's first byte.
  bool await_request(std::chrono::seconds idle, const std::atomic<socket_t>& listening) const {
    const auto until = std::chrono::steady_clock::now() + idle;
    while (listening != INVALID_SOCKET) {
      if (pending() > 0 || ready(POLLIN, std::chrono::milliseconds(100))) return true;
      if (std::chrono::steady_clock::now() > until) return false;
    }
    return false;
  }

  void start_request() {
    request_.clear();
    in_head_ = true;
    head_started_ = false;
    at_line_start_ = true;
  }
  const std::string& request() const { return request_; }

 private:
  std::size_t pending() const { return buffer_.size() - offset_; }

  // Where the line starting at offset_ ends (its LF), reading more while needed; npos when it is
  // longer than kLongestLookedAtLine (httplib refuses such a line itself: 414 or 400) or the
  // connection ends first.
  std::size_t line_end() {
    std::size_t from = offset_;
    while (true) {
      const std::size_t lf = buffer_.find('\n', from);
      if (lf != std::string::npos) return lf;
      from = buffer_.size();
      if (pending() >= kLongestLookedAtLine || fill() <= 0) return std::string::npos;
    }
  }

  // One more recv appended to the buffer: its byte count, 0 at the end, −1 on error or time-out.
  ssize_t fill() {
    if (!ready(POLLIN, read_timeout_)) return -1;
    std::array<char, 4096> chunk{};
    ssize_t got = 0;
    do {
      got = ::recv(sock_, chunk.data(), chunk.size(), 0);
    } while (got < 0 && errno == EINTR);
    if (got > 0) buffer_.append(chunk.data(), static_cast<std::size_t>(got));
    return got;
  }

  // The head's line at offset_ (ending at `lf`), before httplib reads it; returns where it ends now.
  // - The request line: an absolute-form target (`http://host:port/path`) becomes its origin form
  //   (`/path`): RFC 9112 §3.2.2, a server MUST accept it; httplib would route the whole URI.
  // - A Range header is renamed kRangeHeader, in place, so that httplib neither parses nor applies it
  //   (server/http/byte_ranges.h); a client's own header of that name is renamed away.
  // The empty line ends the head: CRLF alone, as httplib reads it. An empty line ended in LF alone
  // is a line httplib skips (and read_framing refuses the request for it): the head goes on, and a
  // Range after it must still be renamed (api_fuzzer found one httplib answered with 416).
  std::size_t look_at_line(std::size_t lf) {
    const std::string_view line = std::string_view(buffer_).substr(offset_, lf - offset_);
    if (line.empty()) return lf;
    if (line == "\r") {
      if (head_started_) in_head_ = false;  // empty lines before the request line are skipped
      return lf;
    }
    if (!head_started_) {
      head_started_ = true;
      const std::size_t space = line.find(' ');
      const std::string_view rest = space == std::string_view::npos ? "" : line.substr(space + 1);
      const std::size_t scheme = rest.find("://");
      const std::string_view name = rest.substr(0, scheme);
      const bool http = scheme != std::string_view::npos && (lower(name) == "http" || lower(name) == "https");
      if (!http) return lf;
      const std::size_t authority = space + 1 + scheme + 3;
      const std::size_t end = line.find(' ', authority);
      const std::size_t path = line.find_first_of("/?", authority);
      const std::size_t target_end = end == std::string_view::npos ? line.size() : end;
      const std::string origin = path == std::string_view::npos || path > target_end
                                     ? "/"
                                     : std::string(line.substr(path, target_end - path));
      const std::string fixed = (origin.front() == '?' ? "/" : "") + origin;
      buffer_.replace(offset_ + space + 1, target_end - space - 1, fixed);
      return buffer_.find('\n', offset_);
    }
    const auto named = [&](std::string_view header) {
      if (line.size() <= header.size() || line[header.size()] != ':') return false;
      for (std::size_t i = 0; i < header.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(line[i])) !=
            std::tolower(static_cast<unsigned char>(header[i])))
          return false;
      return true;
    };
    if (named(kRangeHeader))
      buffer_.replace(offset_, kRangeHeader.size(), "Rnge-");
    else if (named("Range"))
      buffer_.replace(offset_, kRangeHeader.size(), kRangeHeader);
    return lf;
  }

  bool ready(short events, std::chrono::microseconds timeout) const {
    pollfd p{sock_, events, 0};
    int n = 0;
    do {
      n = ::poll(&p, 1,
                 static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(timeout).count()));
    } while (n < 0 && errno == EINTR);
    return n > 0 && (p.revents & (events | POLLHUP | POLLERR));
  }

  template <class Query>
  void address(Query query, std::string& ip, int& port) const {
    sockaddr_storage addr{};
    socklen_t length = sizeof addr;
    if (query(sock_, reinterpret_cast<sockaddr*>(&addr), &length) != 0) return;
    std::array<char, NI_MAXHOST> host{};
    std::array<char, NI_MAXSERV> service{};
    if (::getnameinfo(reinterpret_cast<sockaddr*>(&addr), length, host.data(), host.size(), service.data(),
                      service.size(), NI_NUMERICHOST | NI_NUMERICSERV) == 0) {
      ip = host.data();
      port = std::atoi(service.data());
    }
  }

  socket_t sock_;
  std::chrono::microseconds read_timeout_, write_timeout_;
  std::size_t kept_;  // [bytes] of the current request kept at most
  std::string buffer_;
  std::size_t offset_ = 0;
  std::string request_;
  bool in_head_ = true;                       // the current request's head is being read
  bool head_started_ = false;                 // its request line has been read
  bool at_line_start_ = true;                 // the next byte handed out starts a line of the head
  std::size_t line_end_ = std::string::npos;  // the LF of the head's line being handed out
  // [bytes] a head line is looked at up to this length (httplib's own limit is 8 KiB)
  static constexpr std::size_t kLongestLookedAtLine = 16384;
};

// True when the request was read exactly to the end of its body: the connection may go on.
bool read_to_the_end(const std::string& bytes) {
  const Framing f = read_framing(bytes);
  if (f.status != 0) return false;
  const std::string_view body = std::string_view(bytes).substr(f.head_bytes);
  switch (f.body) {
    case Framing::Body::none: return body.empty();
    case Framing::Body::length: return body.size() == f.length;
    case Framing::Body::chunked: {
      const ChunkedBody c = read_chunked(body);
      return c.verdict == ChunkedBody::Verdict::complete && c.bytes == body.size();
    }
  }
  return false;
}

}  // namespace

bool FramingServer::process_and_close_socket(socket_t sock) {
  using std::chrono::microseconds;
  using std::chrono::seconds;
  ConnectionStream stream(sock, seconds(read_timeout_sec_) + microseconds(read_timeout_usec_),
                          seconds(write_timeout_sec_) + microseconds(write_timeout_usec_),
                          kKeptHead + 2 * payload_max_length_);
  bool ok = false;
  bool unread = false;  // the last request's body was not read to its end
  for (std::size_t left = keep_alive_max_count_; left > 0; --left) {
    if (!stream.await_request(seconds(keep_alive_timeout_sec_), svr_sock_)) break;
    stream.start_request();
    bool closed = false;
    tl_request_bytes = &stream.request();
    ok = process_request(stream, left == 1, closed, nullptr);
    tl_request_bytes = nullptr;
    unread = ok && !read_to_the_end(stream.request());
    if (!ok || closed || unread) break;
  }
  if (unread) {
    // A lingering close (as nginx's): closing with unread bytes would send a reset that can destroy
    // the answer before the client reads it, so the rest of what it sends is read and dropped, for
    // at most 2 s.
    ::shutdown(sock, SHUT_WR);
    const auto until = std::chrono::steady_clock::now() + seconds(2);
    std::array<char, 65536> sink{};
    while (std::chrono::steady_clock::now() < until) {
      pollfd p{sock, POLLIN, 0};
      const int ready = ::poll(&p, 1, 200);
      if (ready < 0 && errno == EINTR) continue;  // a signal is not the end of the input
      if (ready <= 0) break;
      const ssize_t got = ::recv(sock, sink.data(), sink.size(), 0);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) break;
    }
  }
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return ok;
}

}  // namespace spinfold::server
