// HTTP/1.1 framing read from the raw bytes (server/http/framing.h): how a body is delimited, and each
// refusal of RFC 9112 with its status, called directly on request texts (hardening_test's Framing
// cases send such bytes through a real server).
#include "server/http/framing.h"

#include <gtest/gtest.h>

#include <string>

namespace spinfold::server {
namespace {

Framing framing_of(const std::string& head) {
  return read_framing(head);
}

TEST(RequestFraming, AcceptedHeadsAndTheirBodies) {
  const std::string get = "GET /api/v1/health HTTP/1.1\r\nHost: x\r\n\r\n";
  const Framing none = framing_of(get + "next request");
  EXPECT_EQ(none.status, 0) << none.reason;
  EXPECT_EQ(none.body, Framing::Body::none);
  EXPECT_EQ(none.head_bytes, get.size());  // the bytes after the head are not the head's

  const Framing length =
      framing_of("POST /api/v1/sessions HTTP/1.1\r\nHost: x\r\nContent-Length: 42\r\n\r\n");
  EXPECT_EQ(length.status, 0) << length.reason;
  EXPECT_EQ(length.body, Framing::Body::length);
  EXPECT_EQ(length.length, 42u);

  const Framing chunked = framing_of("POST /a HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: Chunked\r\n\r\n");
  EXPECT_EQ(chunked.status, 0) << chunked.reason;
  EXPECT_EQ(chunked.body, Framing::Body::chunked);

  // Repeated equal lengths agree; a zero length is no body.
  EXPECT_EQ(
      framing_of("POST /a HTTP/1.1\r\nHost: x\r\nContent-Length: 7\r\nContent-Length: 7\r\n\r\n").length, 7u);
  EXPECT_EQ(framing_of("POST /a HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\n\r\n").body, Framing::Body::none);
}

// What cpp-httplib would read leniently, refused here with the status of the header's comment.
// RFC 9112 §3.2: an HTTP/1.1 request has exactly one Host, an authority (host and optional port).
TEST(RequestFraming, AnHttp11RequestHasExactlyOneWellFormedHost) {
  const auto status = [](const std::string& hosts, const std::string& version = "HTTP/1.1") {
    return read_framing("GET /api/v1/health " + version + "\r\n" + hosts + "\r\n").status;
  };
  for (const char* fine : {"Host: 127.0.0.1:8080\r\n", "Host: localhost\r\n", "Host: [::1]:80\r\n",
                           "Host: spinfold.example.org\r\n", "host:  a-b.c \r\n", "Host: [::1]\r\n"})
    EXPECT_EQ(status(fine), 0) << fine;
  for (const char* bad :
       {"", "Host: a\r\nHost: a\r\n", "Host: a, b\r\n", "Host: a b\r\n", "Host: a,b\r\n", "Host: \r\n",
        "Host: a/b\r\n", "Host: a:80x\r\n", "Host: [::1\r\n", "Host: u@a\r\n"}) {
    const Framing f = read_framing(std::string("GET / HTTP/1.1\r\n") + bad + "\r\n");
    EXPECT_EQ(f.status, 400) << bad;
    EXPECT_EQ(f.field, "Host") << bad;
  }
  EXPECT_EQ(status("", "HTTP/1.0"), 0);  // HTTP/1.0 has no Host requirement
}

TEST(RequestFraming, AmbiguousHeadsAreRefused) {
  const struct {
    const char* head;
    int status;
  } cases[] = {
      {"GET / HTTP/1.1\nHost: x\r\n\r\n", 400},                                    // request line in LF
      {"GET / HTTP/1.1\r\nHost: x\n\r\n", 400},                                    // header line in LF
      {"GET / HTTP/1.1\r\nHost: x\r\n folded\r\n\r\n", 400},                       // obs-fold
      {"GET / HTTP/1.1\r\nno colon here\r\n\r\n", 400},                            // no colon
      {"GET / HTTP/1.1\r\nHost : x\r\n\r\n", 400},                                 // space before colon
      {"POST / HTTP/1.1\r\nContent-Length: +14\r\n\r\n", 400},                     // sign
      {"POST / HTTP/1.1\r\nContent-Length: -5\r\n\r\n", 400},                      // sign
      {"POST / HTTP/1.1\r\nContent-Length: 5\r\nContent-Length: 6\r\n\r\n", 400},  // two lengths
      {"POST / HTTP/1.1\r\nContent-Length: 5\r\nTransfer-Encoding: chunked\r\n\r\n", 400},  // both
      {"GET / HTTP/1.1\r\nContent-Length: 3\r\n\r\n", 400},                                 // a GET body
      {"POST / HTTP/1.1\r\nTransfer-Encoding: gzip\r\n\r\n", 501},                          // unknown coding
      {"POST / HTTP/1.1\r\nTransfer-Encoding: gzip, chunked\r\n\r\n", 501},
      {"GET /api/v1/sessions/a%2Fb HTTP/1.1\r\nHost: x\r\n\r\n", 404},  // encoded slash
      {"GET / HTTP/1.1\r\nHost: x\r\n", 400},                           // incomplete
      {"", 400},
  };
  for (const auto& c : cases) {
    const Framing f = read_framing(c.head);
    EXPECT_EQ(f.status, c.status) << c.head;
    EXPECT_FALSE(f.reason.empty()) << c.head;
  }
  EXPECT_EQ(read_framing(std::string("GET / HTTP/1.1\r\nX: a") + '\0' + "b\r\n\r\n").status, 400);  // NUL
}

TEST(RequestFraming, ChunkedBodies) {
  const ChunkedBody whole = read_chunked("5\r\nhello\r\n0\r\n\r\nGET / HTTP/1.1");
  EXPECT_EQ(whole.verdict, ChunkedBody::Verdict::complete);
  EXPECT_EQ(whole.bytes, 15u);  // the next request is not part of it
  const ChunkedBody trailer = read_chunked("3;ext=1\r\nabc\r\n0\r\nX-Sum: 1\r\n\r\n");
  EXPECT_EQ(trailer.verdict, ChunkedBody::Verdict::complete);
  EXPECT_EQ(trailer.bytes, 29u);
  for (const char* partial : {"", "5\r\nhel", "5\r\nhello\r\n", "0\r\n"})
    EXPECT_EQ(read_chunked(partial).verdict, ChunkedBody::Verdict::incomplete) << partial;
  for (const char* bad : {"zz\r\nhello\r\n0\r\n\r\n", "5\nhello\r\n0\r\n\r\n", "5\r\nhelloXX0\r\n\r\n",
                          "5\r\nhelloX", "1234567890abcdef\r\n"}) {
    const ChunkedBody b = read_chunked(bad);
    EXPECT_EQ(b.verdict, ChunkedBody::Verdict::malformed) << bad;
    EXPECT_FALSE(b.reason.empty()) << bad;
  }
}

// Outside a FramingServer connection there are no request bytes to see.
TEST(RequestFraming, NoRequestBytesOutsideAConnection) {
  EXPECT_EQ(current_request_bytes(), nullptr);
}

}  // namespace
}  // namespace spinfold::server
