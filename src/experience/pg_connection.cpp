#include "earc/experience/pg_connection.hpp"

#include <libpq-fe.h>

#include <cstdlib>
#include <cstring>
#include <thread>

namespace earc::exp {

namespace {

constexpr unsigned kOidBytea = 17, kOidInt8 = 20, kOidInt2 = 21, kOidInt4 = 23, kOidText = 25, kOidFloat8 = 701,
                   kOidInt8Array = 1016;

// libpq's messages span lines ("...failed: Connection refused\n\tIs the
// server running..."): one line, and never a password, even one libpq
// echoed.
std::string pgOneLine(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\t' || c == '\r') c = ' ';
  std::string out;
  for (char c : text)
    if (!(c == ' ' && (out.empty() || out.back() == ' '))) out += c;
  while (!out.empty() && out.back() == ' ') out.pop_back();
  if (const char* pw = std::getenv("PGPASSWORD"); pw && std::strlen(pw) >= 3)
    for (std::size_t at; (at = out.find(pw)) != std::string::npos;) out.replace(at, std::strlen(pw), "***");
  return out;
}

void putBigEndian(std::string& out, std::uint64_t v) {
  for (int i = 7; i >= 0; --i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

std::uint64_t readBigEndian(const char* p, int n) {
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}

bool lostState(std::string_view state) {
  // 08: connection exceptions; 57P01..57P03: the server shutting down or
  // not yet accepting connections.
  return state.substr(0, 2) == "08" || state == "57P01" || state == "57P02" || state == "57P03";
}

}  // namespace

bool isPostgresLocation(std::string_view location) {
  return location.rfind("postgresql://", 0) == 0 || location.rfind("postgres://", 0) == 0;
}

std::string maskedLocation(std::string_view location) {
  std::string s(location);
  const std::size_t scheme = s.find("://");
  if (scheme != std::string::npos) {
    const std::size_t start = scheme + 3;
    const std::size_t end = s.find_first_of("/?", start);
    const std::size_t at = s.rfind('@', end == std::string::npos ? s.size() : end);
    if (at != std::string::npos && at >= start) {
      const std::size_t colon = s.find(':', start);
      if (colon != std::string::npos && colon < at) s.replace(colon + 1, at - colon - 1, "***");
    }
  }
  for (std::size_t at = 0; (at = s.find("password=", at)) != std::string::npos;) {
    at += std::strlen("password=");
    const std::size_t end = s.find_first_of("& ", at);
    s.replace(at, (end == std::string::npos ? s.size() : end) - at, "***");
  }
  return s;
}

std::int64_t pgBinaryInt(std::span<const unsigned char> value) {
  const char* p = reinterpret_cast<const char*>(value.data());
  switch (value.size()) {
    case 2: return static_cast<std::int16_t>(readBigEndian(p, 2));
    case 4: return static_cast<std::int32_t>(readBigEndian(p, 4));
    case 8: return static_cast<std::int64_t>(readBigEndian(p, 8));
    default: throw StoreError("an integer of " + std::to_string(value.size()) + " bytes");
  }
}

double pgBinaryDouble(std::span<const unsigned char> value) {
  if (value.size() != 8) throw StoreError("a float8 of " + std::to_string(value.size()) + " bytes");
  const std::uint64_t bits = readBigEndian(reinterpret_cast<const char*>(value.data()), 8);
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// --- PgResult ---

void PgResult::Clear::operator()(pg_result* r) const { PQclear(r); }

PgResult::PgResult(pg_result* r) : result_(r) {}

int PgResult::rows() const { return PQntuples(result_.get()); }

bool PgResult::isNull(int row, int col) const { return PQgetisnull(result_.get(), row, col) != 0; }

// The value at (row, col), which must be `bytes` long: a missing row, a
// NULL or a value of another width is an error, never a read past it.
static const char* pgFixedValue(const pg_result* r, int row, int col, int bytes) {
  if (row >= PQntuples(r) || col >= PQnfields(r) || PQgetisnull(r, row, col) || PQgetlength(r, row, col) != bytes)
    throw StoreError("result row " + std::to_string(row) + ", column " + std::to_string(col) +
                     ": missing, NULL or not " + std::to_string(bytes) + " bytes");
  return PQgetvalue(r, row, col);
}

std::int64_t PgResult::int64At(int row, int col) const {
  const pg_result* r = result_.get();
  switch (PQftype(r, col)) {
    case kOidInt2: return static_cast<std::int16_t>(readBigEndian(pgFixedValue(r, row, col, 2), 2));
    case kOidInt4: return static_cast<std::int32_t>(readBigEndian(pgFixedValue(r, row, col, 4), 4));
    case kOidInt8: return static_cast<std::int64_t>(readBigEndian(pgFixedValue(r, row, col, 8), 8));
    default: throw StoreError("column " + std::to_string(col) + " is not an integer");
  }
}

double PgResult::doubleAt(int row, int col) const {
  if (PQftype(result_.get(), col) != kOidFloat8) throw StoreError("column " + std::to_string(col) + " is not float8");
  const std::uint64_t bits = readBigEndian(pgFixedValue(result_.get(), row, col, 8), 8);
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::string PgResult::textAt(int row, int col) const {
  return std::string(PQgetvalue(result_.get(), row, col), static_cast<std::size_t>(PQgetlength(result_.get(), row, col)));
}

std::span<const unsigned char> PgResult::bytesAt(int row, int col) const {
  return {reinterpret_cast<const unsigned char*>(PQgetvalue(result_.get(), row, col)),
          static_cast<std::size_t>(PQgetlength(result_.get(), row, col))};
}

// --- PgParams ---

PgParams& PgParams::push(std::string value, unsigned type, int format) {
  values_.push_back(std::move(value));
  types_.push_back(type);
  formats_.push_back(format);
  return *this;
}

PgParams& PgParams::add(std::int64_t v) {
  std::string s;
  putBigEndian(s, static_cast<std::uint64_t>(v));
  return push(std::move(s), kOidInt8, 1);
}

PgParams& PgParams::add(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  std::string s;
  putBigEndian(s, bits);
  return push(std::move(s), kOidFloat8, 1);
}

PgParams& PgParams::add(std::string_view text) { return push(std::string(text), kOidText, 1); }

PgParams& PgParams::addBytes(std::span<const unsigned char> bytes) {
  return push(std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()), kOidBytea, 1);
}

PgParams& PgParams::addIds(std::span<const std::int64_t> ids) {
  std::string s = "{";
  for (std::size_t i = 0; i < ids.size(); ++i) s += (i ? "," : "") + std::to_string(ids[i]);
  return push(s + "}", kOidInt8Array, 0);
}

PgParams& PgParams::append(const PgParams& more) {
  values_.insert(values_.end(), more.values_.begin(), more.values_.end());
  types_.insert(types_.end(), more.types_.begin(), more.types_.end());
  formats_.insert(formats_.end(), more.formats_.begin(), more.formats_.end());
  return *this;
}

// --- PgConnection ---

PgConnection::PgConnection(std::string location, PgSettings settings)
    : location_(std::move(location)), masked_(maskedLocation(location_)), settings_(settings) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(location_.c_str(), &error);
  if (!options) {
    const std::string why = error ? pgOneLine(error) : "not a connection URI";
    PQfreemem(error);
    throw StoreError(masked_ + ": " + why);
  }
  bool password = false;
  for (PQconninfoOption* o = options; o->keyword; ++o)
    if (std::strcmp(o->keyword, "password") == 0 && o->val && *o->val) password = true;
  PQconninfoFree(options);
  if (password)
    throw StoreError(masked_ +
                     ": a password in the URI is refused (it would show in process lists and logs); "
                     "give it in PGPASSWORD or ~/.pgpass");
  connect();
}

PgConnection::~PgConnection() {
  if (conn_) PQfinish(conn_);
}

void PgConnection::connect() {
  const std::string timeout = std::to_string(settings_.connect_timeout_s);
  // Defaults first: the URI's own values, expanded from dbname, win.
  const char* keys[] = {"connect_timeout", "application_name", "dbname", nullptr};
  const char* values[] = {timeout.c_str(), "earc", location_.c_str(), nullptr};
  conn_ = PQconnectdbParams(keys, values, 1);
  if (!conn_ || PQstatus(conn_) != CONNECTION_OK) {
    const std::string why = conn_ ? pgOneLine(PQerrorMessage(conn_)) : "out of memory";
    if (conn_) PQfinish(conn_);
    conn_ = nullptr;
    throw PgConnectionLostError(masked_ + ": cannot connect: " + why);
  }
  // Notices (a migration's "relation exists, skipping") are not ours to print.
  PQsetNoticeProcessor(conn_, [](void*, const char*) {}, nullptr);
}

void PgConnection::reconnect() {
  if (conn_) PQfinish(conn_);
  conn_ = nullptr;
  connect();
}

// --- PgCanceller ---

PgCanceller::~PgCanceller() { PQfreeCancel(handle_); }

bool PgCanceller::cancel() const {
  char error[256];
  return handle_ && PQcancel(handle_, error, sizeof error) == 1;
}

std::unique_ptr<PgCanceller> PgConnection::canceller() const {
  if (!conn_) throw PgConnectionLostError(masked_ + ": not connected");
  return std::make_unique<PgCanceller>(PQgetCancel(conn_));
}

bool PgConnection::inTransaction() const {
  return conn_ && PQtransactionStatus(conn_) != PQTRANS_IDLE && PQtransactionStatus(conn_) != PQTRANS_UNKNOWN;
}

void PgConnection::fail(pg_result* r, std::string_view sql) {
  const char* state_text = r ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  const std::string state = state_text ? state_text : "";
  std::string why = pgOneLine(r && *PQresultErrorMessage(r) ? PQresultErrorMessage(r) : PQerrorMessage(conn_));
  if (r) PQclear(r);
  if (why.rfind("ERROR: ", 0) == 0) why.erase(0, 7);
  const bool lost = !conn_ || PQstatus(conn_) == CONNECTION_BAD || lostState(state);
  std::string statement(sql.substr(0, sql.find_first_of("(\n")));
  while (!statement.empty() && statement.back() == ' ') statement.pop_back();
  const std::string message = masked_ + ": " + why + (statement.empty() ? "" : " (in: " + statement + ")");
  if (lost) {
    // Whatever state a broken connection is in, a new one is made for the
    // next attempt.
    if (conn_) PQfinish(conn_);
    conn_ = nullptr;
    throw PgConnectionLostError(masked_ + ": connection lost: " + why);
  }
  if (state == "40001" || state == "40P01") throw PgRetryableError(message);
  throw StoreError(message);
}

PgResult PgConnection::exec(std::string_view sql) {
  if (!conn_) throw PgConnectionLostError(masked_ + ": not connected");
  const std::string text(sql);
  pg_result* r = PQexec(conn_, text.c_str());
  const ExecStatusType status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(r, sql);
  return PgResult(r);
}

PgResult PgConnection::query(std::string_view sql, const PgParams& params) {
  if (!conn_) throw PgConnectionLostError(masked_ + ": not connected");
  const std::string text(sql);
  std::vector<const char*> values;
  std::vector<int> lengths;
  for (const std::string& v : params.values()) {
    values.push_back(v.data());
    lengths.push_back(static_cast<int>(v.size()));
  }
  static_assert(sizeof(unsigned) == sizeof(Oid));
  pg_result* r = PQexecParams(conn_, text.c_str(), static_cast<int>(params.size()),
                              reinterpret_cast<const Oid*>(params.types().data()), values.data(), lengths.data(),
                              params.formats().data(), 1);
  const ExecStatusType status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(r, sql);
  return PgResult(r);
}

void PgConnection::rollbackQuietly() {
  if (!conn_ || PQtransactionStatus(conn_) == PQTRANS_IDLE) return;
  if (pg_result* r = PQexec(conn_, "ROLLBACK")) PQclear(r);
}

void PgConnection::backoff(int attempt) const {
  auto wait = settings_.first_backoff * (1 << std::min(attempt - 1, 16));
  if (wait > settings_.max_backoff) wait = settings_.max_backoff;
  std::this_thread::sleep_for(wait);
}

}  // namespace earc::exp
