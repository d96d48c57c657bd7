-- Results migration 1: the trials and the databases they used.
-- trials: one row per planned trial. UNIQUE (suite, robots, method, trial,
-- seed, time_limit_s) is the key a resumed run skips on. Seeds are decimal
-- TEXT (64-bit unsigned). success is 1 only for a solution that
-- `earc-plan validate` accepted within the time limit; failure says why not
-- (NULL on success). planning_time_s is the planner's own figure
-- (stats.planning_time_s), NULL when the process died before reporting one.
-- databases: one row per database built for a run; robots = 0 for a
-- database that serves every robot count (E-ARC's).
-- (No comments inside the statements: SQLite keeps their text.)
CREATE TABLE trials (
  id INTEGER PRIMARY KEY,
  suite TEXT NOT NULL,
  robots INTEGER NOT NULL,
  method TEXT NOT NULL,
  trial INTEGER NOT NULL,
  seed TEXT NOT NULL,
  time_limit_s REAL NOT NULL,
  scenario_seed TEXT NOT NULL,
  planner_seed TEXT NOT NULL,
  success INTEGER NOT NULL CHECK (success IN (0, 1)),
  planning_time_s REAL,
  wall_time_s REAL NOT NULL,
  makespan INTEGER,
  sum_of_costs INTEGER,
  conflicts INTEGER,
  db_hits INTEGER,
  peak_memory_kb INTEGER,
  exit_status INTEGER,
  term_signal INTEGER,
  failure TEXT,
  finished_at TEXT NOT NULL,
  UNIQUE (suite, robots, method, trial, seed, time_limit_s)
);
CREATE TABLE databases (
  id INTEGER PRIMARY KEY,
  method TEXT NOT NULL,
  suite TEXT NOT NULL,
  robots INTEGER NOT NULL,
  path TEXT NOT NULL,
  construction_time_s REAL,
  entries INTEGER,
  size_bytes INTEGER,
  problems INTEGER,
  seed TEXT,
  recorded_at TEXT NOT NULL
);
