// earc-db inspect --db FILE [--entries K]: what a database holds: schema
// version, sizes, entries and hit rates per class, and a few entries in
// readable form. Never writes.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "earc/cli/subcommands.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/util/format.hpp"

namespace {

// Builds named on the "made by" line.
constexpr std::size_t kListedBuilds = 5;
// Bytes of a history line's detail, and of its operation and program, shown.
constexpr std::size_t kShownDetail = 150;
constexpr std::size_t kShownName = 40;

struct InspectOptions {
  std::string db;
  int entries = 3;
  int history = 10;
  bool json = false;
};

std::string bytes(std::int64_t n) {
  char buf[32];
  if (n < 1024) std::snprintf(buf, sizeof buf, "%lld B", static_cast<long long>(n));
  else if (n < (1 << 20)) std::snprintf(buf, sizeof buf, "%.1f KiB", n / 1024.0);
  else std::snprintf(buf, sizeof buf, "%.1f MiB", n / 1048576.0);
  return buf;
}

// A stored number in a bounded width: fixed with `decimals` as usual, %.6g
// from 1e9 on (an imported solve time of 1e308 is 309 digits fixed).
// Exports keep every digit; this is only for reading.
std::string number(double v, int decimals) {
  char buf[32];
  if (std::abs(v) < 1e9) std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  else std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string state(const earc::Path& p, std::size_t t) {
  std::string s = "(";
  for (int d = 0; d < p.dim(); ++d) s += (d ? ", " : "") + number(p.at(t)[d], 3);
  return s + ")";
}

void printEntry(const earc::exp::Experience& e, std::ostream& out) {
  out << "  #" << e.id << " " << earc::exp::kindName(e.cls.kind) << " x" << e.cls.robot_count
      << (e.cls.base_class.empty() ? "" : " ") << e.cls.base_class << ": cost " << number(e.cost, 0) << " steps, "
      << earc::exp::sourceName(e.source) << ", " << earc::utcTimeText(e.created_at) << ", solve " << number(e.solve_time_s, 3)
      << " s, used " << e.succeeded << "/" << e.retrieved << (e.made_by.empty() ? "" : ", by " + e.made_by) << "\n";
  for (std::size_t r = 0; r < e.paths.size(); ++r)
    out << "     robot " << r << ": " << state(e.paths[r], 0) << " -> " << state(e.paths[r], e.paths[r].size() - 1)
        << " in " << e.paths[r].size() - 1 << " steps\n";
}

// The last lines of the file's history, oldest first.
void printHistory(const earc::exp::HistoryTail& h, int schema_version, std::ostream& out) {
  if (schema_version < earc::exp::kHistorySchemaVersion) {
    out << "\nhistory: none kept before schema version " << earc::exp::kHistorySchemaVersion
        << " (the next read-write open migrates the file and starts it)\n";
    return;
  }
  if (h.lines.empty()) return;
  out << "\nhistory";
  if (h.total > static_cast<std::int64_t>(h.lines.size())) out << " (last " << h.lines.size() << " of " << h.total << ")";
  out << ":\n";
  for (const auto& l : h.lines) {
    // A file's text, bounded and printable like every inspect line.
    out << "  " << earc::utcTimeText(l.at) << "  " << earc::printableText(l.operation, kShownName) << "  by "
        << earc::printableText(l.program, kShownName);
    if (l.rows_added || l.rows_removed || l.operation == "build" || l.operation == "import" || l.operation == "curate")
      out << ", +" << l.rows_added << " -" << l.rows_removed << " rows";
    if (!l.detail.empty()) out << ": " << earc::printableText(l.detail, kShownDetail);
    out << "\n";
  }
}

void runInspect(const InspectOptions& opt, std::ostream& out) {
  const auto r = earc::exp::withInputErrors(opt.db, [&] { return earc::exp::inspectDatabase(opt.db, opt.entries, opt.history); });
  if (opt.json) {
    // Text from the file that is not UTF-8 is replaced, never an error.
    out << earc::exp::inspectJson(r).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return;
  }
  out << "database  " << r.path << "\n"
      << "schema    version " << r.schema_version << " (application_id 0x45415243 \"EARC\")\n"
      << "size      " << bytes(r.file_bytes) << " file, " << bytes(r.wal_bytes) << " WAL; blobs "
      << bytes(r.path_bytes) << " paths, " << bytes(r.key_bytes) << " keys\n";
  if (r.older_path_blobs > 0)
    out << "          " << r.older_path_blobs
        << " path blobs in an older format, without a checksum (earc-db curate --compact rewrites them)\n";
  out << "sessions  " << r.sessions << "\n"
      << "entries   " << r.entries << " in " << r.classes.size() << " classes\n";
  // Which builds made them: a few, most rows first.
  if (!r.builds.empty()) {
    out << "made by   ";
    for (std::size_t i = 0; i < r.builds.size() && i < kListedBuilds; ++i)
      out << (i ? ", " : "") << (r.builds[i].first.empty() ? "not known" : r.builds[i].first) << " ("
          << r.builds[i].second << ")";
    if (r.builds.size() > kListedBuilds) out << " and " << r.builds.size() - kListedBuilds << " more builds";
    out << "\n";
  }
  out << "\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-12s %5s %-28s %8s %5s %9s %8s %9s %9s %8s  %s\n", "kind", "robots", "base class",
                "entries", "dims", "mean cost", "solve s", "retrieved", "succeeded", "hit rate", "signature");
  out << line;
  for (const auto& c : r.classes) {
    char rate[16] = "-";
    if (const auto h = c.hitRate()) std::snprintf(rate, sizeof rate, "%.1f%%", 100.0 * *h);
    // The signature after the buffer: 64 robots' signatures would not fit in it.
    std::snprintf(line, sizeof line, "%-12s %5d %-28s %8lld %5lld %9s %8s %9lld %9lld %8s  ",
                  earc::exp::kindName(c.cls.kind), c.cls.robot_count, c.cls.base_class.empty() ? "-" : c.cls.base_class.c_str(),
                  static_cast<long long>(c.entries), static_cast<long long>(c.key_dim), number(c.mean_cost, 1).c_str(),
                  number(c.mean_solve_time_s, 3).c_str(), static_cast<long long>(c.retrieved),
                  static_cast<long long>(c.succeeded), rate);
    out << line << c.cls.signature << "\n";
  }
  if (!r.samples.empty()) {
    out << "\nfirst " << r.samples.size() << " entries:\n";
    for (const auto& e : r.samples) printEntry(e, out);
  }
  printHistory(r.history, r.schema_version, out);
}

void setupInspect(CLI::App& app) {
  auto opt = std::make_shared<InspectOptions>();
  CLI::App* sub = app.add_subcommand("inspect", "Show what an experience database holds (read-only)");
  sub->add_option("--db", opt->db, "Experience database file")->check(earc::cli::kFileName)->required();
  sub->add_option("--entries", opt->entries, "Entries to show in readable form")->check(earc::cli::wholeNumberIn(0, 1000));
  sub->add_option("--history", opt->history, "Lines of the file's history to show (the last ones)")
      ->check(earc::cli::wholeNumberIn(0, 100000));
  sub->add_flag("--json", opt->json, "Print the report as one JSON object (format earc.inspect.v1) for scripts");
  sub->callback([opt] { runInspect(*opt, std::cout); });
}

}  // namespace

static earc::cli::Registrar registered_inspect("earc-db", "inspect", setupInspect);
