// HTTP/1.1 message framing (RFC 9112) checked on the bytes as they arrived, before any route runs.
// cpp-httplib 0.11 reads leniently: a header line without CRLF or without a colon (an obs-fold
// continuation among them) is skipped, the first of two Content-Length headers wins, `+14` and
// `-5` parse as numbers, a chunk not followed by CRLF ends the body early and leaves the rest to be
// read as the next request. FramingServer serves each connection through a stream that keeps the
// bytes of the request being served, so that the checks below see what httplib hid.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

// How a request's body is delimited, or why its head is refused.
struct Framing {
  enum class Body { none, length, chunked };
  Body body = Body::none;
  std::uint64_t length = 0;    // Body::length: the Content-Length (saturated at 2^64 − 1)
  std::size_t head_bytes = 0;  // the request line through the empty line
  int status = 0;              // 0: acceptable; 400, 404 or 501: refused
  std::string field, value, reason;
};

// Reads a request's head: the request line and header lines, each ending in CRLF, through the
// empty line. Refused (400): a line ending in LF alone, a folded line (obs-fold), a line without a
// colon or with a name that is not a token (whitespace before the colon among them), NUL or CR in a
// value, a Content-Length that is not digits or differs from another, Transfer-Encoding together
// with Content-Length, a body on GET or HEAD; 501: a transfer coding other than chunked; 404: `%2F`
// in the path (RFC 3986: an encoded slash is data in a segment, not a separator, and no resource
// here has one in its name). An incomplete head is refused as 400.
Framing read_framing(std::string_view bytes);

// A chunked body (RFC 9112 §7.1) at the start of `bytes`: complete (and its length in bytes),
// incomplete, or malformed with the reason (a size that is not hexadecimal digits, a chunk not
// followed by CRLF, a line ending in LF alone).
struct ChunkedBody {
  enum class Verdict { complete, incomplete, malformed };
  Verdict verdict = Verdict::incomplete;
  std::size_t bytes = 0;
  std::string reason;
};
ChunkedBody read_chunked(std::string_view bytes);

// The bytes of the request this thread is serving (its head and what has been read of its body),
// or nullptr outside a FramingServer connection.
const std::string* current_request_bytes();

// httplib's server with its own connection loop: each connection read through a buffered stream
// that keeps the current request's bytes (current_request_bytes) and carries pipelined bytes to
// the next request; a connection whose request was refused or not read to the end of its body is
// closed after the answer, so that no byte of a body is ever read as a request.
class FramingServer : public httplib::Server {
 private:
  bool process_and_close_socket(socket_t sock) override;
};

}  // namespace spinfold::server
