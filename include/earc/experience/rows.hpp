// Reading and writing whole experience rows with SQL, shared by the store,
// verification, import and export. Every row read is checked: column types,
// kind and source names, blob headers and lengths, finite numbers, and the
// experience's own consistency (findProblem); a failure names the row.
#pragma once

#include <string>

#include "earc/experience/experience.hpp"
#include "earc/experience/sqlite.hpp"

namespace earc::exp {

// "SELECT <all columns> FROM experiences" for a file at `schema_version`;
// columns added by later migrations are read as their defaults. Append a
// WHERE / ORDER BY clause as needed.
std::string selectExperiencesSql(int schema_version);

// The current row of a statement prepared from selectExperiencesSql.
// Throws CorruptRowError(row id, reason).
Experience readExperience(const Statement& row);

// "INSERT INTO experiences (...) VALUES (...)" for the current schema;
// bindExperience binds every column but id.
std::string insertExperienceSql();
void bindExperience(Statement& insert, const Experience& e);

}  // namespace earc::exp
