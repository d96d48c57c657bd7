// earc-plan serve [--db FILE] [--socket PATH] [--method M] [--seed K]
// [--time-limit S] [--roadmap-cache-mib N] [--db-row-cache-mb N]: a
// long-running planner. Opens the experience store, when given, once,
// keeps the robots' roadmaps between requests, and answers planning
// requests, one JSON line each (protocol in earc/service/service.hpp),
// on stdin/stdout and, with --socket, on a Unix domain socket (any number
// of connections, requests answered one at a time in arrival order).
// SIGINT or SIGTERM cuts the request in flight short (its answer says
// "interrupted"), commits what was learned, closes the database and exits
// 0. Without --socket the service also ends at the end of stdin; with
// one, it keeps serving the socket.
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <deque>
#include <list>

#include "earc/cli/stop_signals.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"
#include "earc/service/service.hpp"
#include "earc/util/deadline.hpp"
#include "plan_store.hpp"

namespace earc {
namespace {

struct ServeOptions {
  std::string db;
  std::string socket;
  std::string method = "earc";
  double time_limit = 60.0;
  std::uint64_t seed = 1;
  bool deterministic = false;
  std::size_t roadmap_cache_mib = service::ServiceSettings{}.roadmap_cache_mib;
  std::optional<std::size_t> db_row_cache_mb;
};

class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() { reset(); }
  Fd(Fd&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }
  Fd& operator=(Fd&& o) noexcept {
    if (this != &o) {
      reset();
      fd_ = o.fd_;
      o.fd_ = -1;
    }
    return *this;
  }
  int get() const { return fd_; }
  void reset() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
};

std::runtime_error systemError(const std::string& what) {
  return std::runtime_error(what + ": " + std::strerror(errno));
}

// Writes all of text to a blocking descriptor (stdout); false when the
// reader has gone (EPIPE and the like) or a stop signal came while the
// write waited for a reader that does not read.
bool writeAll(int fd, const std::string& text, const StopFlag& stop) {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR && !stopSet(&stop)) continue;
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

// A connection's answers wait here while its client does not read; past
// this much the service stops reading the client's requests until it has
// read its answers, so one client that does not read holds up no other.
constexpr std::size_t kPendingAnswerBytes = 1 << 20;

// A name for binding beside `path` (same directory, so it can be linked
// to `path`), or "" when none fits in a socket address.
std::string bindingName(const std::string& path, std::size_t max_length) {
  const std::size_t slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string name = dir + ".earc-serve-" + std::to_string(::getpid());
  return name.size() <= max_length ? name : "";
}

// The listening socket at `path`. A stale socket file (no one accepts on
// it) is replaced; a live one, or any other kind of file, is refused.
// The socket is bound under another name and linked to `path` once it
// listens, so a client that sees the file can connect at once (bound
// there directly, the file exists a moment before connections are
// accepted, and such a client is refused).
Fd listenOn(const std::string& path) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  const std::size_t max_length = sizeof addr.sun_path - 1;
  if (path.size() > max_length)
    throw InputError(path, "--socket", "path longer than " + std::to_string(max_length) + " bytes");
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!S_ISSOCK(st.st_mode)) throw InputError(path, "--socket", "exists and is not a socket: not replaced");
    Fd probe(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
    if (probe.get() >= 0 && ::connect(probe.get(), reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0)
      throw InputError(path, "--socket", "another service is listening on it");
    ::unlink(path.c_str());
  }
  Fd fd(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (fd.get() < 0) throw systemError("socket");
  // Bound directly when no other name fits: then the moment remains.
  std::string binding = bindingName(path, max_length);
  if (!binding.empty() && ::lstat(binding.c_str(), &st) == 0) {
    // Left by a killed service of the same pid; anything else is not ours.
    if (S_ISSOCK(st.st_mode))
      ::unlink(binding.c_str());
    else
      binding.clear();
  }
  sockaddr_un bind_addr = addr;
  if (!binding.empty()) std::memcpy(bind_addr.sun_path, binding.c_str(), binding.size() + 1);
  if (::bind(fd.get(), reinterpret_cast<sockaddr*>(&bind_addr), sizeof bind_addr) != 0)
    throw systemError(path + ": cannot bind");
  if (::listen(fd.get(), 16) != 0) {
    const int saved = errno;
    if (!binding.empty()) ::unlink(binding.c_str());
    errno = saved;
    throw systemError(path + ": cannot listen");
  }
  if (!binding.empty()) {
    // link() does not replace: a service that started meanwhile on the
    // same path keeps it. A file system without hard links gets a rename.
    if (::link(binding.c_str(), path.c_str()) == 0) {
      ::unlink(binding.c_str());
    } else {
      const int saved = errno;
      if (saved == EEXIST || ::rename(binding.c_str(), path.c_str()) != 0) {
        const int why = saved == EEXIST ? saved : errno;
        ::unlink(binding.c_str());
        if (why == EEXIST) throw InputError(path, "--socket", "another service took the path while this one started");
        errno = why;
        throw systemError(path + ": cannot create");
      }
    }
  }
  return fd;
}

// One source of requests: stdin (answered on stdout) or a connection.
struct Client {
  int in = -1;
  int out = -1;
  Fd owned;  // connections only (non-blocking)
  service::LineSplitter lines;
  std::deque<service::LineSplitter::Line> queued;  // read, not yet answered
  std::string pending;  // connections: answers not yet taken by the client
  bool reading = true;  // until the client's end of input
  bool open = true;

  bool connection() const { return owned.get() >= 0; }
  // Whether its next request may be answered now: a connection whose
  // client has not taken its earlier answers waits.
  bool ready() const { return !queued.empty() && pending.size() < kPendingAnswerBytes; }
};

class Server {
 public:
  // The stop signals must interrupt blocking calls (Blocking::Interrupt).
  Server(service::Service& service, Fd listener, const cli::StopSignals& signals)
      : service_(service), listener_(std::move(listener)), signals_(signals) {}

  // Serves until a stop signal, or the end of stdin when there is no socket.
  // Requests are answered one at a time, taking the clients in turn (one
  // request each per round), so that a client with many requests queued
  // does not hold up the others'. A client's requests are read only once
  // its earlier ones are answered, and a connection's answers wait in a
  // queue while its client does not read them: a client that does not
  // read holds up no other, nor a stop signal.
  void run() {
    Client stdio;
    stdio.in = STDIN_FILENO;
    stdio.out = STDOUT_FILENO;
    while (!stopping()) {
      std::vector<pollfd> fds{{signals_.wakeFd(), POLLIN, 0}};
      bool work = stdio.open && !stdio.queued.empty();
      if (stdio.open) fds.push_back({stdio.in, static_cast<short>(stdio.reading && stdio.queued.empty() ? POLLIN : 0), 0});
      if (listener_.get() >= 0) fds.push_back({listener_.get(), POLLIN, 0});
      for (const Client& c : connections_) {
        const short in = c.reading && c.queued.empty() && c.pending.size() < kPendingAnswerBytes ? POLLIN : 0;
        fds.push_back({c.in, static_cast<short>(in | (c.pending.empty() ? 0 : POLLOUT)), 0});
        work = work || c.ready();
      }
      if (!stdio.open && listener_.get() < 0) break;
      if (::poll(fds.data(), fds.size(), work ? 0 : -1) < 0) {
        if (errno == EINTR) continue;
        throw systemError("poll");
      }
      std::size_t i = 1;
      if (stdio.open && fds[i++].revents && stdio.reading) read(stdio);
      if (listener_.get() >= 0 && fds[i++].revents & POLLIN) accept();
      for (Client& c : connections_) {
        // Connections accepted just now have no entry yet.
        if (i < fds.size() && fds[i].fd == c.in && fds[i].revents) {
          if (!c.pending.empty()) flush(c);
          if (c.open && c.reading && c.queued.empty() && (fds[i].revents & (POLLIN | POLLHUP | POLLERR))) read(c);
        }
        ++i;
      }
      // One request of each client that has one, in turn.
      if (stdio.open && !stdio.queued.empty()) answerNext(stdio);
      for (Client& c : connections_)
        if (c.open && c.ready()) answerNext(c);
      if (stdio.open && !stdio.reading && stdio.queued.empty()) stdio.open = false;
      for (auto it = connections_.begin(); it != connections_.end();) {
        // Closed once the client has all its answers (or is gone).
        if (!it->reading && it->queued.empty() && it->pending.empty()) it->open = false;
        it = it->open ? std::next(it) : connections_.erase(it);
      }
    }
  }

 private:
  bool stopping() const { return stopSet(&signals_.flag()); }

  void accept() {
    const int fd = ::accept4(listener_.get(), nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0) return;  // the client gave up already, or EINTR: poll again
    Client& c = connections_.emplace_back();
    c.owned = Fd(fd);
    c.in = c.out = fd;
  }

  // Reads what is there and queues its complete lines.
  void read(Client& c) {
    char buf[65536];
    const ssize_t n = ::read(c.in, buf, sizeof buf);
    if (n < 0 && (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK)) return;
    const bool eof = n <= 0;
    auto lines = eof ? c.lines.finish() : c.lines.feed(std::string_view(buf, static_cast<std::size_t>(n)));
    for (auto& line : lines) c.queued.push_back(std::move(line));
    if (eof) c.reading = false;
  }

  // Answers the client's oldest request: on stdout as it is (blocking), to
  // a connection through its queue, written as far as the client takes it.
  void answerNext(Client& c) {
    if (stopping()) return;  // not started: left unanswered
    const service::LineSplitter::Line line = std::move(c.queued.front());
    c.queued.pop_front();
    std::string response = line.too_long ? service_.tooLongResponse() : service_.handleLine(line.text);
    response += '\n';
    if (!c.connection()) {
      if (!writeAll(c.out, response, signals_.flag())) c.open = false;
      return;
    }
    c.pending += response;
    flush(c);
  }

  // Writes a connection's queued answers as far as it takes them now.
  void flush(Client& c) {
    std::size_t written = 0;
    while (written < c.pending.size()) {
      const ssize_t n = ::write(c.out, c.pending.data() + written, c.pending.size() - written);
      if (n < 0) {
        if (errno == EINTR && !stopping()) continue;
        if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) break;
        c.open = false;  // the client has gone: its answers with it
        break;
      }
      written += static_cast<std::size_t>(n);
    }
    c.pending.erase(0, written);
  }

  service::Service& service_;
  Fd listener_;
  const cli::StopSignals& signals_;
  std::list<Client> connections_;
};

// A client that hangs up must not kill the service.
void ignoreBrokenPipes() {
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, nullptr);
}

int runServe(const ServeOptions& o) {
  service::ServiceSettings settings;
  Method method;
  try {
    method = methodFromName(o.method);
  } catch (const std::invalid_argument& e) {
    throw InputError("", "--method", e.what());
  }
  settings.method = o.method;
  settings.time_limit_s = o.time_limit;
  settings.seed = o.seed;
  settings.deterministic = o.deterministic;
  settings.roadmap_cache_mib = o.roadmap_cache_mib;
  // Every stop signal is caught (the service finishes the request in
  // flight as interrupted); blocking calls return EINTR, poll wakes.
  cli::StopSignals signals(cli::StopSignals::Repeats::Caught, cli::StopSignals::Blocking::Interrupt);
  ignoreBrokenPipes();
  // A database given serves E-ARC requests whatever the default method.
  // Without one the service plans every method but E-ARC, and answers an
  // E-ARC request with an error; E-ARC as the default is refused here, as
  // most requests would be errors, before anything is bound or opened.
  const Method store_method = o.db.empty() ? method : Method::Earc;
  requireDatabaseFor(store_method, o.db);
  if (o.db_row_cache_mb && o.db.empty()) throw InputError("", "--db-row-cache-mb", "is for the experience database (--db)");
  // The socket next: a second service on the same path is refused before
  // it touches the database. Clients that connect meanwhile wait in the
  // backlog until the store is open.
  Fd listener;
  if (!o.socket.empty()) listener = listenOn(o.socket);
  std::shared_ptr<exp::ExperienceStore> store;
  try {
    store = openStoreForPlanning(store_method, o.db, true, rowCacheBytes(o.db_row_cache_mb));
    // A damaged file keeps the service from starting, as it always did;
    // the check only ran while the index loaded.
    if (store) exp::withInputErrors(o.db, [&] { store->awaitCheck(); });
  } catch (...) {
    if (!o.socket.empty()) ::unlink(o.socket.c_str());
    throw;
  }
  // Its plans watch the signals' stop flag: one that came before now
  // stops it at once.
  service::Service service(store, settings, &cli::stopFlag());
  std::cerr << "earc-plan serve: "
            << (store ? o.db + " (" + std::to_string(store->size()) + " experiences)"
                      : std::string("no experience database (method earc refused)"))
            << ", requests on stdin" << (o.socket.empty() ? "" : " and " + o.socket) << "\n";
  try {
    Server(service, std::move(listener), signals).run();
  } catch (...) {
    if (!o.socket.empty()) ::unlink(o.socket.c_str());
    throw;
  }
  if (!o.socket.empty()) ::unlink(o.socket.c_str());
  service.close();  // learned rows are committed already; counters, checkpoint
  const auto& n = service.counters();
  std::cerr << "earc-plan serve: " << (signals.signal() ? signals.signalName() : "end of input")
            << ": " << n.requests << " requests, " << n.solved << " solved, " << n.errors << " errors, " << n.learned
            << " experiences learned";
  if (n.db.solved > 0) std::cerr << ", database answered " << n.db.answered() << " of " << n.db.solved << " solved subproblems";
  std::cerr << (store ? "; database closed\n" : "\n");
  return 0;
}

void setupServe(CLI::App& app) {
  auto opts = std::make_shared<ServeOptions>();
  auto* cmd = app.add_subcommand(
      "serve", "Answer planning requests (JSON lines, protocol earc.service.v1), keeping one experience database open (--db)");
  cmd->add_option("--db", opts->db,
                  "Experience database (created when missing); needed when --method is earc, the default")
      ->check(earc::cli::kFileName);
  cmd->add_option("--socket", opts->socket, "Also accept requests on this Unix domain socket");
  cmd->add_option("--method", opts->method, "Method for requests that name none")->capture_default_str();
  cmd->add_option("--time-limit", opts->time_limit, "Time limit for requests that give none (s)")
      ->check(earc::cli::kFinitePositive)
      ->capture_default_str();
  cmd->add_option("--seed", opts->seed, "Seed for requests that give none")->check(earc::cli::kWholeNumber)->capture_default_str();
  cmd->add_flag("--deterministic", opts->deterministic,
                "Count ARC's and E-ARC's solver budgets in work done, not seconds, for requests that do not say "
                "(\"deterministic\": false); see earc-plan plan --deterministic");
  cmd->add_option("--roadmap-cache-mib", opts->roadmap_cache_mib,
                  "Keep the robots' roadmaps between requests, up to this many MiB, for requests on the same "
                  "world, robots and seed (the same plans; 0: build them anew every time)")
      ->check(CLI::Range(std::size_t{0}, std::size_t{1} << 20))
      ->capture_default_str();
  addRowCacheOption(*cmd, opts->db_row_cache_mb);
  cmd->callback([opts] { cli::setExitCode(runServe(*opts)); });
}

cli::Registrar registered_serve("earc-plan", "serve", setupServe);

}  // namespace
}  // namespace earc
