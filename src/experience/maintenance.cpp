#include "earc/experience/maintenance.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "earc/experience/key_index.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/pg_connection.hpp"
#include "earc/experience/rows.hpp"
#include "earc/experience/schema.hpp"
#include "earc/experience/store.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/format.hpp"

namespace earc::exp {

namespace {

std::int64_t fileSize(const std::string& path) {
  std::error_code ec;
  auto n = std::filesystem::file_size(path, ec);
  return ec ? 0 : static_cast<std::int64_t>(n);
}

// A non-negative sum read as a real number, as a count: the largest
// 64-bit integer where it is more (2^63 and up).
std::int64_t saturatingInt64(double v) {
  if (!(v > 0)) return 0;
  if (v >= 0x1p63) return std::numeric_limits<std::int64_t>::max();
  return std::llround(v);
}

std::int64_t count(Connection& db, const std::string& sql) {
  Statement s = db.prepare(sql);
  std::int64_t n = s.step() ? s.int64At(0) : 0;
  s.reset();
  return n;
}

// The ids to delete of rows in the current schema, read best first.
std::vector<std::int64_t> nearDuplicates(Connection& db, int version, double eps) {
  std::vector<DedupeRow> rows;
  Statement s = db.prepare(selectExperiencesSql(version) +
                           " ORDER BY succeeded_count DESC, retrieved_count DESC, id ASC");
  while (s.step()) {
    Experience e = readExperience(s);
    rows.push_back({e.id, e.cls, std::move(e.key)});
  }
  return nearDuplicateIds(rows, eps);
}

// Reads every row in id order, in one read transaction: each readable one
// goes to onRow, each damaged one (CorruptRowError) to onDamaged. verify
// lists the damage; curate counts what it kept.
template <class OnRow, class OnDamaged>
void scanRows(Connection& db, int version, OnRow&& onRow, OnDamaged&& onDamaged) {
  db.read([&] {
    Statement rows = db.prepare(selectExperiencesSql(version) + " ORDER BY id");
    while (rows.step()) {
      try {
        onRow(readExperience(rows));
      } catch (const CorruptRowError& e) {
        onDamaged(e);
      }
    }
  });
}

std::int64_t deleteIds(Connection& db, const std::vector<std::int64_t>& ids) {
  Statement del = db.prepare("DELETE FROM experiences WHERE id = ?1");
  for (std::int64_t id : ids) {
    del.bind(1, id);
    del.run();
    del.reset();
  }
  return static_cast<std::int64_t>(ids.size());
}

// The rows whose path blob is in format version 1 or 2, the older formats
// (no checksum; version 1 not compressed either): the magic, then the
// version little-endian. Not any blob that differs from the current
// format, which would count damaged blobs, and a newer earc's, as older.
std::string olderBlobsWhere() {
  static_assert(kPathBlobVersion == 3, "name every older version here");
  std::string hex;
  char byte[3];
  for (unsigned char c : kPathBlobMagic) {
    std::snprintf(byte, sizeof byte, "%02x", c);
    hex += byte;
  }
  return " WHERE substr(paths, 1, 6) IN (x'" + hex + "0100', x'" + hex + "0200')";
}

// Rewrites those blobs, a batch of rows at a time (a blob in memory per
// row of the batch, not per row of the file). Inside a write transaction.
std::int64_t rewriteOlderBlobs(Connection& db) {
  constexpr int kBatch = 256;
  Statement next = db.prepare("SELECT id, paths FROM experiences" + olderBlobsWhere() + " AND id > ?1 ORDER BY id LIMIT ?2");
  Statement put = db.prepare("UPDATE experiences SET paths = ?1 WHERE id = ?2");
  std::int64_t after = std::numeric_limits<std::int64_t>::min(), rewritten = 0;
  std::vector<std::pair<std::int64_t, std::vector<unsigned char>>> batch;
  for (int seen = kBatch; seen == kBatch;) {
    batch.clear();
    seen = 0;
    next.bind(1, after).bind(2, kBatch);
    while (next.step()) {
      ++seen;
      after = next.int64At(0);
      try {
        batch.emplace_back(after, encodePaths(decodePaths(next.blobAt(1), after)));
      } catch (const CorruptRowError&) {
        // left as it is: verify names it
      }
    }
    next.reset();
    for (auto& [id, blob] : batch) {
      put.bindBlob(1, blob).bind(2, id);
      put.run();
      put.reset();
      ++rewritten;
    }
  }
  return rewritten;
}

}  // namespace

std::optional<std::string> KeyDimensionCheck::add(const Experience& e) {
  auto [it, fresh] = first_.try_emplace(e.cls, e.key.size(), e.id);
  if (fresh || it->second.first == e.key.size()) return std::nullopt;
  return "row " + std::to_string(e.id) + ": key dimension " + std::to_string(e.key.size()) + " differs from row " +
         std::to_string(it->second.second) + " of the same class";
}

std::vector<std::int64_t> nearDuplicateIds(const std::vector<DedupeRow>& rows, double eps) {
  KeyIndex kept;
  std::size_t added = 0;
  std::vector<std::int64_t> drop;
  for (const DedupeRow& r : rows) {
    const ClassIndex* index = kept.find(r.cls);
    if (index) {
      auto n = index->nearest(r.key, 1);
      if (!n.empty() && n.front().distance <= eps) {
        drop.push_back(r.id);
        continue;
      }
    }
    kept.add(r.cls, r.id, r.key);
    if (++added % ClassIndex::kBulkSettleEvery == 0) kept.settle();
  }
  return drop;
}

InspectReport inspectDatabase(const std::string& path, int sample_entries, int history_lines) {
  if (isPostgresLocation(path)) return pgInspectDatabase(path, sample_entries, history_lines);
  ExperienceStore store(path, wholeFileStoreOptions(true));
  Connection& db = store.connection();
  InspectReport r;
  r.path = path;
  r.schema_version = store.schemaVersion();
  r.file_bytes = fileSize(path);
  r.wal_bytes = fileSize(databaseFile(path) + "-wal");  // beside the real file, through any link
  r.sessions = store.session();
  db.exec("BEGIN");  // one snapshot for every number
  const std::string usage = r.schema_version >= 2 ? "total(retrieved_count), total(succeeded_count), avg(solve_time_s)"
                                                  : "0, 0, 0.0";
  Statement classes = db.prepare(
      "SELECT kind, robot_count, signature, base_class, count(*), sum(length(key)), sum(length(paths)), " + usage +
      ", avg(cost) FROM experiences GROUP BY kind, robot_count, signature, base_class ORDER BY kind, robot_count, "
      "base_class, signature");
  while (classes.step()) {
    ClassSummary c;
    c.cls = {kindFromName(classes.textAt(0)).value_or(RobotKind::Mobile), static_cast<int>(classes.int64At(1)),
             classes.textAt(2), classes.textAt(3)};
    c.entries = classes.int64At(4);
    c.key_dim = c.entries ? classes.int64At(5) / c.entries / 8 : 0;
    c.path_bytes = classes.int64At(6);
    // total(): a sum that cannot overflow, whatever a row holds (a row
    // past kMaxUseCount is verify's to report).
    c.retrieved = saturatingInt64(classes.doubleAt(7));
    c.succeeded = saturatingInt64(classes.doubleAt(8));
    c.mean_solve_time_s = classes.doubleAt(9);
    c.mean_cost = classes.doubleAt(10);
    r.entries += c.entries;
    r.key_bytes += classes.int64At(5);
    r.path_bytes += c.path_bytes;
    r.classes.push_back(std::move(c));
  }
  Statement builds = db.prepare(r.schema_version >= 4
                                    ? "SELECT made_by, count(*) AS n FROM experiences GROUP BY made_by ORDER BY n DESC, made_by"
                                    : "SELECT '', count(*) FROM experiences HAVING count(*) > 0");
  while (builds.step()) r.builds.emplace_back(builds.textAt(0), builds.int64At(1));
  r.older_path_blobs = count(db, "SELECT count(*) FROM experiences" + olderBlobsWhere());
  Statement sample = db.prepare(selectExperiencesSql(r.schema_version) + " ORDER BY id LIMIT ?1");
  sample.bind(1, sample_entries);
  while (sample.step()) {
    try {
      r.samples.push_back(readExperience(sample));
    } catch (const CorruptRowError&) {
      // inspect shows what it can; verify names the bad rows
    }
  }
  r.history = readHistory(db, r.schema_version, history_lines);
  db.exec("COMMIT");
  return r;
}

nlohmann::json inspectJson(const InspectReport& r) {
  using nlohmann::json;
  json classes = json::array();
  for (const ClassSummary& c : r.classes) {
    // null: never retrieved (the text report's "-")
    const json hit_rate = c.hitRate() ? json(*c.hitRate()) : json(nullptr);
    classes.push_back({{"kind", kindName(c.cls.kind)},
                       {"robots", c.cls.robot_count},
                       {"base_class", c.cls.base_class},
                       {"signature", c.cls.signature},
                       {"entries", c.entries},
                       {"key_dim", c.key_dim},
                       {"path_bytes", c.path_bytes},
                       {"retrieved", c.retrieved},
                       {"succeeded", c.succeeded},
                       {"hit_rate", hit_rate},
                       {"mean_cost", c.mean_cost},
                       {"mean_solve_time_s", c.mean_solve_time_s}});
  }
  json builds = json::array();
  for (const auto& [build, rows] : r.builds) builds.push_back({{"made_by", build}, {"rows", rows}});
  json lines = json::array();
  for (const HistoryLine& l : r.history.lines)
    lines.push_back({{"at", utcTimeText(l.at)},
                     {"program", l.program},
                     {"operation", l.operation},
                     {"detail", l.detail},
                     {"rows_added", l.rows_added},
                     {"rows_removed", l.rows_removed}});
  json samples = json::array();
  for (const Experience& e : r.samples) samples.push_back(experienceToJson(e));
  return {{"format", "earc.inspect.v1"},
          {"database", r.path},
          {"schema_version", r.schema_version},
          {"file_bytes", r.file_bytes},
          {"wal_bytes", r.wal_bytes},
          {"sessions", r.sessions},
          {"entries", r.entries},
          {"path_bytes", r.path_bytes},
          {"key_bytes", r.key_bytes},
          {"older_path_blobs", r.older_path_blobs},
          {"classes", std::move(classes)},
          {"builds", std::move(builds)},
          // null: the file's schema keeps no history (before version 5)
          {"history", r.schema_version >= kHistorySchemaVersion
                          ? json{{"total", r.history.total}, {"lines", std::move(lines)}}
                          : json(nullptr)},
          {"samples", std::move(samples)}};
}

// Every row: column types, blob headers and lengths, finite numbers, key
// and class consistency; and one key dimension per class.
VerifyReport verifyDatabase(const std::string& path) {
  if (isPostgresLocation(path)) return pgVerifyDatabase(path);
  VerifyReport r;
  requireDatabaseFile(path);
  std::unique_ptr<Connection> db;
  // A file that cannot be read as an earc database at all (not SQLite,
  // foreign, newer, damaged where the schema lives) is bad input: one line,
  // exit 2. Past that point every problem is listed in the report.
  withInputErrors(path, [&] {
    db = std::make_unique<Connection>(path, OpenMode::Hostile);
    r.schema_version = checkIdentity(*db);
  });
  if (r.schema_version == 0) throw notYetADatabase(path);
  if (r.schema_version < currentSchemaVersion())
    r.notes.push_back("schema version " + std::to_string(r.schema_version) + " (this program: " +
                      std::to_string(currentSchemaVersion()) + "); migrated on the next read-write open");
  try {
    Statement integrity = db->prepare("PRAGMA integrity_check");
    while (integrity.step())
      for (const std::string& line : checkProblemLines(integrity.textAt(0)))
        r.problems.push_back("integrity_check: " + line);
  } catch (const StoreError& e) {
    r.problems.push_back(e.what());
  }
  KeyDimensionCheck key_dims;
  try {
    scanRows(
        *db, r.schema_version,
        [&](const Experience& e) {
          ++r.rows;
          if (auto problem = key_dims.add(e)) r.problems.push_back(*problem);
        },
        [&](const CorruptRowError& e) {
          ++r.rows;
          r.problems.push_back(e.what());
        });
  } catch (const StoreError& e) {
    // The damage integrity_check already met stops the row scan too: once.
    if (std::find(r.problems.begin(), r.problems.end(), e.what()) == r.problems.end()) r.problems.push_back(e.what());
  }
  // A file created with a history counts every row added or removed since:
  // a difference means rows were changed outside earc (not damage: a note).
  if (r.schema_version >= kHistorySchemaVersion && r.problems.empty()) {
    try {
      Statement h = db->prepare(
          "SELECT (SELECT operation FROM history ORDER BY id LIMIT 1), "
          "(SELECT coalesce(sum(rows_added - rows_removed), 0) FROM history)");
      if (h.step() && h.textAt(0) == "create") {
        const std::int64_t counted = h.int64At(1);
        if (counted != r.rows)
          r.notes.push_back("the history counts " + std::to_string(counted) +
                            " rows added and not removed, the file holds " + std::to_string(r.rows) +
                            ": rows were added or deleted outside earc");
      }
    } catch (const StoreError& e) {
      r.problems.push_back(e.what());
    }
  }
  return r;
}

namespace {

// The curate's line in the database's history: its options.
std::string curateDescription(const CurateSettings& s, const std::string& copy_of) {
  std::ostringstream out;
  if (!copy_of.empty()) out << "copy of " << copy_of << ":";
  auto add = [&](const std::string& part) { out << (out.tellp() > 0 ? " " : "") << part; };
  for (const std::string& m : s.merge) add("--merge " + m);
  if (s.dedupe_eps >= 0) add("--dedupe " + formatNumber(s.dedupe_eps));
  if (s.drop_unused)
    add("--drop-unused" +
        (s.older_than_sessions > 0 ? " --older-than-sessions " + std::to_string(s.older_than_sessions) : ""));
  for (const std::string& b : s.drop_made_by) add("--drop-made-by \"" + b + "\"");
  if (s.compact) add("--compact");
  if (s.vacuum) add("--vacuum");
  return out.str();
}

// Curates the database file at `target` in place.
// copy_of: the original, when this is the -o copy.
CurateReport curateFile(const std::string& target, const CurateSettings& settings, const std::string& copy_of = {}) {
  CurateReport r;
  r.curated_path = target;
  // Curation is not a planning session. In place, the file is checked
  // whole, indexes too, before any step writes to it; a -o copy was made
  // just now from a source checked so (copyDatabase).
  StoreOptions options = wholeFileStoreOptions(false);
  options.full_check = copy_of.empty();
  ExperienceStore store(target, options);
  store.describeHistory("curate", curateDescription(settings, copy_of));
  Connection& db = store.connection();
  // Rows deleted by a step, counted on the history line in its transaction.
  auto removed = [&](std::int64_t n) {
    store.history().record(db, store.schemaVersion(), 0, n);
    return n;
  };
  r.rows_before = count(db, "SELECT count(*) FROM experiences");
  // "Never retrieved" says nothing about a file no learning plan has used
  // yet (a fresh build): there --drop-unused would empty it. Refused before
  // any step changes the file; --older-than-sessions sparing recent rows
  // is another matter.
  const std::string unused = "retrieved_count = 0 AND created_session <= "
                             "(SELECT value FROM store_meta WHERE name = 'sessions') - " +
                             std::to_string(settings.older_than_sessions);
  if (settings.drop_unused && r.rows_before > 0 &&
      count(db, "SELECT count(*) FROM experiences WHERE retrieved_count > 0") == 0 &&
      count(db, "SELECT count(*) FROM experiences WHERE " + unused) == r.rows_before)
    throw InputError(copy_of.empty() ? target : copy_of, "--drop-unused",
                     "no entry has been retrieved yet (no learning plan has used this file): it would remove all " +
                         std::to_string(r.rows_before) + "; plan with the file first");
  if (settings.dedupe_eps >= 0)
    r.duplicates_removed =
        db.write([&] { return removed(deleteIds(db, nearDuplicates(db, store.schemaVersion(), settings.dedupe_eps))); });
  if (settings.drop_unused)
    r.unused_removed = db.write([&] {
      Statement del = db.prepare("DELETE FROM experiences WHERE " + unused);
      del.run();
      return removed(sqlite3_changes(db.handle()));
    });
  // Merged after the steps above, which judge this file's own rows: rows
  // from another file are new here (this session), never retrieved here,
  // and are checked against the rows kept for near duplicates instead.
  if (!settings.merge.empty()) {
    ImportSettings merge;
    merge.near_duplicate_eps = std::max(0.0, settings.dedupe_eps);  // never the same row twice
    merge.keep_sessions = false;
    r.merged = static_cast<std::int64_t>(importInto(store, settings.merge, merge).inserted);
  }
  if (!settings.drop_made_by.empty())
    r.made_by_removed = db.write([&] {
      // A pattern (GLOB: '*' any text, '?' one character, case-sensitive);
      // a build name without those matches itself only.
      Statement del = db.prepare("DELETE FROM experiences WHERE made_by GLOB ?1");
      std::int64_t n = 0;
      for (const std::string& build : settings.drop_made_by) {
        del.bind(1, std::string_view(build));
        del.run();
        const int changed = sqlite3_changes(db.handle());
        if (changed == 0) r.made_by_unmatched.push_back(build);
        n += changed;
        del.reset();
      }
      return removed(n);
    });
  if (!r.made_by_unmatched.empty()) {
    Statement builds = db.prepare(
        "SELECT made_by, count(*) AS n FROM experiences GROUP BY made_by ORDER BY n DESC, made_by LIMIT 5");
    while (builds.step()) r.builds_present.emplace_back(builds.textAt(0), builds.int64At(1));
  }
  if (settings.compact) r.blobs_rewritten = db.write([&] { return rewriteOlderBlobs(db); });
  // A curate that changed no rows says so too.
  db.write([&] { store.history().record(db, store.schemaVersion(), 0, 0, true); });
  if (settings.vacuum || settings.compact) db.exec("VACUUM");
  r.rows_after = count(db, "SELECT count(*) FROM experiences");
  // Damaged rows that curation kept: said, not passed on silently. The
  // near-duplicate pass has read every row already, and refuses the file
  // at the first damaged one, so only without it is there anything to count.
  if (settings.dedupe_eps < 0)
    scanRows(db, store.schemaVersion(), [](const Experience&) {}, [&](const CorruptRowError&) { ++r.damaged_rows; });
  store.close();  // checkpointed: the main file holds everything
  return r;
}

}  // namespace

void removeDatabaseFiles(const std::string& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  for (const char* suffix : kDatabaseCompanions) std::filesystem::remove(path + suffix, ignored);
}

namespace {

// The temporary a curate of process `pid` works in.
std::string curateTemporary(const std::string& out, const std::string& pid) { return out + ".tmp." + pid; }

// A curate killed part way leaves OUT.tmp.PID (and its -wal, -shm or
// -journal) beside OUT; the next curate to OUT removes those whose process
// is gone (kill(pid, 0): ESRCH). A live process's temporary is left alone:
// it may be curating right now. (A PID is only meaningful on this host; a
// curate run on another machine into a shared directory is not expected.)
void removeStaleTemporaries(const std::string& out) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(out).parent_path().empty() ? fs::path(".") : fs::path(out).parent_path();
  const std::string prefix = fs::path(out).filename().string() + ".tmp.";
  std::set<std::string> gone;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    std::string pid = name.substr(prefix.size());
    for (std::string_view suffix : kDatabaseCompanions)
      if (pid.ends_with(suffix)) pid.erase(pid.size() - suffix.size());
    // A PID, nothing else: export's OUT.tmp.PID.RANDOM is not ours.
    if (!isDigits(pid) || pid.size() > 9) continue;
    const pid_t p = static_cast<pid_t>(std::stol(pid));
    if (p > 0 && ::kill(p, 0) != 0 && errno == ESRCH) gone.insert(pid);
  }
  for (const std::string& pid : gone) removeDatabaseFiles(curateTemporary(out, pid));
}

}  // namespace

// In each eps-ball the entry kept is the one that succeeded most, then was
// retrieved most, then is oldest. A compacted blob gives back exactly the
// same paths; a damaged blob is left as it is. The file checked is the one
// curated in place or the source of a copy.
CurateReport curateDatabase(const std::string& path, const CurateSettings& settings) {
  if (isPostgresLocation(path)) return pgCurateDatabase(path, settings);
  // Every input before anything is written; curating in place writes, so a
  // 0-byte file becomes a database there, as it would with build.
  requireDatabaseFile(path, settings.output.empty());
  for (const std::string& in : settings.merge)
    if (!isPostgresLocation(in)) requireDatabaseFile(in);
  if (settings.output.empty()) return curateFile(path, settings);
  // The copy is curated under a temporary name and appears under its own
  // name only when complete: a crash or an error part way never leaves a
  // half-curated copy that looks like a database.
  // A link given as the output has its target created (as export's
  // does): the copy is made beside the target and renamed onto it, and a
  // dangling link is no existing file. Messages name the output as given.
  const std::string& given = settings.output;
  const std::string out = databaseFile(given);
  std::error_code ec;
  if (std::filesystem::exists(std::filesystem::symlink_status(out, ec)))
    throw InputError(given, "", "already exists; not overwriting it");
  removeStaleTemporaries(out);
  const std::string tmp = curateTemporary(out, std::to_string(::getpid()));
  removeDatabaseFiles(tmp);
  try {
    copyDatabase(path, tmp, /*full_check=*/true);  // VACUUM INTO copies a damaged index as it is
    CurateReport r = curateFile(tmp, settings, path);
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, out.c_str(), RENAME_NOREPLACE) != 0) {
      const int err = errno;
      throw InputError(given, "", err == EEXIST ? std::string("already exists; not overwriting it")
                                                : std::string("cannot create it: ") + std::strerror(err));
    }
    removeDatabaseFiles(tmp);  // an empty -wal or -shm left by the close
    syncDirectoryOf(out);
    r.curated_path = given;
    return r;
  } catch (const NoSpaceError&) {
    // Met writing the copy (VACUUM INTO, a statement reading the source,
    // names the source; a step on the copy, the temporary): the output
    // is what had no room.
    removeDatabaseFiles(tmp);
    throw InputError(given, "", std::string(kDiskFull) + "; no copy was made");
  } catch (...) {
    removeDatabaseFiles(tmp);
    throw;
  }
}

// Never cp: a live file's copy would tear. VACUUM INTO copies an index's
// pages as they are, damage included, hence full_check.
void copyDatabase(const std::string& from, const std::string& to, bool full_check) {
  if (std::filesystem::exists(to)) throw InputError(to, "", "already exists; not overwriting it");
  StoreOptions options = wholeFileStoreOptions(true);
  options.full_check = full_check;
  ExperienceStore source(from, options);  // identity and version checked
  // VACUUM INTO only reads the source, but query_only (how a read-only
  // store opens its own files) refuses it as a write.
  source.connection().exec("PRAGMA query_only = OFF");
  Statement vacuum = source.connection().prepare("VACUUM INTO ?1");
  vacuum.bind(1, std::string_view(literalName(to)));  // INTO takes a URI too
  vacuum.run();
}

}  // namespace earc::exp
