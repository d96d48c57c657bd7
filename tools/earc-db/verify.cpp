// earc-db verify --db FILE: integrity_check, identity and schema version,
// and every row's blobs and consistency. Exit 0 sound, 1 anything wrong
// (each problem named, rows by id), 2 not readable as an earc database at
// all (missing, not SQLite, foreign, newer, damaged schema). Never writes.
#include <iostream>

#include "earc/cli/subcommands.hpp"
#include "earc/experience/maintenance.hpp"

namespace {

struct VerifyOptions {
  std::string db;
};

// Returns the exit status.
int runVerify(const VerifyOptions& opt, std::ostream& out) {
  const earc::exp::VerifyReport r = earc::exp::verifyDatabase(opt.db);
  for (const auto& note : r.notes) out << "note: " << note << "\n";
  for (const auto& problem : r.problems) out << "FAIL: " << problem << "\n";
  if (r.ok()) out << "OK: " << r.rows << " rows, schema version " << r.schema_version << "\n";
  else out << "FAILED: " << r.problems.size() << " problem(s) in " << opt.db << "\n";
  return r.ok() ? 0 : 1;
}

void setupVerify(CLI::App& app) {
  auto opt = std::make_shared<VerifyOptions>();
  CLI::App* sub = app.add_subcommand("verify", "Check a database's integrity and every row (exit 1 when anything is wrong)");
  sub->add_option("--db", opt->db, "Experience database file")->check(earc::cli::kFileName)->required();
  sub->callback([opt] { earc::cli::setExitCode(runVerify(*opt, std::cout)); });
}

}  // namespace

static earc::cli::Registrar registered_verify("earc-db", "verify", setupVerify);
