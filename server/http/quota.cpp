#include "server/http/quota.h"

#include <arpa/inet.h>

#include <cmath>

#include "engine/integer_cast.h"
#include "engine/number_text.h"
#include "server/http/problem.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

using Clock = std::chrono::steady_clock;

bool is_ip_address(const std::string& text) {
  unsigned char buffer[sizeof(in6_addr)];
  return inet_pton(AF_INET, text.c_str(), buffer) == 1 || inet_pton(AF_INET6, text.c_str(), buffer) == 1;
}

// 429 naming the limit (as the problem's field), its value and what to do.
ApiError over_quota(const std::string& limit, double value, const std::string& reason, long retry_after) {
  return ApiError{
      429, "Too many requests", {{"limits." + limit, shortest(value), reason}}, std::to_string(retry_after)};
}

}  // namespace

bool is_trusted_proxy(const std::string& address, const std::string& trusted) {
  if (trusted.empty()) return false;
  const std::size_t slash = trusted.find('/');
  if (slash == std::string::npos) return address == trusted;
  // IPv4 a.b.c.d/n: a front whose address changes (a Kubernetes pod) inside a known network.
  in_addr net{}, peer{};
  const int bits = std::atoi(trusted.c_str() + slash + 1);
  if (bits < 0 || bits > 32 || inet_pton(AF_INET, trusted.substr(0, slash).c_str(), &net) != 1 ||
      inet_pton(AF_INET, address.c_str(), &peer) != 1)
    return false;
  const std::uint32_t mask = bits == 0 ? 0 : ~std::uint32_t{0} << (32 - bits);
  return (ntohl(net.s_addr) & mask) == (ntohl(peer.s_addr) & mask);
}

std::string client_address(const httplib::Request& req, const std::string& trusted_proxy) {
  if (!is_trusted_proxy(req.remote_addr, trusted_proxy)) return req.remote_addr;
  const std::string forwarded = req.get_header_value("X-Forwarded-For");
  const std::size_t end = forwarded.find(',');
  std::string first = forwarded.substr(0, end);
  first.erase(0, first.find_first_not_of(" \t"));
  first.erase(first.find_last_not_of(" \t") + 1);
  return is_ip_address(first) ? first : req.remote_addr;
}

ClientQuotas::Client& ClientQuotas::client_locked(const std::string& address) {
  const auto [it, added] = clients_.try_emplace(address);
  if (added) {
    it->second.tokens = limits_.request_burst_per_client;
    it->second.refilled = Clock::now();
    if (clients_.size() > prune_above_) prune_locked();
  }
  return it->second;
}

// Drops the clients that hold nothing (a full bucket, no live session, no stream); keeps the map
// proportional to the clients that do.
void ClientQuotas::prune_locked() {
  const auto now = Clock::now();
  for (auto it = clients_.begin(); it != clients_.end();) {
    Client& c = it->second;
    std::erase_if(c.sessions, [](const auto& entry) { return entry.second.expired(); });
    const double seconds = std::chrono::duration<double>(now - c.refilled).count();
    const bool full =
        c.tokens + seconds * limits_.requests_per_second_per_client >= limits_.request_burst_per_client;
    it = full && c.sessions.empty() && c.streams == 0 ? clients_.erase(it) : std::next(it);
  }
  prune_above_ = std::max<std::size_t>(1024, 2 * clients_.size());
}

void ClientQuotas::admit_request(const std::string& client) {
  if (limits_.requests_per_second_per_client <= 0.0) return;  // unlimited
  const std::lock_guard lock(mutex_);
  Client& c = client_locked(client);
  const auto now = Clock::now();
  const double rate = limits_.requests_per_second_per_client;
  const double burst = limits_.request_burst_per_client;
  c.tokens = std::min(burst, c.tokens + std::chrono::duration<double>(now - c.refilled).count() * rate);
  c.refilled = now;
  if (c.tokens >= 1.0) {
    c.tokens -= 1.0;
    return;
  }
  // Seconds until a token, checked before it becomes an integer (a tiny rate makes it huge): a day
  // at most.
  const long wait = clamped_integer<long>(std::ceil((1.0 - c.tokens) / rate), 1, 86400);
  throw over_quota("requests_per_second_per_client", rate,
                   "this client (" + client + ") sends more than " + shortest(rate) +
                       " requests a second (bursts of " + shortest(burst) + "); slow down",
                   wait);
}

void ClientQuotas::add_session(const std::string& client, const std::string& id,
                               const std::shared_ptr<Session>& session,
                               const std::function<bool(const std::string&)>& gone) {
  const std::lock_guard lock(mutex_);
  Client& c = client_locked(client);
  std::erase_if(c.sessions, [](const auto& entry) { return entry.second.expired(); });
  const int quota = limits_.max_sessions_per_client;
  if (static_cast<int>(c.sessions.size()) >= quota && gone)
    std::erase_if(c.sessions, [&gone](const auto& entry) { return gone(entry.first); });
  if (static_cast<int>(c.sessions.size()) >= quota)
    throw over_quota("max_sessions_per_client", quota,
                     "this client (" + client + ") has " + std::to_string(quota) +
                         " sessions; DELETE one (or wait for an idle one to expire)",
                     60);
  c.sessions[id] = session;
}

void ClientQuotas::release_session(const std::string& id) {
  const std::lock_guard lock(mutex_);
  for (auto& [address, c] : clients_)
    if (c.sessions.erase(id) > 0) return;
}

std::shared_ptr<void> ClientQuotas::open_stream(const std::string& client) {
  const std::lock_guard lock(mutex_);
  Client& c = client_locked(client);
  const int quota = limits_.max_streams_per_client;
  if (c.streams >= quota)
    throw over_quota(
        "max_streams_per_client", quota,
        "this client (" + client + ") has " + std::to_string(quota) + " event streams open; close one first",
        10);
  ++c.streams;
  // The handle gives the stream back; the client's entry stays while it has a stream open.
  return std::shared_ptr<void>(nullptr, [this, client](void*) {
    const std::lock_guard released(mutex_);
    --clients_[client].streams;
  });
}

}  // namespace spinfold::server
