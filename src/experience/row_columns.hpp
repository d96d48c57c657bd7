// Decoding one experience row from its columns, the same for both
// engines' readers (rows.cpp, pg_rows.cpp). Not a public header.
#pragma once

#include <string>

#include "earc/experience/experience.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/sqlite.hpp"

namespace earc::exp {

// The columns of a whole row, in the order both engines select them.
enum RowColumn {
  kColId, kColKind, kColRobotCount, kColSignature, kColBaseClass, kColKey, kColPaths, kColCost, kColSource,
  kColCreatedAt, kColSolveTime, kColRetrieved, kColSucceeded, kColCreatedSession, kColMadeBy
};

// The row `r` holds (Row: int64(c), real(c), text(c), bytes(c) of column
// c), checked as findProblem checks. Throws CorruptRowError.
template <class Row>
Experience decodeRowColumns(const Row& r) {
  Experience e;
  e.id = r.int64(kColId);
  const std::string kind_text = r.text(kColKind);
  auto kind = kindFromName(kind_text);
  if (!kind) throw CorruptRowError(e.id, "unknown kind \"" + kind_text + "\"");
  const std::string source_text = r.text(kColSource);
  auto source = sourceFromName(source_text);
  if (!source) throw CorruptRowError(e.id, "unknown source \"" + source_text + "\"");
  const std::int64_t count = r.int64(kColRobotCount);
  if (count < 1 || count > kMaxBlobRobots)
    throw CorruptRowError(e.id, "robot_count " + std::to_string(count) + " out of range");
  e.cls = {*kind, static_cast<int>(count), r.text(kColSignature), r.text(kColBaseClass)};
  e.key = decodeKey(r.bytes(kColKey), e.id);
  e.paths = decodePaths(r.bytes(kColPaths), e.id);
  e.cost = r.real(kColCost);
  e.source = *source;
  e.created_at = r.int64(kColCreatedAt);
  e.solve_time_s = r.real(kColSolveTime);
  e.retrieved = r.int64(kColRetrieved);
  e.succeeded = r.int64(kColSucceeded);
  e.created_session = r.int64(kColCreatedSession);
  e.made_by = r.text(kColMadeBy);
  if (auto problem = findProblem(e)) throw CorruptRowError(e.id, *problem);
  return e;
}

}  // namespace earc::exp
