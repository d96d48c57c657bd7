// A thin RAII layer over the SQLite C API for the experience store: one
// Connection per open file, Statements finalized by unique_ptr, typed errors,
// and write transactions that begin IMMEDIATE and are retried whole when
// another process holds the write lock (shared/design/reliability.md).
//
// A Connection is not thread-safe; the store serializes its use. Never open
// a Connection before fork() and use it after.
#pragma once

#include <sqlite3.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace earc::exp {

// Every error about a database file; what() names the file.
class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The file is not an earc experience database: not SQLite at all, or a
// SQLite file of another application (foreign application_id or tables).
class ForeignDatabaseError : public StoreError {
 public:
  using StoreError::StoreError;
};

// The file is damaged (malformed to SQLite, failing quick_check or
// integrity_check, or with header bytes SQLite never writes); what() names
// the file and says what to do.
class DamagedDatabaseError : public StoreError {
 public:
  using StoreError::StoreError;
};

// The file's schema is newer than this program understands (or, for a
// read-only open, older than the program and not migratable in place).
class SchemaVersionError : public StoreError {
 public:
  SchemaVersionError(const std::string& what, int file_version, int program_version)
      : StoreError(what), file_version_(file_version), program_version_(program_version) {}
  int fileVersion() const { return file_version_; }
  int programVersion() const { return program_version_; }

 private:
  int file_version_;
  int program_version_;
};

// The write lock stayed with another connection through every retry.
class BusyError : public StoreError {
 public:
  using StoreError::StoreError;
};

// A write that could not be made for want of a resource (disk room, the
// server's connection): it was rolled back, and the store holds what it
// held. A plan made meanwhile is kept; what it learned is reported lost.
class WriteLostError : public StoreError {
 public:
  using StoreError::StoreError;
};

// The disk (or the file's page limit) had no room for a write, which was
// rolled back. what() is "FILE: " + kDiskFull, without the statement that
// met it.
class NoSpaceError : public WriteLostError {
 public:
  using WriteLostError::WriteLostError;
};

// A stored row failed validation; what() names the row id.
class CorruptRowError : public StoreError {
 public:
  CorruptRowError(std::int64_t row, const std::string& reason)
      : StoreError("row " + std::to_string(row) + ": " + reason), row_(row), reason_(reason) {}
  std::int64_t row() const { return row_; }
  const std::string& reason() const { return reason_; }

 private:
  std::int64_t row_;
  std::string reason_;
};

// The problems in one result row of PRAGMA quick_check or integrity_check,
// a line each: SQLite reports page-level damage as several lines in one
// row after "*** in database main ***", and a sound file as "ok" (none).
std::vector<std::string> checkProblemLines(const std::string& row);

// Whether the file begins with SQLite's header, read through SQLite's file
// layer so that this process's locks on the file stay (see sqlite.cpp).
bool startsLikeSqlite(const std::string& path);

// The file SQLite opens for `path`, symbolic links followed as SQLite
// follows them (`path` when it cannot be resolved): where its -wal and
// -shm lie. For the filesystem only; messages name `path`.
std::string databaseFile(const std::string& path);

// `path` as a name SQLite opens as that very file: a relative name that
// SQLite would read as a URI ("file:...") or as an in-memory database
// (":memory:") is given as "./" + path.
std::string literalName(const std::string& path);

// A StoreError's message without its leading "FILE: " (path as given, or
// as SQLite names it, absolute), for errors that name the file themselves.
std::string withoutFile(const std::string& message, const std::string& path);

struct StatementFinalizer {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
struct ConnectionCloser {
  void operator()(sqlite3* db) const { sqlite3_close_v2(db); }
};

// A prepared statement. step() throws BusyError for SQLITE_BUSY/LOCKED (the
// caller's transaction is then retried whole) and StoreError otherwise.
class Statement {
 public:
  // `file` names the database in errors (default: SQLite's absolute name).
  Statement(sqlite3* db, std::string_view sql, std::string file = {});

  Statement& bind(int index, std::int64_t v);
  Statement& bind(int index, int v) { return bind(index, static_cast<std::int64_t>(v)); }
  Statement& bind(int index, double v);
  Statement& bind(int index, std::string_view text);
  Statement& bindBlob(int index, std::span<const unsigned char> bytes);

  // True when a row is available, false when the statement is done.
  bool step();
  // Steps to completion, ignoring rows.
  void run();
  void reset();

  int columnType(int col) const { return sqlite3_column_type(stmt_.get(), col); }
  std::int64_t int64At(int col) const { return sqlite3_column_int64(stmt_.get(), col); }
  double doubleAt(int col) const { return sqlite3_column_double(stmt_.get(), col); }
  std::string textAt(int col) const;
  std::span<const unsigned char> blobAt(int col) const;
  // The column's name in the result (its name in the table, or the
  // expression selected), for messages about a value in it.
  std::string columnName(int col) const {
    const char* name = sqlite3_column_name(stmt_.get(), col);
    return name ? name : "";
  }

 private:
  sqlite3* db_;
  std::string file_;
  std::unique_ptr<sqlite3_stmt, StatementFinalizer> stmt_;
};

enum class OpenMode {
  ReadWrite,  // create when missing, WAL, writable
  ReadOnly,   // our own file, no writes (inspect, export, curate -o, bench table)
  Hostile,    // an import source or verify: read-only, cell_size_check, no mmap, length limit
  Memory,     // a new, empty database in memory; the path only names it in messages
};

// Connection tuning. Named here so every connection is opened alike.
struct ConnectionSettings {
  // How long one statement waits for another process's lock before
  // SQLITE_BUSY: long enough to cover another planner's short insert, short
  // enough that a planner never stalls for long.
  int busy_timeout_ms = 2000;
  // Whole-transaction retries after SQLITE_BUSY, with doubling backoff.
  int write_attempts = 8;
  std::chrono::milliseconds first_backoff{5};
  std::chrono::milliseconds max_backoff{400};
  // ReadOnly mode: a file whose header says WAL mode and this
  // application_id (0: never) is opened read-write under PRAGMA query_only,
  // so that closing it removes its -wal and -shm.
  std::int64_t own_application_id = 0;
};

// Cap on the WAL file kept after a checkpoint (bytes).
inline constexpr std::int64_t kJournalSizeLimit = 64ll << 20;
// Page cache of our own connections (KiB): retrieval reads k rows at random
// places in the file; keeping recently read pages saves the system calls.
inline constexpr int kPageCacheKiB = 32 * 1024;
// Memory-mapped reads of our own files (never of hostile ones): a page read
// becomes a memory access instead of a system call.
inline constexpr std::int64_t kMmapBytes = 1ll << 30;
// Page cache while quick_check reads the whole file (KiB).
inline constexpr int kQuickCheckCacheKiB = 2 * 1024;
// Largest string or blob a hostile file may hand us (bytes): a path blob of
// 4 robots x 5 joints x 100,000 steps is 16 MB.
inline constexpr int kHostileMaxLength = 64 << 20;
// Said of a database file SQLite could not write for want of room
// (SQLITE_FULL), whichever statement met it.
inline constexpr const char* kDiskFull = "cannot write: the disk is full";
// Said of a device, FIFO or socket given as a database.
inline constexpr const char* kNotARegularFile = "not a regular file (a device, FIFO or socket); a database is a file";

class Connection {
 public:
  // Opens and configures the file, Hostile with the stricter limits; the
  // journal mode is left to enableWal(). Throws StoreError naming the file
  // (DamagedDatabaseError for a header SQLite never writes).
  Connection(const std::string& path, OpenMode mode, const ConnectionSettings& settings = {});

  const std::string& path() const { return path_; }
  OpenMode mode() const { return mode_; }
  sqlite3* handle() const { return db_.get(); }

  void exec(std::string_view sql);
  Statement prepare(std::string_view sql) { return Statement(db_.get(), sql, path_); }
  std::int64_t pragmaInt(std::string_view pragma);
  std::string pragmaText(std::string_view pragma);

  // PRAGMA quick_check (all but index contents), reading the whole file
  // with little memory: throws DamagedDatabaseError naming the file and the
  // first problem.
  void requireQuickCheck();

  // PRAGMA integrity_check: quick_check's checks and index contents too;
  // the same error and memory. Slower: for the offline writers
  // (StoreOptions::full_check), never for a planner's open.
  void requireIntegrityCheck();

  // journal_mode=WAL (checked: a file system without WAL support is an
  // error), journal_size_limit, synchronous=FULL.
  void enableWal();

  // Runs body() in BEGIN IMMEDIATE ... COMMIT, run again on SQLITE_BUSY (at
  // most settings.write_attempts times, then BusyError); another exception
  // rolls back and propagates. body's effects must stay in the database.
  template <class Body>
  auto write(Body&& body) -> decltype(body());

  // Runs body() in one read transaction (one snapshot, one WAL read lock),
  // or as it is inside a transaction already. An exception rolls back and
  // propagates.
  template <class Body>
  auto read(Body&& body) -> decltype(body());

  // Runs f(), again after a doubling backoff on BusyError, at most
  // settings.write_attempts times. For steps outside a transaction that the
  // busy handler does not wait on (switching a new file to WAL).
  template <class F>
  auto retryWhileBusy(F&& f) -> decltype(f());

  // PRAGMA-free passive checkpoint: copies what it can from the WAL
  // without waiting for readers (keeps the WAL from growing without bound
  // behind a long-lived reader).
  void checkpointPassive();

  // Human-readable message for an SQLite result code on this connection.
  std::string message(int rc) const;

 private:
  // Runs body() between `begin` and COMMIT; any exception rolls back.
  template <class Body>
  auto transaction(const char* begin, Body&& body) -> decltype(body());
  void rollbackQuietly();
  // requireQuickCheck and requireIntegrityCheck: PRAGMA `pragma`.
  void requireCheck(const char* pragma);
  void backoff(int attempt) const;
  [[noreturn]] void throwBusy(int attempts) const;

  std::string path_;
  OpenMode mode_;
  ConnectionSettings settings_;
  std::unique_ptr<sqlite3, ConnectionCloser> db_;
};

template <class F>
auto Connection::retryWhileBusy(F&& f) -> decltype(f()) {
  for (int attempt = 1;; ++attempt) {
    try {
      return f();
    } catch (const BusyError&) {
      if (attempt >= settings_.write_attempts) throwBusy(attempt);
      backoff(attempt);
    }
  }
}

template <class Body>
auto Connection::transaction(const char* begin, Body&& body) -> decltype(body()) {
  try {
    exec(begin);
    if constexpr (std::is_void_v<decltype(body())>) {
      body();
      exec("COMMIT");
    } else {
      auto result = body();
      exec("COMMIT");
      return result;
    }
  } catch (...) {
    rollbackQuietly();  // busy or not: nothing of this attempt stays
    throw;
  }
}

template <class Body>
auto Connection::read(Body&& body) -> decltype(body()) {
  if (!sqlite3_get_autocommit(db_.get())) return body();
  return transaction("BEGIN", body);
}

template <class Body>
auto Connection::write(Body&& body) -> decltype(body()) {
  return retryWhileBusy([&]() -> decltype(body()) { return transaction("BEGIN IMMEDIATE", body); });
}

// A table of an application's file and the schema version that added it
// (a migration adds, never drops one).
struct TableSince {
  const char* name;
  int version;
};

// What makes a SQLite file one application's: the experience store's
// ("EARC") and earc-bench's results ("EBNC") are checked alike.
struct FileIdentity {
  std::int64_t application_id;
  const char* kind;     // "earc experience database", in messages
  const char* program;  // "earc": the program whose newer version reads a newer file
  int program_version;  // the newest schema version this program reads
  std::span<const TableSince> tables;
};

// The file's schema version (0: an empty file) when it is one of
// `identity`'s; else ForeignDatabaseError, SchemaVersionError (newer), or
// DamagedDatabaseError (a table of its version missing).
int checkFileIdentity(Connection& db, const FileIdentity& identity);

}  // namespace earc::exp
