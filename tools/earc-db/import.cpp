// earc-db import --db FILE IN...: adds the rows of exports (.jsonl) and of
// other earc databases. Inputs are treated as hostile and validated whole
// before anything is written; the import applies in one transaction, so a
// bad row anywhere means nothing is imported (exit 2, the row named).
#include <iostream>
#include <sstream>

#include "earc/cli/subcommands.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/schema.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/io/json_io.hpp"

namespace {

struct ImportOptions {
  std::string db;
  std::vector<std::string> inputs;
  double dedupe = -1.0;
  bool mark_imported = false;
  bool quiet = false;
};

void runImport(const ImportOptions& opt, std::ostream& out) {
  // Importing a file into itself would double every row.
  std::vector<earc::NamedPath> files{{"--db", opt.db, true}};
  for (const auto& in : opt.inputs) files.push_back({"input", in, true});
  earc::requireDistinctFiles(files);
  earc::exp::ImportSettings settings;
  settings.near_duplicate_eps = opt.dedupe;
  settings.mark_imported = opt.mark_imported;
  earc::Progress progress("import", 0, !opt.quiet);
  settings.progress = &progress;
  // Every input is read and checked before the target is opened, which
  // creates it: a refused import leaves no empty database behind.
  const std::vector<earc::exp::Experience> rows = earc::exp::readImportSources(opt.inputs, settings);
  progress.finish();
  const auto report = earc::exp::withInputErrors(opt.db, [&] {
    earc::exp::StoreOptions options;
    options.new_session = false;
    options.full_check = true;  // never import into a damaged file (indexes too)
    earc::exp::ExperienceStore store(opt.db, options);
    std::ostringstream from;
    from << "from";
    for (const auto& in : opt.inputs) from << " " << in;
    if (opt.dedupe >= 0) from << ", --dedupe " << opt.dedupe;
    if (opt.mark_imported) from << ", --mark-imported";
    store.describeHistory("import", from.str());
    return earc::exp::insertImported(store, rows, settings);
  });
  out << "imported " << report.inserted << " of " << report.read << " rows into " << opt.db;
  if (report.already_stored) out << " (" << report.already_stored << " already in it)";
  if (report.duplicates) out << " (" << report.duplicates << " near-duplicates skipped)";
  out << "\n";
}

void setupImport(CLI::App& app) {
  auto opt = std::make_shared<ImportOptions>();
  CLI::App* sub = app.add_subcommand("import", "Add experiences from exports (.jsonl) or other earc databases, all or nothing");
  sub->add_option("--db", opt->db, "Experience database file (created when missing)")->check(earc::cli::kFileName)->required();
  sub->add_option("inputs", opt->inputs, "Export files or earc databases")->required();
  sub->add_option("--dedupe", opt->dedupe, "Skip rows within this key distance of a stored one (default: keep all)")
      ->check(earc::cli::kFinite);
  sub->add_flag("--mark-imported", opt->mark_imported, "Set every imported row's source to 'import'");
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] { runImport(*opt, earc::cli::unlessQuiet(opt->quiet, std::cout)); });
}

}  // namespace

static earc::cli::Registrar registered_import("earc-db", "import", setupImport);
