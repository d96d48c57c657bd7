// earc-db curate --db FILE [--merge OTHER...] [--dedupe EPS] [--drop-unused
// [--older-than-sessions N]] [--drop-made-by BUILD...] [-o OUT] [--vacuum]
// [--compact]: offline dataset curation.
// With -o the database is first copied (VACUUM INTO, never cp) and only the
// copy is changed.
#include <iostream>

#include "earc/cli/subcommands.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/io/json_io.hpp"

namespace {

struct CurateOptions {
  std::string db;
  earc::exp::CurateSettings settings;
  bool quiet = false;
};

void runCurate(const CurateOptions& opt, std::ostream& out) {
  std::vector<earc::NamedPath> files{{"--db", opt.db, true}};
  for (const auto& in : opt.settings.merge) files.push_back({"--merge", in, true});
  files.push_back({"-o", opt.settings.output, true});
  earc::requireDistinctFiles(files);
  earc::requireWritableOutput({"-o", opt.settings.output});
  const auto r = earc::exp::withInputErrors(opt.db, [&] { return earc::exp::curateDatabase(opt.db, opt.settings); });
  // A build name that matched nothing is most likely mistyped: said even
  // under -q, with the builds the rows do name.
  for (const std::string& build : r.made_by_unmatched) {
    std::cerr << "earc-db: warning: --drop-made-by \"" << build << "\": no row of " << r.curated_path
              << " was made by such a build; its rows name ";
    if (r.builds_present.empty()) std::cerr << "none (it has no rows)";
    for (std::size_t i = 0; i < r.builds_present.size(); ++i)
      std::cerr << (i ? ", " : "") << (r.builds_present[i].first.empty() ? "(not known)" : r.builds_present[i].first)
                << " (" << r.builds_present[i].second << " rows)";
    std::cerr << "\n";
  }
  out << "curated " << r.curated_path << ": " << r.rows_before << " rows before";
  if (!opt.settings.merge.empty()) out << ", " << r.merged << " merged";
  if (opt.settings.dedupe_eps >= 0) out << ", " << r.duplicates_removed << " near-duplicates removed";
  if (opt.settings.drop_unused) out << ", " << r.unused_removed << " unused removed";
  if (!opt.settings.drop_made_by.empty()) out << ", " << r.made_by_removed << " of the builds named removed";
  out << ", " << r.rows_after << " rows after";
  if (opt.settings.compact) out << ", " << r.blobs_rewritten << " path blobs rewritten in the current format";
  if (r.damaged_rows) out << " (" << r.damaged_rows << " damaged, kept as they were; earc-db verify names them)";
  out << "\n";
}

void setupCurate(CLI::App& app) {
  auto opt = std::make_shared<CurateOptions>();
  CLI::App* sub = app.add_subcommand(
      "curate", "Merge databases, remove near-duplicates, unused entries and entries of a given build");
  sub->add_option("--db", opt->db, "Experience database file")->check(earc::cli::kFileName)->required();
  sub->add_option("--merge", opt->settings.merge, "Databases or exports to merge in (validated like import)");
  sub->add_option("--dedupe", opt->settings.dedupe_eps,
                  "Keep one entry per key-distance ball of this radius in each class (the most successful)")
      ->check(earc::cli::kFiniteNonNegative);
  CLI::Option* drop = sub->add_flag("--drop-unused", opt->settings.drop_unused, "Delete entries never retrieved");
  sub->add_option("--older-than-sessions", opt->settings.older_than_sessions,
                  "With --drop-unused: only entries created at least this many planning sessions ago")
      ->check(earc::cli::kFiniteNonNegative)
      ->needs(drop);
  sub->add_option("--drop-made-by", opt->settings.drop_made_by,
                  "Delete entries made by this build, as earc-db inspect lists them, or by the builds a pattern "
                  "matches ('*' any text, '?' one character: '*.dirty'); \"\": entries whose build is not known; "
                  "repeatable");
  sub->add_option("-o,--output", opt->settings.output, "Curate a copy written here; the original stays untouched");
  sub->add_flag("--vacuum", opt->settings.vacuum, "Shrink the file afterwards");
  sub->add_flag("--compact", opt->settings.compact,
                "Rewrite path blobs of an older format in the current one (the same paths exactly, with a checksum; "
                "a fifth of version 1's size), then shrink the file");
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] { runCurate(*opt, earc::cli::unlessQuiet(opt->quiet, std::cout)); });
}

}  // namespace

static earc::cli::Registrar registered_curate("earc-db", "curate", setupCurate);
