// A thin RAII layer over libpq for the PostgreSQL experience store: a
// connection made from a URI (postgresql://USER@HOST:PORT/DBNAME, the
// password only from PGPASSWORD or ~/.pgpass), queries with binary
// parameters and results, and write transactions retried whole on
// serialization failures, deadlocks and lost connections (reconnecting).
//
// A PgConnection is not thread-safe; the store serializes its use. Every
// message names the location with any password masked.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "earc/experience/sqlite.hpp"  // StoreError and its kinds

struct pg_conn;
struct pg_result;
struct pg_cancel;

namespace earc::exp {

// Whether a --db value names a PostgreSQL store (postgresql:// or postgres://).
bool isPostgresLocation(std::string_view location);

// The location with a password (user:PASSWORD@, password=...) replaced by
// "***": the only form of a URI that goes into a message.
std::string maskedLocation(std::string_view location);

// A statement the server rolled back that may succeed when run again:
// serialization failure (40001) or deadlock (40P01).
class PgRetryableError : public StoreError {
 public:
  using StoreError::StoreError;
};

// The connection broke, or the server is stopping or starting. A write
// that meets it through every attempt is lost (as on a full disk).
class PgConnectionLostError : public WriteLostError {
 public:
  using WriteLostError::WriteLostError;
};

// One query's result (binary format). Not thread-safe.
class PgResult {
 public:
  explicit PgResult(pg_result* r);
  int rows() const;
  bool isNull(int row, int col) const;
  std::int64_t int64At(int row, int col) const;   // int8, int4 or int2
  double doubleAt(int row, int col) const;        // float8
  std::string textAt(int row, int col) const;     // text
  std::span<const unsigned char> bytesAt(int row, int col) const;  // bytea

 private:
  struct Clear {
    void operator()(pg_result* r) const;
  };
  std::unique_ptr<pg_result, Clear> result_;
};

// A binary int2, int4 or int8 value (told apart by its length), and a
// float8. Throw StoreError for any other length.
std::int64_t pgBinaryInt(std::span<const unsigned char> value);
double pgBinaryDouble(std::span<const unsigned char> value);

// Parameters of one query, each sent in binary ($1, $2, ... in order).
class PgParams {
 public:
  PgParams& add(std::int64_t v);
  PgParams& add(int v) { return add(static_cast<std::int64_t>(v)); }
  PgParams& add(double v);
  PgParams& add(std::string_view text);
  PgParams& add(const char* text) { return add(std::string_view(text)); }
  PgParams& addBytes(std::span<const unsigned char> bytes);
  // An int8[] (sent as text: '{1,2,3}').
  PgParams& addIds(std::span<const std::int64_t> ids);
  // Every parameter of `more`, after these.
  PgParams& append(const PgParams& more);

  std::size_t size() const { return values_.size(); }
  const std::vector<std::string>& values() const { return values_; }
  const std::vector<unsigned>& types() const { return types_; }
  const std::vector<int>& formats() const { return formats_; }

 private:
  PgParams& push(std::string value, unsigned type, int format);
  std::vector<std::string> values_;
  std::vector<unsigned> types_;
  std::vector<int> formats_;
};

struct PgSettings {
  // Whole-transaction attempts after a retryable error or a lost
  // connection, with doubling backoff between them.
  int write_attempts = 10;
  std::chrono::milliseconds first_backoff{20};
  std::chrono::milliseconds max_backoff{2000};
  // Seconds libpq waits for a server that does not answer (connect_timeout;
  // a URI's own value wins).
  int connect_timeout_s = 10;
};

// Cancels the statement one connection runs, from another thread
// (libpq's PQcancel); made by PgConnection::canceller. Thread-safe.
class PgCanceller {
 public:
  explicit PgCanceller(pg_cancel* handle) : handle_(handle) {}
  ~PgCanceller();
  PgCanceller(const PgCanceller&) = delete;
  PgCanceller& operator=(const PgCanceller&) = delete;
  // Asks the server to cancel what the connection runs now (nothing when
  // idle); false when the request could not be sent.
  bool cancel() const;

 private:
  pg_cancel* handle_;
};

class PgConnection {
 public:
  // Connects. Throws StoreError naming the masked location: a password in
  // the URI (refused: PGPASSWORD or ~/.pgpass hold it), an unreachable
  // server, a refused login.
  explicit PgConnection(std::string location, PgSettings settings = {});
  ~PgConnection();
  PgConnection(const PgConnection&) = delete;
  PgConnection& operator=(const PgConnection&) = delete;

  // The masked location, for messages.
  const std::string& location() const { return masked_; }
  const PgSettings& settings() const { return settings_; }

  // Runs SQL without parameters (may hold several statements).
  PgResult exec(std::string_view sql);
  // One statement with parameters; results in binary.
  PgResult query(std::string_view sql, const PgParams& params = {});

  // Drops the connection and connects again; throws PgConnectionLostError.
  void reconnect();
  bool inTransaction() const;
  // A canceller of this connection's statements (valid until it reconnects
  // or closes). Throws PgConnectionLostError when not connected.
  std::unique_ptr<PgCanceller> canceller() const;

  // Runs body() in one transaction, again after a retryable error or a lost
  // connection (at most settings.write_attempts times; committed() settles a
  // COMMIT cut off). Rolled back on any exception, which is rethrown.
  template <class Body>
  auto write(Body&& body, const std::function<bool()>& committed = {}) -> decltype(body());

  // Runs f() once; when the connection is lost, reconnects and runs it
  // again (as write's attempts). For reads outside a transaction.
  template <class F>
  auto retryLost(F&& f) -> decltype(f());

  // Sleeps before attempt `attempt` + 1 (doubling, capped).
  void backoff(int attempt) const;

 private:
  void connect();
  [[noreturn]] void fail(pg_result* r, std::string_view sql);
  void rollbackQuietly();

  std::string location_;
  std::string masked_;
  PgSettings settings_;
  pg_conn* conn_ = nullptr;
  bool in_write_ = false;  // inside write(): a lost connection ends the attempt
};

template <class F>
auto PgConnection::retryLost(F&& f) -> decltype(f()) {
  for (int attempt = 1;; ++attempt) {
    try {
      return f();
    } catch (const PgConnectionLostError&) {
      if (attempt >= settings_.write_attempts || in_write_) throw;
      backoff(attempt);
      try {
        reconnect();
      } catch (const PgConnectionLostError&) {
        if (attempt + 1 >= settings_.write_attempts) throw;
      }
    }
  }
}

template <class Body>
auto PgConnection::write(Body&& body, const std::function<bool()>& committed) -> decltype(body()) {
  struct InWrite {
    bool& flag;
    explicit InWrite(bool& f) : flag(f) { flag = true; }
    ~InWrite() { flag = false; }
  } in_write{in_write_};
  for (int attempt = 1;; ++attempt) {
    bool committing = false;
    try {
      if (!conn_) reconnect();
      exec("BEGIN");
      if constexpr (std::is_void_v<decltype(body())>) {
        body();
        committing = true;
        exec("COMMIT");
        return;
      } else {
        auto result = body();
        committing = true;
        exec("COMMIT");
        return result;
      }
    } catch (const PgRetryableError&) {
      rollbackQuietly();
      if (attempt >= settings_.write_attempts) throw;
      backoff(attempt);
    } catch (const PgConnectionLostError&) {
      if (attempt >= settings_.write_attempts) throw;
      // Reconnect (retrying while the server comes back) before asking
      // whether a COMMIT that broke went through.
      for (;;) {
        backoff(attempt);
        try {
          reconnect();
          break;
        } catch (const PgConnectionLostError&) {
          if (++attempt >= settings_.write_attempts) throw;
        }
      }
      if (committing) {
        if (!committed) throw;
        if (committed()) {
          if constexpr (std::is_void_v<decltype(body())>)
            return;
          else
            throw;  // a result cannot be rebuilt: the caller's committed() must not say so
        }
      }
    } catch (...) {
      rollbackQuietly();
      throw;
    }
  }
}

}  // namespace earc::exp
