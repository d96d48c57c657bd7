// earc-db export --db FILE -o OUT.jsonl: every row as portable JSON lines
// (a header line, then one object per row; doubles round-trip exactly).
#include <iostream>

#include "earc/cli/subcommands.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/io/json_io.hpp"

namespace {

struct ExportOptions {
  std::string db;
  std::string out;
  bool quiet = false;
};

void runExport(const ExportOptions& opt, std::ostream& out) {
  earc::requireDistinctFiles({{"--db", opt.db, true}, {"-o", opt.out}});
  earc::requireWritableOutput({"-o", opt.out});
  // The bar goes to stderr on a terminal only: never into `-o /dev/stdout`.
  earc::Progress progress("export", 0, !opt.quiet);
  const std::size_t rows =
      earc::exp::withInputErrors(opt.db, [&] { return earc::exp::exportJsonl(opt.db, opt.out, &progress); });
  progress.finish();
  out << "exported " << rows << " rows from " << opt.db << " to " << opt.out << "\n";
}

void setupExport(CLI::App& app) {
  auto opt = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand("export", "Write every experience as JSON lines (" + std::string(earc::exp::kExportFormat) + ")");
  sub->add_option("--db", opt->db, "Experience database file")->check(earc::cli::kFileName)->required();
  sub->add_option("-o,--output", opt->out, "Output file (.jsonl), written atomically")->check(earc::cli::kFileName)->required();
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] { runExport(*opt, earc::cli::unlessQuiet(opt->quiet, earc::summaryStream({opt->out}))); });
}

}  // namespace

static earc::cli::Registrar registered_export("earc-db", "export", setupExport);
