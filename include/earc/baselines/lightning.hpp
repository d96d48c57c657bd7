// The Lightning baseline (Berenson, Abbeel and Goldberg, ICRA 2012), as the
// E-ARC paper runs it: OMPL's ompl::tools::Lightning over the composite
// space of ALL robots. Two planners race in OMPL's threads: RRT-Connect from
// scratch and retrieve-and-repair from a database of whole-problem paths
// (RRT-Connect repairs the invalid stretches of the recalled path); the
// first solution wins, and a solution that did not come from the database
// (or was repaired far enough from it) is added to the database.
//
// The database file is OMPL's own (LightningDB::save: a path count, then
// one boost archive of PlannerData per path). Its states are composite
// states, so one file serves one robot count and kind of robot: a file of
// another state space is refused. Files are written atomically (temporary
// file + rename); concurrent writers to one file are not supported (the
// last one wins), so benchmarks open databases with learn = false.
//
// Determinism, honestly: every sampler draws from PlannerSettings::seed
// (each planner thread has a stream of its own) and OMPL's global seed is
// reset from it before each call, but the two planners run in parallel
// threads under a wall-clock limit, and the first to finish stops the
// other. Which planner wins, how far the loser got, and hence the path and
// what is added to the database depend on timing. Runs with one seed agree
// when one planner wins by a wide margin (e.g. an empty database); a
// database grown from many problems is reproducible only in distribution.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "earc/planning/planner.hpp"

namespace earc {

struct LightningSettings {
  std::string db_path;             // empty: start from an empty database, write none
  bool learn = true;               // add the solution found, when Lightning would ...
  bool save = true;                // ... and write the grown database back to db_path
  int recall_k = 10;               // paths retrieved per query (OMPL's default)
};

// A Lightning database in memory, for scenarios whose robots have the kinds
// and count of the prototype (their composite state spaces are alike).
class LightningDatabase {
 public:
  explicit LightningDatabase(const Scenario& prototype);
  ~LightningDatabase();
  LightningDatabase(const LightningDatabase&) = delete;
  LightningDatabase& operator=(const LightningDatabase&) = delete;

  // Adds the paths of a database file. Throws InputError naming the file
  // when it cannot be read or is not a Lightning database of this space.
  void load(const std::string& path);
  // Writes all paths atomically (temporary file, then rename).
  void save(const std::string& path) const;

  std::size_t entries() const;  // paths
  std::size_t states() const;   // composite states over all paths

  // Plans `scenario` (same kinds and count of robots as the prototype) with
  // Lightning over this database, adding the solution when settings say so
  // and Lightning's policy agrees. The solution is not validated here.
  PlanResult plan(const Scenario& scenario, const PlannerSettings& settings, const LightningSettings& lightning,
                  const PlanContext& context = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Lightning with the database file lightning.db_path (created when missing
// and learn and save are set). Not validated here: plan() (method
// lightning, settings.db.lightning_file) validates, and is what callers want.
PlanResult planLightning(const Scenario& scenario, const PlannerSettings& settings,
                         const LightningSettings& lightning, const PlanContext& context = {});

// plan()'s Lightning: the database file settings.db.lightning_file, if any.
PlanResult planLightning(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context = {});

}  // namespace earc
