// Whole-file operations behind earc-db: inspect (what is in a database),
// verify (is every byte of it sound), curate (remove near-duplicates and
// unused entries, merge files), and copying a live database safely.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "earc/experience/experience.hpp"
#include "earc/experience/history.hpp"
#include "earc/experience/pg_connection.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/io/input_error.hpp"

namespace earc::exp {

struct ClassSummary {
  ExperienceClass cls;
  std::int64_t entries = 0;
  std::int64_t key_dim = 0;
  std::int64_t path_bytes = 0;
  std::int64_t retrieved = 0;
  std::int64_t succeeded = 0;
  double mean_cost = 0.0;        // steps summed over robots
  double mean_solve_time_s = 0.0;
  // Of the entries handed out, the share used; none when never retrieved.
  std::optional<double> hitRate() const {
    if (retrieved <= 0) return std::nullopt;
    return static_cast<double>(succeeded) / static_cast<double>(retrieved);
  }
};

struct InspectReport {
  std::string path;
  int schema_version = 0;
  std::int64_t file_bytes = 0;   // main file
  std::int64_t wal_bytes = 0;    // -wal file (0 when absent)
  std::int64_t sessions = 0;
  std::int64_t entries = 0;
  std::int64_t path_bytes = 0;   // sum of path blob sizes
  std::int64_t older_path_blobs = 0;  // path blobs in a format older than kPathBlobVersion
  std::int64_t key_bytes = 0;
  std::vector<ClassSummary> classes;
  // Rows per build that made them (Experience::made_by; '' not known),
  // most rows first. Schema versions before 4: every row, not known.
  std::vector<std::pair<std::string, std::int64_t>> builds;
  std::vector<Experience> samples;  // the first entries by id
  HistoryTail history;              // the last lines of the file's history
};

// Reads without writing (opens read-only; older schemas are fine).
InspectReport inspectDatabase(const std::string& path, int sample_entries, int history_lines = 10);

// The report for scripts (`earc-db inspect --json`, format
// "earc.inspect.v1"): every number of the text report, per class and per
// build, the history lines, and the sample entries as export rows.
nlohmann::json inspectJson(const InspectReport& r);

struct VerifyReport {
  int schema_version = 0;
  std::int64_t rows = 0;
  std::vector<std::string> problems;  // empty when the file is sound
  std::vector<std::string> notes;     // not problems (e.g. an older schema)
  bool ok() const { return problems.empty(); }
};

// Checks the file's integrity, identity and version and every row, and
// reports each problem; never writes. Throws InputError for a file that is
// not readable as an earc database at all.
VerifyReport verifyDatabase(const std::string& path);

struct CurateSettings {
  std::vector<std::string> merge;      // other databases or exports to add first
  double dedupe_eps = -1.0;            // >= 0: keep one entry per eps-ball in each class
  bool drop_unused = false;            // delete entries never retrieved ...
  int older_than_sessions = 0;         // ... created at least this many sessions ago
  // Delete entries made by these builds ("": not known); each may be a
  // GLOB pattern ('*' any text, '?' one character): "*.dirty".
  std::vector<std::string> drop_made_by;
  std::string output;                  // non-empty: curate a copy, leave the original untouched
  bool vacuum = false;                 // give freed pages back to the file system
  bool compact = false;                // rewrite older path blobs in the current format, then vacuum
};

struct CurateReport {
  std::int64_t rows_before = 0;
  std::int64_t merged = 0;
  std::int64_t duplicates_removed = 0;
  std::int64_t unused_removed = 0;
  std::int64_t made_by_removed = 0;
  // --drop-made-by names that matched no row (a typo, most likely), and
  // then the builds the file's rows do name, most rows first (up to 5).
  std::vector<std::string> made_by_unmatched;
  std::vector<std::pair<std::string, std::int64_t>> builds_present;
  std::int64_t rows_after = 0;
  std::int64_t blobs_rewritten = 0;  // compact: older path blobs now in the current format
  // Rows kept as they were whose key or path blob cannot be read (verify
  // names them; a near-duplicate pass refuses such a file instead).
  std::int64_t damaged_rows = 0;
  std::string curated_path;
};

// Merges, removes near-duplicates, drops unused entries and those of the
// builds named, then (compact) rewrites older path blobs: a transaction a
// step. A file failing integrity_check throws DamagedDatabaseError first.
CurateReport curateDatabase(const std::string& path, const CurateSettings& settings);

// A consistent copy of a live database (VACUUM INTO) that readers and
// writers may keep using; `to` must not exist. full_check: the source must
// pass integrity_check, not only quick_check.
void copyDatabase(const std::string& from, const std::string& to, bool full_check = false);

// Runs f(); a database file that cannot be used (missing, foreign, newer,
// damaged) becomes an InputError naming it: one line and exit status 2 in
// the tools. BusyError stays a runtime error (exit status 1).
template <class F>
auto withInputErrors(const std::string& path, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const BusyError&) {
    throw;
  } catch (const StoreError& e) {
    const std::string named = isPostgresLocation(path) ? maskedLocation(path) : path;  // never a password
    throw InputError(named, "", withoutFile(e.what(), named));
  }
}

// verify's check that the rows of a class share one key dimension: add()
// returns the problem of a row whose dimension differs from the first row
// of its class seen. Not thread-safe.
class KeyDimensionCheck {
 public:
  std::optional<std::string> add(const Experience& e);

 private:
  std::map<ExperienceClass, std::pair<std::size_t, std::int64_t>> first_;  // class -> (dim, row)
};

// One row as the near-duplicate pass reads it.
struct DedupeRow {
  std::int64_t id;
  ExperienceClass cls;
  std::vector<double> key;
};
// Of rows read best first, the ids to delete: each is kept unless a kept
// row of its class lies within eps (either engine's curate --dedupe).
std::vector<std::int64_t> nearDuplicateIds(const std::vector<DedupeRow>& rows, double eps);

// The PostgreSQL store's inspect, verify and curate (pg_maintenance.cpp;
// the functions above call them for a postgresql:// location). Curate
// refuses -o, --vacuum and --compact there (InputError).
InspectReport pgInspectDatabase(const std::string& location, int sample_entries, int history_lines);
VerifyReport pgVerifyDatabase(const std::string& location);
CurateReport pgCurateDatabase(const std::string& location, const CurateSettings& settings);

// Removes a database file and its -wal, -shm and -journal, if there.
void removeDatabaseFiles(const std::string& path);

}  // namespace earc::exp
