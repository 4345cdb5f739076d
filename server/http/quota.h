// Quotas per client address (server::Limits): sessions, open event streams and a request rate, each
// refused with 429, Retry-After and a problem+json body that names the limit.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "server/options.h"

namespace httplib {
struct Request;
}

namespace spinfold::server {

struct Session;

// True when `address` is the trusted proxy: equal to `trusted`, or inside it when it is an IPv4
// network "a.b.c.d/n" (a front whose pod address changes); never when `trusted` is "".
bool is_trusted_proxy(const std::string& address, const std::string& trusted);

// The client's address: the socket's peer, or the first address of X-Forwarded-For when the peer is
// the trusted proxy (is_trusted_proxy) and the header holds an IP address.
std::string client_address(const httplib::Request& req, const std::string& trusted_proxy);

class ClientQuotas {
 public:
  explicit ClientQuotas(const Limits& limits) : limits_(limits) {}

  // Takes one request from the client's token bucket, or ApiError 429 (Retry-After: when the next
  // token is there).
  void admit_request(const std::string& client);

  // Counts a new session against its creator's quota, or ApiError 429 (then the caller drops it).
  // The session counts until release_session(id) or until it is gone (deleted, expired).
  // `gone(id)`: whether another replica deleted a session this one counted (asked only at the
  // quota, so that a client's sessions deleted through another replica count no more).
  void add_session(const std::string& client, const std::string& id, const std::shared_ptr<Session>& session,
                   const std::function<bool(const std::string&)>& gone = {});
  void release_session(const std::string& id);

  // An open event stream of the client, counted while the returned handle lives; ApiError 429 over
  // the quota.
  std::shared_ptr<void> open_stream(const std::string& client);

 private:
  struct Client {
    double tokens = 0.0;  // [requests]
    std::chrono::steady_clock::time_point refilled;
    std::map<std::string, std::weak_ptr<Session>> sessions;  // by id
    int streams = 0;
  };
  Client& client_locked(const std::string& address);
  void prune_locked();

  const Limits limits_;
  std::mutex mutex_;
  std::map<std::string, Client> clients_;
  std::size_t prune_above_ = 1024;  // clients kept before the idle ones are dropped (doubles as needed)
};

}  // namespace spinfold::server
