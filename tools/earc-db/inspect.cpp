// earc-db inspect --db FILE [--entries K]: what a database holds: schema
// version, sizes, entries and hit rates per class, and a few entries in
// readable form. Never writes.
#include <cstdio>
#include <ctime>
#include <iostream>

#include "earc/experience/maintenance.hpp"
#include "earc/util/subcommands.hpp"

namespace {

struct InspectOptions {
  std::string db;
  int entries = 3;
};

std::string bytes(std::int64_t n) {
  char buf[32];
  if (n < 1024) std::snprintf(buf, sizeof buf, "%lld B", static_cast<long long>(n));
  else if (n < (1 << 20)) std::snprintf(buf, sizeof buf, "%.1f KiB", n / 1024.0);
  else std::snprintf(buf, sizeof buf, "%.1f MiB", n / 1048576.0);
  return buf;
}

std::string isoTime(std::int64_t unix_seconds) {
  std::time_t t = static_cast<std::time_t>(unix_seconds);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string state(const earc::Path& p, std::size_t t) {
  std::string s = "(";
  for (int d = 0; d < p.dim(); ++d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%.3f", d ? ", " : "", p.at(t)[d]);
    s += buf;
  }
  return s + ")";
}

void printEntry(const earc::exp::Experience& e, std::ostream& out) {
  char head[256];
  std::snprintf(head, sizeof head, "  #%lld %s x%d%s%s: cost %.0f steps, %s, %s, solve %.3f s, used %lld/%lld\n",
                static_cast<long long>(e.id), earc::exp::kindName(e.cls.kind), e.cls.robot_count,
                e.cls.base_class.empty() ? "" : " ", e.cls.base_class.c_str(), e.cost, earc::exp::sourceName(e.source),
                isoTime(e.created_at).c_str(), e.solve_time_s, static_cast<long long>(e.succeeded),
                static_cast<long long>(e.retrieved));
  out << head;
  for (std::size_t r = 0; r < e.paths.size(); ++r)
    out << "     robot " << r << ": " << state(e.paths[r], 0) << " -> " << state(e.paths[r], e.paths[r].size() - 1)
        << " in " << e.paths[r].size() - 1 << " steps\n";
}

void runInspect(const InspectOptions& opt, std::ostream& out) {
  const auto r = earc::exp::withInputErrors(opt.db, [&] { return earc::exp::inspectDatabase(opt.db, opt.entries); });
  out << "database  " << r.path << "\n"
      << "schema    version " << r.schema_version << " (application_id 0x45415243 \"EARC\")\n"
      << "size      " << bytes(r.file_bytes) << " file, " << bytes(r.wal_bytes) << " WAL; blobs "
      << bytes(r.path_bytes) << " paths, " << bytes(r.key_bytes) << " keys\n"
      << "sessions  " << r.sessions << "\n"
      << "entries   " << r.entries << " in " << r.classes.size() << " classes\n\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-12s %5s %-28s %8s %5s %9s %8s %9s %9s %8s  %s\n", "kind", "robots", "base class",
                "entries", "dims", "mean cost", "solve s", "retrieved", "succeeded", "hit rate", "signature");
  out << line;
  for (const auto& c : r.classes) {
    char rate[16] = "-";
    if (c.retrieved > 0) std::snprintf(rate, sizeof rate, "%.1f%%", 100.0 * c.succeeded / c.retrieved);
    std::snprintf(line, sizeof line, "%-12s %5d %-28s %8lld %5lld %9.1f %8.3f %9lld %9lld %8s  %s\n",
                  earc::exp::kindName(c.cls.kind), c.cls.robot_count, c.cls.base_class.empty() ? "-" : c.cls.base_class.c_str(),
                  static_cast<long long>(c.entries), static_cast<long long>(c.key_dim), c.mean_cost, c.mean_solve_time_s,
                  static_cast<long long>(c.retrieved), static_cast<long long>(c.succeeded), rate, c.cls.signature.c_str());
    out << line;
  }
  if (!r.samples.empty()) {
    out << "\nfirst " << r.samples.size() << " entries:\n";
    for (const auto& e : r.samples) printEntry(e, out);
  }
}

void setupInspect(CLI::App& app) {
  auto opt = std::make_shared<InspectOptions>();
  CLI::App* sub = app.add_subcommand("inspect", "Show what an experience database holds (read-only)");
  sub->add_option("--db", opt->db, "Experience database file")->required();
  sub->add_option("--entries", opt->entries, "Entries to show in readable form")->check(CLI::Range(0, 1000));
  sub->callback([opt] { runInspect(*opt, std::cout); });
}

}  // namespace

static earc::cli::Registrar reg("earc-db", "inspect", setupInspect);
