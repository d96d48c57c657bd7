// Moving experiences between files: a portable JSON-lines export, and
// imports that treat every input as hostile (shared/design/reliability.md):
// SQLite inputs are opened read-only with quick_check, cell_size_check and
// no mmap; every row of every input is validated (types, dimensions, finite
// numbers, blob header and length, class consistency) before anything is
// written, and the rows are then stored in ONE transaction: an import
// applies whole or not at all.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "earc/experience/experience.hpp"
#include "earc/experience/store.hpp"
#include "earc/util/progress.hpp"

namespace earc::exp {

// First line of an export: {"format": kExportFormat, "schema_version": N,
// "rows": count}; then one JSON object per row, in id order.
inline constexpr const char* kExportFormat = "earc.experiences.v1";

// Writes every row of the database at db_path to out_path atomically, each
// double in its shortest exact form; returns the number of rows. Counts
// rows on `progress` when given.
std::size_t exportJsonl(const std::string& db_path, const std::string& out_path, Progress* progress = nullptr);

// One row as an export line's object, and back. experienceFromJson throws
// InputError(file, where, reason) for anything malformed or inconsistent.
nlohmann::json experienceToJson(const Experience& e);
Experience experienceFromJson(const nlohmann::json& row, const std::string& file, const std::string& where);

// Every row of an import source (.jsonl export or earc database, told apart
// by content), validated; throws InputError naming the file and bad rows.
// Counts rows on `progress` when given.
std::vector<Experience> readImportSource(const std::string& path, Progress* progress = nullptr);

struct ImportSettings {
  double near_duplicate_eps = -1.0;  // < 0: store every row
  bool mark_imported = false;        // set every row's source to 'import'
  // Keep each row's created_session when the target is empty (export then
  // import gives the same rows); into a file with rows, and always when
  // false (curate --merge), they are stamped with this session.
  bool keep_sessions = true;
  Progress* progress = nullptr;  // counts the rows read, when given
};

struct ImportReport {
  std::size_t read = 0;
  std::size_t inserted = 0;
  std::size_t duplicates = 0;      // near duplicates skipped (--dedupe)
  std::size_t already_stored = 0;  // the same experience was in the file
};

// Every row of every input, validated and ready to insert (ids cleared,
// sources set per the settings). Throws like readImportSource.
std::vector<Experience> readImportSources(const std::vector<std::string>& inputs, const ImportSettings& settings = {});
// Inserts rows read by readImportSources in one transaction.
ImportReport insertImported(ExperienceStore& store, const std::vector<Experience>& rows,
                            const ImportSettings& settings = {});
// Both: reads and validates every input, then inserts all rows at once.
ImportReport importInto(ExperienceStore& store, const std::vector<std::string>& inputs,
                        const ImportSettings& settings = {});

}  // namespace earc::exp
