// Databases and export files shared by the transfer and curate tests
// (test_store_transfer.cpp, test_store_curate.cpp).
#pragma once

#include <doctest/doctest.h>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <tuple>
#include "earc/experience/maintenance.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/rows.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/store.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/gen/generators.hpp"
#include "earc/scene/robot_signature.hpp"
#include "earc/util/version.hpp"
#include "support.hpp"

namespace earc::store_test {

using namespace earc;
using namespace earc::exp;


// A database with mobile rows of 2 and 3 robots and arm-pair rows, some
// with usage counts, written through the store.
inline void fill(const std::string& path, std::uint64_t seed, int per_class = 20) {
  RobotSpec disc;
  disc.radius = 0.3;
  const RobotTraits d = traitsOf(*makeRobotModel(disc, Resolution{}));
  gen::ArmSettings arms;
  arms.robots = 2;
  auto models = makeRobotModels(gen::generateArms(arms));
  std::vector<RobotTraits> arm_pair{traitsOf(*models[0]), traitsOf(*models[1])};
  std::mt19937_64 rng(seed);
  ExperienceStore store(path);
  std::vector<Experience> rows;
  for (int i = 0; i < per_class; ++i) {
    rows.push_back(straightLineExperience(std::vector<RobotTraits>{d, d}, sampleMobileQuery(2, rng), 5));
    rows.push_back(straightLineExperience(std::vector<RobotTraits>{d, d, d}, sampleMobileQuery(3, rng), 7,
                                          Source::Planner));
    rows.push_back(straightLineExperience(arm_pair, sampleArmQuery(*models[0], *models[1], rng), 4));
    rows.back().solve_time_s = 0.1 * (i + 1) / 3.0;  // not a short decimal
    rows.back().made_by = i % 2 ? "0.0.9+abc1234" : "";  // an older build's row; one from before schema 4
  }
  auto ids = store.insertAll(rows, -1);
  for (std::size_t i = 0; i < ids.size(); i += 4) store.recordUse(*ids[i], i % 8 == 0);
}

// Every row of a database except its id, in id order.
inline std::vector<nlohmann::json> contents(const std::string& path) {
  StoreOptions ro;
  ro.read_only = true;
  ExperienceStore store(path, ro);
  Statement s = store.connection().prepare(selectExperiencesSql(store.schemaVersion()) + " ORDER BY id");
  std::vector<nlohmann::json> out;
  while (s.step()) {
    nlohmann::json row = experienceToJson(readExperience(s));
    row.erase("id");
    out.push_back(std::move(row));
  }
  return out;
}

inline std::int64_t rowCount(const std::string& path) {
  Connection c(path, OpenMode::ReadOnly);
  Statement s = c.prepare("SELECT count(*) FROM experiences");
  s.step();
  return s.int64At(0);
}

inline std::string importError(const std::string& db, const std::vector<std::string>& inputs) {
  ExperienceStore store(db);
  try {
    importInto(store, inputs);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("import accepted bad input");
  return "";
}

inline std::vector<std::string> readLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

inline void writeLines(const std::string& path, const std::vector<std::string>& lines) {
  std::ofstream out(path);
  for (const auto& l : lines) out << l << "\n";
}

// The lines of `jsonl`, an export of a.db in `dir` filled with `seed`, 2
// rows per class: what the tests of a damaged export start from.
inline std::vector<std::string> exportedLines(const ScratchDirectory& dir, const std::string& jsonl, std::uint64_t seed) {
  const std::string a = dir.file("a.db");
  fill(a, seed, 2);
  exportJsonl(a, jsonl);
  return readLines(jsonl);
}


}  // namespace earc::store_test
