#include "earc/experience/sqlite.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include "earc/util/format.hpp"

namespace earc::exp {

namespace {

bool isBusy(int rc) {
  int primary = rc & 0xff;
  return primary == SQLITE_BUSY || primary == SQLITE_LOCKED;
}

std::string fileOf(sqlite3* db) {
  const char* f = sqlite3_db_filename(db, "main");
  return f && *f ? f : "<memory>";
}

// The 100-byte header of an SQLite file, read before SQLite opens it;
// nothing for a short or unreadable file or one without SQLite's magic.
// Read through SQLite's own file layer, never through a descriptor of our
// own: closing any descriptor of a file drops every POSIX lock this
// process holds on it (fcntl semantics), SQLite's included. A plan's
// background quick_check opened a second connection and read the header
// so, and from then on its main connection held no lock: another process
// closing the database took itself for the last user, checkpointed and
// deleted the WAL under it, and rows were lost and the file damaged. The
// unix VFS keeps such a descriptor open until the file's last lock in the
// process is released.
// The name given is resolved first, as SQLite resolves a main database's
// (xFullPathname): the unix VFS opens with O_NOFOLLOW and refuses a
// symbolic link, so through a link the header went unread, and with it
// every check that reads it.
using SqliteHeader = std::array<unsigned char, 100>;
std::optional<SqliteHeader> sqliteHeader(const std::string& path) {
  sqlite3_vfs* vfs = sqlite3_vfs_find(nullptr);
  if (!vfs) return std::nullopt;
  // A main-database name as SQLite makes them (double NUL-terminated, so
  // the VFS may look for URI parameters after it).
  const std::unique_ptr<const char, decltype(&sqlite3_free_filename)> name(
      sqlite3_create_filename(databaseFile(path).c_str(), "", "", 0, nullptr), &sqlite3_free_filename);
  if (!name) return std::nullopt;  // out of memory; a null name would open a temporary file
  // sqlite3_file's state, as large as the VFS asks, suitably aligned;
  // allocated before the file is open, so that nothing throws while it is.
  std::vector<std::max_align_t> state((static_cast<std::size_t>(vfs->szOsFile) + sizeof(std::max_align_t) - 1) /
                                      sizeof(std::max_align_t));
  auto* file = reinterpret_cast<sqlite3_file*>(state.data());
  SqliteHeader h{};
  int flags = 0;
  const int opened = vfs->xOpen(vfs, name.get(), file, SQLITE_OPEN_READONLY | SQLITE_OPEN_MAIN_DB, &flags);
  const bool read = opened == SQLITE_OK && file->pMethods->xRead(file, h.data(), static_cast<int>(h.size()), 0) == SQLITE_OK;
  if (file->pMethods) file->pMethods->xClose(file);
  static constexpr char kMagic[] = "SQLite format 3";  // and its NUL: 16 bytes
  if (!read || std::memcmp(h.data(), kMagic, sizeof kMagic) != 0) return std::nullopt;
  return h;
}

// The header's big-endian 32-bit number at byte `at`.
std::uint64_t be32(const SqliteHeader& h, int at) {
  return std::uint64_t{h[at]} << 24 | std::uint64_t{h[at + 1]} << 16 | std::uint64_t{h[at + 2]} << 8 | h[at + 3];
}

// Where SQLite keeps a database's -wal and -shm: beside the real file,
// through any link.
struct RealFile {
  std::filesystem::path path, dir;
};
RealFile realFile(const std::string& path) {
  RealFile f{databaseFile(path), {}};
  f.dir = f.path.parent_path();
  if (f.dir.empty()) f.dir = ".";
  return f;
}

// "truncated: N bytes, its header says M" when the file is shorter than the
// pages its SQLite header counts (a copy cut short): the one damage worth
// naming more plainly than SQLite's "malformed".
std::optional<std::string> truncation(const std::string& file) {
  const auto h = sqliteHeader(file);
  if (!h) return std::nullopt;
  std::uint64_t page = std::uint64_t{(*h)[16]} << 8 | (*h)[17];
  if (page == 1) page = 65536;
  // The page count is valid only when written by the same change as the
  // header's counter (SQLite 3.7.0 and later).
  if (be32(*h, 92) != be32(*h, 24)) return std::nullopt;
  const std::uint64_t want = be32(*h, 28) * page;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec || size >= want) return std::nullopt;
  return "truncated: " + std::to_string(size) + " bytes, its header says " + std::to_string(want);
}

// Errors that say what is wrong with the file rather than which statement
// met it: the user can act on "damaged" or "not a SQLite database", not on
// the SQL that happened to read the bad page first.
[[noreturn]] void throwForFile(const std::string& file, int rc, const std::string& raw_message,
                               std::string_view context) {
  // SQLite quotes a damaged schema's SQL, line breaks and all.
  const std::string message = oneLine(raw_message);
  const int primary = rc & 0xff;
  if (primary == SQLITE_NOTADB) throw ForeignDatabaseError(file + ": not a SQLite database");
  if (primary == SQLITE_CORRUPT) {
    if (auto cut = truncation(file))
      throw DamagedDatabaseError(file + ": damaged database file (" + *cut + "); restore a copy or rebuild it");
    throw DamagedDatabaseError(file + ": damaged database file (" + message +
                               "); restore a copy or rebuild it (earc-db verify lists what is wrong)");
  }
  if (primary == SQLITE_CANTOPEN || primary == SQLITE_READONLY) {
    // A WAL database is read through a -shm file beside it, which SQLite
    // must be able to make: in a directory this user may not write to
    // (a shared copy) it cannot, and says only "unable to open" (where
    // the file itself is writable, as for root) or "attempt to write a
    // readonly database" (where it is not, as for another user).
    const RealFile real = realFile(file);
    if (::access(real.dir.c_str(), W_OK) != 0)
      throw StoreError(file + ": cannot read: SQLite needs to make " + real.path.filename().string() +
                       "-shm beside it and directory " + real.dir.string() +
                       " is not writable (copy the database to a writable directory)");
  }
  if (primary == SQLITE_IOERR && (rc == SQLITE_IOERR_SHORT_READ || rc == SQLITE_IOERR_TRUNCATE))
    throw DamagedDatabaseError(file + ": damaged database file (truncated: " + message + ")");
  // A full disk is the same whichever statement met it ("executing
  // \"VACUUM INTO ?1\"", "COMMIT"): said plainly.
  if (primary == SQLITE_FULL) throw NoSpaceError(file + ": " + std::string(kDiskFull));
  std::string msg = file + ": " + std::string(context) + ": " + message;
  if (isBusy(rc)) throw BusyError(msg);
  throw StoreError(msg);
}

[[noreturn]] void throwFor(sqlite3* db, const std::string& file, int rc, std::string_view context) {
  throwForFile(file.empty() ? fileOf(db) : file, rc, sqlite3_errmsg(db), context);
}

}  // namespace

bool startsLikeSqlite(const std::string& path) { return sqliteHeader(path).has_value(); }

std::string literalName(const std::string& path) {
  // Debian's SQLite takes a name beginning "file:" as a URI (built with
  // SQLITE_USE_URI), and ":memory:" is no file at all: either would open
  // something other than the file the name says, one the checks before
  // opening never looked at.
  if (path.rfind("file:", 0) == 0 || path == ":memory:") return "./" + path;
  return path;
}

// Every symbolic link on the way is followed, a dangling one too (to the
// file SQLite would create). Look for -wal and -shm, or remove or rename
// the database, at the file this names, not at `path`.
std::string databaseFile(const std::string& path) {
  sqlite3_vfs* vfs = sqlite3_vfs_find(nullptr);
  if (!vfs || path.empty()) return path;
  std::string full(static_cast<std::size_t>(vfs->mxPathname) + 1, '\0');
  const int rc = vfs->xFullPathname(vfs, path.c_str(), static_cast<int>(full.size()), full.data());
  // SQLITE_OK_SYMLINK: resolved, and a link was followed on the way.
  if (rc != SQLITE_OK && rc != SQLITE_OK_SYMLINK) return path;  // a loop, a name too long: SQLite refuses it too
  full.resize(std::strlen(full.c_str()));
  return full;
}

std::string withoutFile(const std::string& message, const std::string& path) {
  std::error_code ec;
  for (const std::string& name : {path, std::filesystem::absolute(path, ec).lexically_normal().string()})
    if (!name.empty() && message.rfind(name + ": ", 0) == 0) return message.substr(name.size() + 2);
  return message;
}

// ---------------------------------------------------------------- Statement

Statement::Statement(sqlite3* db, std::string_view sql, std::string file) : db_(db), file_(std::move(file)) {
  sqlite3_stmt* raw = nullptr;
  int rc = sqlite3_prepare_v3(db, sql.data(), static_cast<int>(sql.size()), 0, &raw, nullptr);
  stmt_.reset(raw);
  if (rc == SQLITE_ERROR) {
    // The program's statements are fixed and the file's identity and
    // tables were checked at open: a column or table they name that is not
    // there means the file was edited or damaged. Said so in one line,
    // without the statement's SQL.
    const std::string message = oneLine(sqlite3_errmsg(db));
    if (message.starts_with("no such column") || message.starts_with("no such table") ||
        message.find(" has no column named ") != std::string::npos)
      throw DamagedDatabaseError((file_.empty() ? fileOf(db) : file_) + ": damaged database file (" + message +
                                 "; its schema version has it)");
  }
  if (rc != SQLITE_OK) throwFor(db, file_, rc, "preparing \"" + std::string(sql.substr(0, 60)) + "\"");
}

Statement& Statement::bind(int index, std::int64_t v) {
  int rc = sqlite3_bind_int64(stmt_.get(), index, v);
  if (rc != SQLITE_OK) throwFor(db_, file_, rc, "bind");
  return *this;
}

Statement& Statement::bind(int index, double v) {
  int rc = sqlite3_bind_double(stmt_.get(), index, v);
  if (rc != SQLITE_OK) throwFor(db_, file_, rc, "bind");
  return *this;
}

Statement& Statement::bind(int index, std::string_view text) {
  int rc = sqlite3_bind_text64(stmt_.get(), index, text.data(), text.size(), SQLITE_TRANSIENT, SQLITE_UTF8);
  if (rc != SQLITE_OK) throwFor(db_, file_, rc, "bind");
  return *this;
}

Statement& Statement::bindBlob(int index, std::span<const unsigned char> bytes) {
  // A zero-length blob must still be a blob, not NULL: pass a non-null pointer.
  static const unsigned char kEmpty = 0;
  int rc = sqlite3_bind_blob64(stmt_.get(), index, bytes.empty() ? &kEmpty : bytes.data(), bytes.size(),
                               SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) throwFor(db_, file_, rc, "bind");
  return *this;
}

bool Statement::step() {
  int rc = sqlite3_step(stmt_.get());
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) {
    sqlite3_reset(stmt_.get());
    return false;
  }
  sqlite3_reset(stmt_.get());
  throwFor(db_, file_, rc, std::string("executing \"") + std::string(std::string_view(sqlite3_sql(stmt_.get())).substr(0, 60)) + "\"");
}

void Statement::run() {
  while (step()) {
  }
}

void Statement::reset() {
  sqlite3_reset(stmt_.get());
  sqlite3_clear_bindings(stmt_.get());
}

std::string Statement::textAt(int col) const {
  const unsigned char* p = sqlite3_column_text(stmt_.get(), col);
  int n = sqlite3_column_bytes(stmt_.get(), col);
  return p ? std::string(reinterpret_cast<const char*>(p), static_cast<std::size_t>(n)) : std::string();
}

std::span<const unsigned char> Statement::blobAt(int col) const {
  const void* p = sqlite3_column_blob(stmt_.get(), col);
  int n = sqlite3_column_bytes(stmt_.get(), col);
  if (!p || n <= 0) return {};
  return {static_cast<const unsigned char*>(p), static_cast<std::size_t>(n)};
}

// --------------------------------------------------------------- Connection

namespace {

// Whether a file's header (none: short, unreadable or not SQLite) is in
// WAL mode (file format bytes 18 and 19 are 2) with this application_id
// (big-endian at byte 68). Any doubt is false.
bool ownWalHeader(const std::optional<SqliteHeader>& h, std::int64_t application_id) {
  if (application_id == 0) return false;
  if (!h || (*h)[18] != 2 || (*h)[19] != 2) return false;
  return static_cast<std::int64_t>(be32(*h, 68)) == application_id;
}

// SQLite writes 1 (rollback journal) or 2 (WAL) in the header's file
// format bytes, 18 (write version) and 19 (read version); earc's own files
// have 2. Any other value is damage (or a format no SQLite writes), and
// SQLite itself would find it late: a write version above 2 opens the
// file read-only, and only the first write fails ("attempt to write a
// readonly database", after a plan or a build's work); a read version
// above 2 reads as "not a database". Refused before SQLite opens the file,
// for every command alike.
void requireKnownFileFormat(const std::optional<SqliteHeader>& h, const std::string& path) {
  if (!h) return;  // not SQLite, or too short: SQLite says so itself
  for (const auto& [at, name] : {std::pair{18, "write"}, std::pair{19, "read"}}) {
    const int v = (*h)[static_cast<std::size_t>(at)];
    if (v != 1 && v != 2)
      throw DamagedDatabaseError(path + ": damaged database file (SQLite header byte " + std::to_string(at) +
                                 ", the file format " + name + " version, is " + std::to_string(v) +
                                 "; SQLite writes 1 or 2 there, earc 2); restore a copy or rebuild it");
  }
}

// The checks of a database file before SQLite opens it, and the flags to
// open it with; query_only: open our own WAL file read-write under PRAGMA
// query_only (ConnectionSettings::own_application_id).
int checkFileBeforeOpen(const std::string& path, OpenMode mode, const ConnectionSettings& settings, bool& query_only) {
  // SQLite would open a device or FIFO and hang reading it, or write a
  // journal beside /dev/null: refused before it is touched.
  {
    std::error_code ec;
    const auto st = std::filesystem::status(path, ec);
    if (std::filesystem::is_directory(st)) throw StoreError(path + ": is a directory, not a file");
    if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
      throw StoreError(path + ": " + std::string(kNotARegularFile));
  }
  const std::optional<SqliteHeader> header = sqliteHeader(path);
  requireKnownFileFormat(header, path);
  const RealFile real = realFile(path);
  const std::filesystem::path& dir = real.dir;
  query_only = mode == OpenMode::ReadOnly && ownWalHeader(header, settings.own_application_id);
  // Writing needs the file and its directory (for -wal and -shm): said
  // before any work, not as a failed PRAGMA or a failed commit after it.
  if (mode == OpenMode::ReadWrite) {
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec) && ::access(dir.c_str(), W_OK) != 0)
      throw StoreError(path + ": cannot write: directory " + dir.string() + " is not writable");
    if (std::filesystem::exists(real.path, ec) && ::access(real.path.c_str(), W_OK) != 0)
      throw StoreError(path + ": cannot write: the file is read-only");
  }
  return mode == OpenMode::ReadWrite ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE
         : query_only                ? SQLITE_OPEN_READWRITE
                                     : SQLITE_OPEN_READONLY;
}

}  // namespace

// File format bytes (18, 19) other than 1 or 2 are refused before SQLite
// opens the file. own_application_id: only a read-write connection removes
// -wal and -shm at the last close; reading the header first keeps a foreign
// file from being opened read-write (its WAL would be checkpointed).
Connection::Connection(const std::string& path, OpenMode mode, const ConnectionSettings& settings)
    : path_(path), mode_(mode), settings_(settings) {
  const bool memory = mode == OpenMode::Memory;
  bool query_only = false;
  int flags = memory ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_MEMORY
                     : checkFileBeforeOpen(path, mode, settings, query_only);
  // The store serializes access itself; the connection need not.
  flags |= SQLITE_OPEN_NOMUTEX | SQLITE_OPEN_EXRESCODE;
  sqlite3* raw = nullptr;
  int rc = sqlite3_open_v2(memory ? ":memory:" : literalName(path).c_str(), &raw, flags, nullptr);
  db_.reset(raw);
  if (rc != SQLITE_OK) {
    std::string why = raw ? sqlite3_errmsg(raw) : sqlite3_errstr(rc);
    // SQLite says "unable to open database file" for all of these: the
    // usual causes said as the output checks say them.
    std::error_code ec;
    const std::filesystem::path dir = realFile(path).dir;
    if (!memory && !std::filesystem::is_directory(dir, ec))
      why = "no directory " + dir.string();
    else if (!memory && mode != OpenMode::ReadWrite && !std::filesystem::exists(path, ec))
      why = "no such file";
    throw StoreError(path + ": cannot open: " + why);
  }
  sqlite3* db = db_.get();
  sqlite3_extended_result_codes(db, 1);
  // Defensive: no writable_schema, no journal_mode=OFF, no raw shadow-table
  // writes; untrusted schema: functions in a file's views and triggers may
  // not have side effects.
  sqlite3_db_config(db, SQLITE_DBCONFIG_DEFENSIVE, 1, nullptr);
  sqlite3_db_config(db, SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, nullptr);
  sqlite3_db_config(db, SQLITE_DBCONFIG_ENABLE_LOAD_EXTENSION, 0, nullptr);
  sqlite3_busy_timeout(db, settings_.busy_timeout_ms);
  exec("PRAGMA trusted_schema = OFF");
  exec("PRAGMA foreign_keys = ON");
  if (query_only) exec("PRAGMA query_only = ON");
  if (mode == OpenMode::Hostile) {
    sqlite3_limit(db, SQLITE_LIMIT_LENGTH, kHostileMaxLength);
    exec("PRAGMA cell_size_check = ON");
    exec("PRAGMA mmap_size = 0");
  } else {
    exec("PRAGMA cache_size = -" + std::to_string(kPageCacheKiB));
    exec("PRAGMA mmap_size = " + std::to_string(kMmapBytes));
  }
}

void Connection::exec(std::string_view sql) {
  std::string text(sql);
  char* err = nullptr;
  int rc = sqlite3_exec(db_.get(), text.c_str(), nullptr, nullptr, &err);
  if (rc != SQLITE_OK) {
    std::string msg = err ? err : sqlite3_errstr(rc);
    sqlite3_free(err);
    throwForFile(path_, rc, msg, text.substr(0, 60));
  }
}

std::vector<std::string> checkProblemLines(const std::string& row) {
  std::vector<std::string> lines;
  for (std::size_t at = 0; at < row.size();) {
    const std::size_t end = std::min(row.find('\n', at), row.size());
    std::string line = row.substr(at, end - at);
    at = end + 1;
    if (line != "ok" && line != "*** in database main ***") lines.push_back(std::move(line));
  }
  return lines;
}

void Connection::requireQuickCheck() { requireCheck("quick_check"); }

void Connection::requireIntegrityCheck() { requireCheck("integrity_check"); }

// Each check reads every page once: unmapped and with a small page cache,
// else the whole file stays in the process's memory. integrity_check also
// finds an index missing rows (a flipped byte in an index page passes
// quick_check), into which a write would compound the damage.
void Connection::requireCheck(const char* pragma) {
  const std::int64_t mmap = pragmaInt("mmap_size"), cache = pragmaInt("cache_size");
  exec("PRAGMA mmap_size = 0");
  exec("PRAGMA cache_size = -" + std::to_string(kQuickCheckCacheKiB));
  struct Restore {
    Connection& c;
    std::int64_t mmap, cache;
    ~Restore() {
      try {
        c.exec("PRAGMA cache_size = " + std::to_string(cache));
        c.exec("PRAGMA mmap_size = " + std::to_string(mmap));
      } catch (...) {  // settings only: the connection stays usable
      }
    }
  } restore{*this, mmap, cache};
  Statement check = prepare("PRAGMA " + std::string(pragma));
  std::string first;
  std::size_t problems = 0;
  while (check.step())
    for (std::string& line : checkProblemLines(check.textAt(0)))
      if (problems++ == 0) first = oneLine(std::move(line));
  if (problems > 0)
    throw DamagedDatabaseError(path_ + ": damaged database file (" + pragma + ": " + first +
                               (problems > 1 ? "; " + std::to_string(problems - 1) + " more" : std::string()) +
                               "); restore a copy or rebuild it (earc-db verify lists what is wrong)");
}

std::int64_t Connection::pragmaInt(std::string_view pragma) {
  Statement s = prepare("PRAGMA " + std::string(pragma));
  std::int64_t v = s.step() ? s.int64At(0) : 0;
  s.reset();
  return v;
}

std::string Connection::pragmaText(std::string_view pragma) {
  Statement s = prepare("PRAGMA " + std::string(pragma));
  std::string v = s.step() ? s.textAt(0) : std::string();
  s.reset();
  return v;
}

void Connection::enableWal() {
  std::string mode = pragmaText("journal_mode = WAL");
  if (mode != "wal")
    throw StoreError(path_ + ": cannot switch to WAL journaling (got \"" + mode +
                     "\"); the file system may not support shared memory (network drive?)");
  exec("PRAGMA journal_size_limit = " + std::to_string(kJournalSizeLimit));
  // FULL: a commit that returned is on disk even across a power cut; the
  // store's transactions are few and small, so the fsync is affordable.
  exec("PRAGMA synchronous = FULL");
}

void Connection::checkpointPassive() {
  if (mode_ != OpenMode::ReadWrite) return;
  // Passive never blocks and never fails for busy readers; nothing to handle.
  sqlite3_wal_checkpoint_v2(db_.get(), nullptr, SQLITE_CHECKPOINT_PASSIVE, nullptr, nullptr);
}

std::string Connection::message(int rc) const { return sqlite3_errstr(rc); }

void Connection::rollbackQuietly() {
  if (!sqlite3_get_autocommit(db_.get())) sqlite3_exec(db_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
}

void Connection::backoff(int attempt) const {
  // Doubling delay with jitter so two waiting processes do not retry in step.
  auto base = settings_.first_backoff * (1 << std::min(attempt - 1, 16));
  if (base > settings_.max_backoff) base = settings_.max_backoff;
  thread_local std::minstd_rand jitter(std::random_device{}());
  auto ms = base.count() / 2 + static_cast<long>(jitter() % static_cast<unsigned>(base.count() + 1));
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

void Connection::throwBusy(int attempts) const {
  throw BusyError(path_ + ": database stayed locked by another process through " + std::to_string(attempts) +
                  " attempts (busy_timeout " + std::to_string(settings_.busy_timeout_ms) +
                  " ms each); is a long transaction holding it?");
}

// ------------------------------------------------------------ file identity

namespace {

std::string hex32(std::int64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%08llx", static_cast<unsigned long long>(v) & 0xffffffffull);
  return buf;
}

// The four characters an application_id spells ("EARC").
std::string fourCharacters(std::int64_t v) {
  std::string s;
  for (int shift = 24; shift >= 0; shift -= 8) s += static_cast<char>((v >> shift) & 0xff);
  return s;
}

void requireTables(Connection& db, int version, std::span<const TableSince> tables) {
  Statement s = db.prepare("SELECT count(*) FROM sqlite_schema WHERE type = 'table' AND name = ?1");
  for (const TableSince& t : tables) {
    if (t.version > version) continue;
    s.bind(1, std::string_view(t.name));
    s.step();
    const bool there = s.int64At(0) == 1;
    s.reset();
    if (!there)
      throw DamagedDatabaseError(db.path() + ": damaged database file (table " + t.name +
                                 " is missing; schema version " + std::to_string(version) + " has it)");
  }
}

}  // namespace

// A missing table (damaged or edited file) is refused here, before a
// statement needing it fails with SQL text.
int checkFileIdentity(Connection& db, const FileIdentity& identity) {
  // One statement, one snapshot: another process may be creating the file
  // right now, and separate reads could mix its before and after.
  Statement s = db.prepare(
      "SELECT (SELECT application_id FROM pragma_application_id), (SELECT user_version FROM pragma_user_version), "
      "(SELECT count(*) FROM sqlite_schema)");
  s.step();  // NOTADB -> ForeignDatabaseError
  const std::int64_t app = s.int64At(0);
  const int version = static_cast<int>(s.int64At(1));
  const std::int64_t objects = s.int64At(2);
  s.reset();
  const std::string program = identity.program;
  if (app == identity.application_id) {
    if (version > identity.program_version)
      throw SchemaVersionError(db.path() + ": schema version " + std::to_string(version) +
                                   " is newer than this program's version " + std::to_string(identity.program_version) +
                                   "; use a newer " + program + " (this one would not understand the file)",
                               version, identity.program_version);
    if (version < 1)
      throw ForeignDatabaseError(db.path() + ": " + program + " application_id but schema version " +
                                 std::to_string(version) + "; the file was not created by " + program);
    requireTables(db, version, identity.tables);
    return version;
  }
  if (app == 0 && version == 0 && objects == 0) return 0;  // empty or new file
  throw ForeignDatabaseError(db.path() + ": not an " + identity.kind + " (application_id " + hex32(app) +
                             ", expected " + hex32(identity.application_id) + " \"" +
                             fourCharacters(identity.application_id) + "\"; " + std::to_string(objects) +
                             " schema objects, user_version " + std::to_string(version) + ")");
}

}  // namespace earc::exp
