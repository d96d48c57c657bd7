#include "earc/experience/transfer.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "earc/experience/pg_schema.hpp"
#include "earc/experience/rows.hpp"
#include "earc/experience/schema.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"

namespace earc::exp {

namespace {

using nlohmann::json;

// Bad rows listed in one import error before "... and N more".
constexpr std::size_t kListedBadRows = 10;

json pathsToJson(const std::vector<Path>& paths) {
  json out = json::array();
  for (const Path& p : paths) {
    json states = json::array();
    for (std::size_t t = 0; t < p.size(); ++t) states.push_back(std::vector<double>(p.state(t).begin(), p.state(t).end()));
    out.push_back(std::move(states));
  }
  return out;
}

// Collects bad rows so one error (one line) names the first fully and the
// next few by position.
struct BadRows {
  std::string file;
  std::string first_where, first_reason;
  std::vector<std::string> others;
  std::size_t count = 0;
  void add(const std::string& where, const std::string& reason) {
    if (count == 0) {
      first_where = where;
      first_reason = reason;
    } else if (others.size() < kListedBadRows) {
      others.push_back(where);
    }
    ++count;
  }
  void throwIfAny() const {
    if (count == 0) return;
    std::string reason = first_reason;
    if (count > 1) {
      reason += "; " + std::to_string(count - 1) + " more bad row" + (count == 2 ? "" : "s") + " (";
      for (std::size_t i = 0; i < others.size(); ++i) reason += (i ? ", " : "") + others[i];
      reason += count - 1 > others.size() ? ", ...)" : ")";
    }
    throw InputError(file, first_where, reason + "; nothing was imported");
  }
};

const json& field(const json& row, const char* name, const std::string& file, const std::string& where) {
  auto it = row.find(name);
  if (it == row.end()) throw InputError(file, where, std::string("missing field \"") + name + "\"");
  return *it;
}

std::int64_t integerField(const json& row, const char* name, const std::string& file, const std::string& where) {
  const json& v = field(row, name, file, where);
  if (!v.is_number_integer()) throw InputError(file, where + "." + name, "not an integer");
  return v.get<std::int64_t>();
}

double numberField(const json& row, const char* name, const std::string& file, const std::string& where) {
  const json& v = field(row, name, file, where);
  if (!v.is_number() || !std::isfinite(v.get<double>())) throw InputError(file, where + "." + name, "not a finite number");
  return v.get<double>();
}

std::string textField(const json& row, const char* name, const std::string& file, const std::string& where) {
  const json& v = field(row, name, file, where);
  if (!v.is_string()) throw InputError(file, where + "." + name, "not a string");
  return v.get<std::string>();
}

std::vector<double> numbers(const json& v, const std::string& file, const std::string& where) {
  if (!v.is_array()) throw InputError(file, where, "not an array of numbers");
  std::vector<double> out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      throw InputError(file, where + "[" + std::to_string(i) + "]", "not a finite number");
    out.push_back(v[i].get<double>());
  }
  return out;
}

std::vector<Experience> readJsonl(const std::string& path, Progress* progress) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open for reading");
  std::string line;
  if (!std::getline(in, line)) throw InputError(path, "line 1", "empty file: expected an earc experience export");
  json header;
  try {
    header = parseJsonText(line, path);
  } catch (const InputError&) {
    throw InputError(path, "line 1",
                     std::string("not an earc experience database or export (neither SQLite nor JSON lines of \"") +
                         kExportFormat + "\")");
  }
  if (!header.is_object() || header.value("format", json()) != kExportFormat)
    throw InputError(path, "line 1", std::string("not an earc experience export (expected format \"") + kExportFormat + "\")");
  // Like a database file: an export of a newer schema may hold what this
  // program would not understand.
  if (header.contains("schema_version")) {
    const json& v = header["schema_version"];
    if (!v.is_number_integer() || v.get<std::int64_t>() < 1)
      throw InputError(path, "line 1", "schema_version must be a positive integer, not " + v.dump());
    if (v.get<std::int64_t>() > currentSchemaVersion())
      throw InputError(path, "line 1",
                       "exported from schema version " + v.dump() + ", newer than this program's version " +
                           std::to_string(currentSchemaVersion()) + "; use a newer earc");
  }
  if (header.contains("rows") && !(header["rows"].is_number_integer() && header["rows"].get<std::int64_t>() >= 0))
    throw InputError(path, "line 1", "rows must be a count of rows, not " + header["rows"].dump());
  if (progress && header.contains("rows")) progress->addToTotal(header["rows"].get<std::size_t>());
  std::vector<Experience> rows;
  BadRows bad{path, {}, {}, {}, 0};
  std::size_t number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    if (progress) progress->tick();
    const std::string where = "line " + std::to_string(number);
    try {
      rows.push_back(experienceFromJson(parseJsonText(line, path + ": " + where), path, where));
    } catch (const InputError& e) {
      // Row errors name the line already; parse errors name the column
      // (of the line, which the parser saw as line 1) and the JSON path.
      std::string at = e.where();
      if (at.rfind("line 1, ", 0) == 0) at.erase(0, 8);
      bad.add(e.file() == path ? e.where() : where + (at.empty() ? "" : " " + at), e.reason());
    }
  }
  bad.throwIfAny();
  if (header.contains("rows") && header["rows"].get<std::int64_t>() != static_cast<std::int64_t>(rows.size()))
    throw InputError(path, "line 1", "header announces " + header["rows"].dump() + " rows, the file holds " +
                                         std::to_string(rows.size()) + " (truncated?)");
  return rows;
}

std::vector<Experience> readSqlite(const std::string& path, Progress* progress) {
  try {
    Connection db(path, OpenMode::Hostile);
    // Foreign, newer or without its tables: refused before reading rows.
    const int version = checkIdentity(db);
    if (version == 0) throw notYetADatabase(path);
    // quick_check before reading rows: a damaged file is refused as a whole.
    db.requireQuickCheck();
    std::vector<Experience> rows;
    BadRows bad{path, {}, {}, {}, 0};
    // One read transaction: the count and the rows are one snapshot.
    db.exec("BEGIN");
    if (progress) {
      Statement count = db.prepare("SELECT count(*) FROM experiences");
      count.step();
      progress->addToTotal(static_cast<std::size_t>(count.int64At(0)));
    }
    Statement select = db.prepare(selectExperiencesSql(version) + " ORDER BY id");
    while (select.step()) {
      if (progress) progress->tick();
      try {
        rows.push_back(readExperience(select));
      } catch (const CorruptRowError& e) {
        bad.add("row " + std::to_string(e.row()), e.reason());
      }
    }
    select.reset();
    db.exec("COMMIT");
    bad.throwIfAny();
    return rows;
  } catch (const StoreError& e) {
    throw InputError(path, "", withoutFile(e.what(), path));
  }
}

}  // namespace

json experienceToJson(const Experience& e) {
  return json{{"id", e.id},
              {"kind", kindName(e.cls.kind)},
              {"robot_count", e.cls.robot_count},
              {"signature", e.cls.signature},
              {"base_class", e.cls.base_class},
              {"key", e.key},
              {"paths", pathsToJson(e.paths)},
              {"cost", e.cost},
              {"source", sourceName(e.source)},
              {"created_at", e.created_at},
              {"solve_time_s", e.solve_time_s},
              {"retrieved", e.retrieved},
              {"succeeded", e.succeeded},
              {"created_session", e.created_session},
              {"made_by", e.made_by}};
}

Experience experienceFromJson(const json& row, const std::string& file, const std::string& where) {
  if (!row.is_object()) throw InputError(file, where, "not a JSON object");
  Experience e;
  e.id = integerField(row, "id", file, where);
  const std::string w = where + " (id " + std::to_string(e.id) + ")";
  auto kind = kindFromName(textField(row, "kind", file, w));
  if (!kind) throw InputError(file, w + ".kind", "not \"mobile\" or \"manipulator\"");
  const std::int64_t count = integerField(row, "robot_count", file, w);
  if (count < 1 || count > 64) throw InputError(file, w + ".robot_count", "outside 1..64");
  e.cls = {*kind, static_cast<int>(count), textField(row, "signature", file, w), textField(row, "base_class", file, w)};
  e.key = numbers(field(row, "key", file, w), file, w + ".key");
  const json& paths = field(row, "paths", file, w);
  if (!paths.is_array()) throw InputError(file, w + ".paths", "not an array");
  for (std::size_t r = 0; r < paths.size(); ++r) {
    const std::string pw = w + ".paths[" + std::to_string(r) + "]";
    if (!paths[r].is_array() || paths[r].empty()) throw InputError(file, pw, "not a non-empty array of states");
    const std::size_t dim = paths[r][0].is_array() ? paths[r][0].size() : 0;
    if (dim < 1 || dim > 64) throw InputError(file, pw + "[0]", "a state must hold 1..64 numbers");
    Path p(static_cast<int>(dim));
    for (std::size_t t = 0; t < paths[r].size(); ++t) {
      std::vector<double> q = numbers(paths[r][t], file, pw + "[" + std::to_string(t) + "]");
      if (q.size() != dim) throw InputError(file, pw + "[" + std::to_string(t) + "]", "dimension differs from state 0");
      p.push(q);
    }
    e.paths.push_back(std::move(p));
  }
  // findProblem checks it too; here the message can name the field.
  if (auto problem = signatureProblem(e.cls, e.paths)) throw InputError(file, w + ".signature", *problem);
  e.cost = numberField(row, "cost", file, w);
  auto source = sourceFromName(textField(row, "source", file, w));
  if (!source) throw InputError(file, w + ".source", "not \"build\", \"planner\" or \"import\"");
  e.source = *source;
  e.created_at = integerField(row, "created_at", file, w);
  e.solve_time_s = numberField(row, "solve_time_s", file, w);
  e.retrieved = integerField(row, "retrieved", file, w);
  e.succeeded = integerField(row, "succeeded", file, w);
  e.created_session = integerField(row, "created_session", file, w);
  // Exports of schema versions before 4 have no made_by: not known.
  if (row.contains("made_by")) e.made_by = textField(row, "made_by", file, w);
  if (auto problem = findProblem(e)) throw InputError(file, w, *problem);
  return e;
}

std::size_t exportJsonl(const std::string& db_path, const std::string& out_path, Progress* progress) {
  ExperienceStore store(db_path, wholeFileStoreOptions(true));
  // Streamed to the file a megabyte at a time: 50,000 rows are about
  // 700 MB of text, too much to build in memory first.
  AtomicFile file(out_path);
  std::string chunk;
  constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
  if (store.isPostgres()) {
    // Its rows have every column of kExperienceRowsSchemaVersion.
    std::size_t written = 0;
    pgForEachExperience(
        store.pgConnection(), "ORDER BY id",
        [&](std::int64_t rows) {
          if (progress) progress->addToTotal(static_cast<std::size_t>(rows));
          chunk += json{{"format", kExportFormat}, {"schema_version", kExperienceRowsSchemaVersion}, {"rows", rows}}
                       .dump() + "\n";
        },
        [&](Experience&& e) {
          chunk += experienceToJson(e).dump() + "\n";
          ++written;
          if (progress) progress->tick();
          if (chunk.size() >= kChunkBytes) {
            file.write(chunk);
            chunk.clear();
          }
        });
    file.write(chunk);
    file.commit();
    return written;
  }
  Connection& db = store.connection();
  // One read transaction: the header's count and the rows are one snapshot.
  db.exec("BEGIN");
  Statement count = db.prepare("SELECT count(*) FROM experiences");
  count.step();
  const std::int64_t rows = count.int64At(0);
  count.reset();
  if (progress) progress->addToTotal(static_cast<std::size_t>(rows));
  chunk += json{{"format", kExportFormat}, {"schema_version", std::min(store.schemaVersion(), kExperienceRowsSchemaVersion)},
                {"rows", rows}}.dump() + "\n";
  Statement select = db.prepare(selectExperiencesSql(store.schemaVersion()) + " ORDER BY id");
  std::size_t written = 0;
  while (select.step()) {
    chunk += experienceToJson(readExperience(select)).dump() + "\n";
    ++written;
    if (progress) progress->tick();
    if (chunk.size() >= kChunkBytes) {
      file.write(chunk);
      chunk.clear();
    }
  }
  db.exec("COMMIT");
  file.write(chunk);
  file.commit();
  return written;
}

std::vector<Experience> readImportSource(const std::string& path, Progress* progress) {
  if (isPostgresLocation(path)) {
    // A store earc wrote: its rows were checked on the way in, and are
    // checked again as they are read.
    ExperienceStore store(path, wholeFileStoreOptions(true));
    std::vector<Experience> rows;
    pgForEachExperience(
        store.pgConnection(), "ORDER BY id",
        [&](std::int64_t n) {
          rows.reserve(static_cast<std::size_t>(n));
          if (progress) progress->addToTotal(static_cast<std::size_t>(n));
        },
        [&](Experience&& e) {
          rows.push_back(std::move(e));
          if (progress) progress->tick();
        });
    return rows;
  }
  requireDatabaseFile(path);
  return startsLikeSqlite(path) ? readSqlite(path, progress) : readJsonl(path, progress);
}

std::vector<Experience> readImportSources(const std::vector<std::string>& inputs, const ImportSettings& settings) {
  std::vector<Experience> all;
  for (const std::string& input : inputs) {
    std::vector<Experience> rows = readImportSource(input, settings.progress);
    all.insert(all.end(), std::make_move_iterator(rows.begin()), std::make_move_iterator(rows.end()));
  }
  for (Experience& e : all) {
    e.id = 0;
    if (settings.mark_imported) e.source = Source::Import;
  }
  return all;
}

namespace {

// True when the store already holds `e`'s experience: a row of its class
// with the same key and the same paths (counters and provenance aside).
bool alreadyStored(ExperienceStore& store, const Experience& e) {
  // Rows with equal keys are at distance 0; a few may share a key.
  for (const Neighbor& n : store.nearestIds(e.cls, e.key, 8)) {
    if (n.distance > 0.0) break;
    const std::optional<Experience> stored = store.get(n.id);
    if (stored && stored->key == e.key && stored->paths == e.paths) return true;
  }
  return false;
}

}  // namespace

ImportReport insertImported(ExperienceStore& store, const std::vector<Experience>& rows,
                            const ImportSettings& settings) {
  ImportReport report;
  report.read = rows.size();
  // Sessions count one file's planning sessions: kept only when the rows
  // restore an empty file (export then import gives the same rows); into
  // a file with rows of its own they are new there, as curate --merge's.
  const bool restoring = store.size() == 0;
  const auto stamp = settings.keep_sessions && restoring ? ExperienceStore::SessionStamp::AsGiven
                                                         : ExperienceStore::SessionStamp::ThisSession;
  // An experience the file already holds is not stored twice: importing
  // the same export again changes nothing. Rows repeated within the
  // inputs are kept, so that an export restores its file exactly.
  std::vector<Experience> fresh;
  if (!restoring) {
    fresh.reserve(rows.size());
    for (const Experience& e : rows) {
      if (alreadyStored(store, e))
        report.already_stored++;
      else
        fresh.push_back(e);
    }
  }
  for (const auto& id : store.insertAll(restoring ? rows : fresh, settings.near_duplicate_eps, stamp))
    (id ? report.inserted : report.duplicates)++;
  return report;
}

ImportReport importInto(ExperienceStore& store, const std::vector<std::string>& inputs, const ImportSettings& settings) {
  return insertImported(store, readImportSources(inputs, settings), settings);
}

}  // namespace earc::exp
