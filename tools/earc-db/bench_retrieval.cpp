// earc-db bench-retrieval [--entries N] [--queries Q] [--k K] [--seed S]
// [--row-cache-mb M] [--db URI] [--no-warm-rows]: k-closest retrieval time per class on
// synthetic entries (straight-line paths between the builder's kind of
// queries) in a temporary database. For each class: median and p90 of
// ExperienceStore::nearest (k-d tree search, reading and decoding k rows,
// or taking them from the row cache) over uniformly random queries, the
// share of rows the row cache (or PostgreSQL's background copy) had, the median of the same queries asked
// again, the k-d tree search alone, and a linear scan of all keys. A
// PostgreSQL store's background copy (StoreOptions::warm_rows) is awaited
// first, and the time it took printed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>
#include <iostream>
#include <random>

#include "earc/cli/subcommands.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/store.hpp"
#include "earc/gen/generators.hpp"
#include "earc/util/random.hpp"

namespace {

struct BenchRetrievalOptions {
  int entries = 100000;
  int queries = 1000;
  int k = 10;
  std::uint64_t seed = 1;
  std::string db;  // an empty store to fill instead of a temporary file (postgresql://...)
  int row_cache_mb = static_cast<int>(earc::exp::kDefaultRowCacheBytes >> 20);
  bool no_warm_rows = false;
};

// Rows per insert transaction while filling the database.
constexpr std::size_t kFillBatch = 5000;
// States per synthetic path: about a conflict window's length.
constexpr int kSyntheticSteps = 20;

using Clock = std::chrono::steady_clock;

struct BenchClass {
  std::string name;
  std::vector<std::shared_ptr<const earc::RobotModel>> models;
  earc::exp::Query sample(std::mt19937_64& rng) const {
    if (models.front()->isMobile()) return earc::exp::sampleMobileQuery(static_cast<int>(models.size()), rng);
    return earc::exp::sampleArmQuery(*models[0], *models[1], rng);
  }
  std::vector<earc::exp::RobotTraits> traits() const {
    std::vector<earc::exp::RobotTraits> t;
    for (const auto& m : models) t.push_back(earc::exp::traitsOf(*m));
    return t;
  }
};

std::vector<BenchClass> benchClasses() {
  std::vector<BenchClass> out;
  earc::RobotSpec disc;
  disc.radius = 0.3;
  for (int n : {2, 3, 4}) {
    BenchClass c{"mobile x" + std::to_string(n), {}};
    for (int i = 0; i < n; ++i) c.models.push_back(earc::makeRobotModel(disc, earc::Resolution{}));
    out.push_back(std::move(c));
  }
  // The facing pair of the generated arm scenarios (paper, Scenario II).
  earc::gen::ArmSettings arms;
  arms.robots = 2;
  const earc::Scenario s = earc::gen::generateArms(arms);
  auto models = earc::makeRobotModels(s);
  out.push_back({"manipulator x2 facing", {models[0], models[1]}});
  return out;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::size_t i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i), v.end());
  return v[i];
}

template <class F>
double microseconds(F&& f) {
  auto t0 = Clock::now();
  f();
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

double threadCpuMicroseconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

// The machine's load when the benchmark ran: on a shared machine wall
// times grow with it, CPU times much less.
std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  return in >> one ? one : "?";
}

void runBenchRetrieval(const BenchRetrievalOptions& opt, std::ostream& out) {
  earc::exp::ScratchDirectory dir("bench-retrieval");
  const std::string path = opt.db.empty() ? dir.file("bench.db") : opt.db;
  const auto classes = benchClasses();
  std::vector<earc::exp::ExperienceClass> ids;
  const auto t_fill = Clock::now();
  {
    earc::exp::ExperienceStore store(path);
    for (std::size_t c = 0; c < classes.size(); ++c) {
      std::mt19937_64 rng(earc::splitSeed(opt.seed, c));
      const auto traits = classes[c].traits();
      std::vector<earc::exp::Experience> batch;
      for (int i = 0; i < opt.entries; ++i) {
        batch.push_back(earc::exp::straightLineExperience(traits, classes[c].sample(rng), kSyntheticSteps));
        if (batch.size() == kFillBatch || i + 1 == opt.entries) {
          store.insertAll(batch, -1);
          batch.clear();
        }
      }
      ids.push_back(earc::exp::straightLineExperience(traits, classes[c].sample(rng), 2).cls);
    }
  }
  const double fill_s = std::chrono::duration<double>(Clock::now() - t_fill).count();
  earc::exp::StoreOptions measured;
  measured.row_cache_bytes = static_cast<std::size_t>(opt.row_cache_mb) << 20;
  measured.warm_rows = !opt.no_warm_rows;
  const auto t_open = Clock::now();
  earc::exp::ExperienceStore store(path, measured);  // a fresh open: index built from the file
  const double open_s = std::chrono::duration<double>(Clock::now() - t_open).count();
  const std::size_t warm = store.awaitWarmRows();
  const double warm_s = std::chrono::duration<double>(Clock::now() - t_open).count();
  char line[256];
  if (store.isPostgres()) {
    std::snprintf(line, sizeof line, "the measured open took %.2f s; its background copy held %zu rows %.2f s after it began\n",
                  open_s, warm, warm_s);
    out << line;
  }
  earc::exp::StoreOptions unwarmed;  // opens that retrieve nothing
  unwarmed.warm_rows = false;
  const double load_s = microseconds([&] { earc::exp::ExperienceStore again(path, unwarmed); }) * 1e-6;
  std::snprintf(line, sizeof line, "filled %d entries x %zu classes in %.1f s; a fresh open loads the index in %.2f s; k = %d, %d queries\n\n",
                opt.entries, classes.size(), fill_s, load_s, opt.k, opt.queries);
  out << line;
  std::snprintf(line, sizeof line, "%-22s %8s %5s %10s %9s %9s %6s %9s %10s %9s\n", "class", "entries", "dims",
                "median us", "p90 us", "cpu us", "hit %", "again us", "search us", "brute us");
  out << line;
  for (std::size_t c = 0; c < classes.size(); ++c) {
    const auto* index = store.classIndex(ids[c]);
    if (!index) continue;
    std::mt19937_64 rng(earc::splitSeed(opt.seed + 1, c));
    const auto traits = classes[c].traits();
    std::vector<std::vector<double>> keys;
    for (int q = 0; q < opt.queries; ++q) {
      const auto query = classes[c].sample(rng);
      keys.push_back(earc::exp::canonicalize(traits, query.starts, query.goals).key);
    }
    // One loop per method: the linear scans would otherwise flush the CPU
    // caches between two store queries and charge that to the store.
    const auto k = static_cast<std::size_t>(opt.k);
    std::vector<double> full, cpu, again, search, brute;
    std::size_t returned = 0;
    const auto before = store.retrievalStats();
    for (const auto& key : keys) {
      const double cpu0 = threadCpuMicroseconds();
      full.push_back(microseconds([&] { returned += store.nearest(ids[c], key, k).size(); }));
      cpu.push_back(threadCpuMicroseconds() - cpu0);
    }
    const auto after = store.retrievalStats();
    const double looked = static_cast<double>(after.cache_hits + after.cache_misses - before.cache_hits - before.cache_misses);
    const double in_memory = static_cast<double>(after.cache_hits - before.cache_hits + after.warm_hits - before.warm_hits);
    const double hit_pct = looked > 0 ? 100.0 * in_memory / looked : 0.0;
    for (const auto& key : keys) again.push_back(microseconds([&] { store.nearest(ids[c], key, k); }));
    for (const auto& key : keys) search.push_back(microseconds([&] { returned += index->nearest(key, k).size(); }));
    for (const auto& key : keys) brute.push_back(microseconds([&] { returned += index->bruteForce(key, k).size(); }));
    std::snprintf(line, sizeof line, "%-22s %8zu %5zu %10.1f %9.1f %9.1f %6.1f %9.1f %10.1f %9.1f\n",
                  classes[c].name.c_str(), index->size(), index->dim(), percentile(full, 0.5), percentile(full, 0.9),
                  percentile(cpu, 0.5), hit_pct, percentile(again, 0.5), percentile(search, 0.5),
                  percentile(brute, 0.5));
    out << line;
    if (returned != 3 * static_cast<std::size_t>(opt.queries) * std::min<std::size_t>(static_cast<std::size_t>(opt.k), index->size()))
      out << "  (some queries returned fewer than k entries)\n";
  }
  // Two connections standing in for two machines: how long a row committed
  // through one takes to be retrievable through the other.
  {
    earc::exp::ExperienceStore writer(path, unwarmed);
    std::mt19937_64 rng(opt.seed + 2);
    const auto traits = classes[0].traits();
    std::vector<double> visible;
    for (int i = 0; i < 20; ++i) {
      const auto e = earc::exp::straightLineExperience(traits, classes[0].sample(rng), kSyntheticSteps);
      const auto id = writer.insert(e, -1);
      const auto t0 = Clock::now();
      for (bool seen = false; !seen;)
        for (const auto& m : store.nearest(e.cls, e.key, 1)) seen = seen || m.experience.id == *id;
      visible.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    }
    std::snprintf(line, sizeof line, "\na row committed through another connection is retrievable after %.1f us (median), %.1f us (max of 20)\n",
                  percentile(visible, 0.5), percentile(visible, 1.0));
    out << line;
  }
  out << "\nmedian/p90: wall time of ExperienceStore::nearest (search + read + decode k rows, or take them from\n"
         "the row cache); cpu: its median thread CPU time; hit: rows the row cache or the background copy had; again: the same queries\n"
         "asked again (median); search: k-d tree + tail only (median); brute: linear scan of every key (median).\n"
         "load average " << loadAverage() << " on " << std::thread::hardware_concurrency() << " cores.\n";
}

void setupBenchRetrieval(CLI::App& app) {
  auto opt = std::make_shared<BenchRetrievalOptions>();
  CLI::App* sub = app.add_subcommand("bench-retrieval", "Time k-closest retrieval per class on synthetic entries");
  sub->add_option("--entries", opt->entries, "Entries per class")->check(earc::cli::wholeNumberIn(1, 10000000));
  sub->add_option("--queries", opt->queries, "Queries per class")->check(earc::cli::wholeNumberIn(1, 1000000));
  sub->add_option("--k", opt->k, "Experiences retrieved per query")->check(earc::cli::wholeNumberIn(1, 1000));
  sub->add_option("--seed", opt->seed, "Random seed")->check(earc::cli::kWholeNumber);
  sub->add_option("--row-cache-mb", opt->row_cache_mb, "Bound of the store's cache of retrieved rows in MiB (0: off)")
      ->check(earc::cli::wholeNumberIn(0, 65536));
  sub->add_flag("--no-warm-rows", opt->no_warm_rows,
                "PostgreSQL: no background copy of the rows (StoreOptions::warm_rows)");
  sub->add_option("--db", opt->db, "An empty store to fill (e.g. postgresql://USER@HOST:PORT/DBNAME) instead of a temporary file");
  sub->callback([opt] { runBenchRetrieval(*opt, std::cout); });
}

}  // namespace

static earc::cli::Registrar registered_bench_retrieval("earc-db", "bench-retrieval", setupBenchRetrieval);
