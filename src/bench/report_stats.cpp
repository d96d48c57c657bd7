// The report's statistics: bootstrap intervals, quantiles, cells and paired
// ratios of trials.
#include "earc/bench/report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"
#include "report_util.hpp"

namespace earc::bench {

using report_detail::methodRank;
using report_detail::suiteRank;

namespace {

// The values at the given indices (one bootstrap resample).
std::vector<double> gather(const std::vector<double>& values, const std::vector<std::size_t>& idx) {
  std::vector<double> out;
  out.reserve(idx.size());
  for (std::size_t i : idx) out.push_back(values[i]);
  return out;
}

// Where a cell goes in the tables (see summarize).
auto cellOrder(const CellSummary& c) {
  return std::make_tuple(suiteRank(c.suite), c.suite, c.time_limit_s, c.robots, methodRank(c.method), c.method);
}

}  // namespace

// A 95% bootstrap interval (percentile method) of a statistic of n paired
// items: `statistic` gets the indices of one resample (n draws from 0..n-1
// with replacement); 2,000 resamples from a generator seeded with `seed`,
// so the same items and seed give the same interval. n must be positive.
std::pair<double, double> bootstrapInterval(std::size_t n,
                                            const std::function<double(const std::vector<std::size_t>&)>& statistic,
                                            std::uint64_t seed) {
  // Enough resamples that the interval's ends move by less than the
  // printed precision from one seed to another.
  constexpr int kResamples = 2000;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::vector<double> values(kResamples);
  std::vector<std::size_t> sample(n);
  for (double& v : values) {
    for (std::size_t& i : sample) i = pick(rng);
    v = statistic(sample);
  }
  return {*quantile(values, 0.025), *quantile(values, 0.975)};
}

std::pair<double, double> medianInterval(const std::vector<double>& values, std::uint64_t seed) {
  return bootstrapInterval(
      values.size(), [&](const std::vector<std::size_t>& idx) { return *quantile(gather(values, idx), 0.5); }, seed);
}

std::optional<double> quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nullopt;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

bool TrialFilter::matches(const TrialRecord& t) const {
  return (!seed || t.seed == *seed) && (!time_limit_s || t.time_limit_s == *time_limit_s);
}

std::vector<TrialRecord> TrialFilter::apply(std::vector<TrialRecord> trials) const {
  std::erase_if(trials, [this](const TrialRecord& t) { return !matches(t); });
  return trials;
}

std::vector<TrialRecord> TrialFilter::applyRequired(std::vector<TrialRecord> trials, const std::string& results) const {
  if (trials.empty()) return trials;
  std::set<std::uint64_t> seeds;
  std::set<double> limits;
  for (const TrialRecord& t : trials) {
    seeds.insert(t.seed);
    limits.insert(t.time_limit_s);
  }
  trials = apply(std::move(trials));
  if (!trials.empty()) return trials;
  // Said of the first option that matches nothing on its own.
  auto list = [](const auto& values, auto text) {
    std::string out;
    for (const auto& v : values) out += (out.empty() ? "" : ", ") + text(v);
    return out;
  };
  auto seconds = [](double s) { return formatNumber(s) + " s"; };
  auto number = [](std::uint64_t n) { return std::to_string(n); };
  if (seed && !seeds.count(*seed))
    throw InputError(results, "--seed", "no trials of run seed " + std::to_string(*seed) + " (its trials' seeds: " +
                                             list(seeds, number) + ")");
  if (time_limit_s && !limits.count(*time_limit_s))
    throw InputError(results, "--time-limit", "no trials with a time limit of " + seconds(*time_limit_s) +
                                                  " (its trials' limits: " + list(limits, seconds) + ")");
  throw InputError(results, "--seed/--time-limit",
                   "no trials of run seed " + std::to_string(*seed) + " with a time limit of " + seconds(*time_limit_s));
}

std::vector<CellSummary> summarize(const std::vector<TrialRecord>& trials) {
  std::map<std::tuple<std::string, int, std::string, double>, std::vector<const TrialRecord*>> cells;
  for (const auto& t : trials) cells[{t.suite, t.robots, t.method, t.time_limit_s}].push_back(&t);
  std::vector<CellSummary> out;
  for (const auto& [key, list] : cells) {
    CellSummary c;
    std::tie(c.suite, c.robots, c.method, c.time_limit_s) = key;
    std::vector<double> times;
    for (const TrialRecord* t : list) {
      ++c.trials;
      if (t->success) {
        ++c.solved;
        if (t->planning_time_s) times.push_back(*t->planning_time_s);
      }
    }
    c.median_s = quantile(times, 0.5);
    c.q1_s = quantile(times, 0.25);
    c.q3_s = quantile(times, 0.75);
    out.push_back(std::move(c));
  }
  std::sort(out.begin(), out.end(),
            [](const CellSummary& a, const CellSummary& b) { return cellOrder(a) < cellOrder(b); });
  return out;
}

PairedRatio pairedRatio(const std::vector<TrialRecord>& trials, const std::string& suite, int robots,
                        const std::string& a, const std::string& b, std::optional<double> time_limit_s) {
  using Key = std::tuple<int, std::uint64_t, double>;
  std::map<Key, const TrialRecord*> ta, tb;
  for (const auto& t : trials) {
    if (t.suite != suite || t.robots != robots || !t.success || !t.planning_time_s) continue;
    if (time_limit_s && t.time_limit_s != *time_limit_s) continue;
    if (t.method == a) ta[{t.trial, t.seed, t.time_limit_s}] = &t;
    if (t.method == b) tb[{t.trial, t.seed, t.time_limit_s}] = &t;
  }
  std::vector<double> ratios, paired_a, paired_b, makespans_a, makespans_b;
  for (const auto& [k, ra] : ta) {
    auto it = tb.find(k);
    if (it == tb.end()) continue;
    const TrialRecord& rb = *it->second;
    const double va = *ra->planning_time_s, vb = *rb.planning_time_s;
    if (vb <= 0) continue;
    ratios.push_back(va / vb);
    paired_a.push_back(va);
    paired_b.push_back(vb);
    if (ra->makespan && rb.makespan) {
      makespans_a.push_back(static_cast<double>(*ra->makespan));
      makespans_b.push_back(static_cast<double>(*rb.makespan));
    }
  }
  PairedRatio r{static_cast<int>(ratios.size()), quantile(ratios, 0.5), std::nullopt, std::nullopt, std::nullopt,
                quantile(makespans_a, 0.5), quantile(makespans_b, 0.5)};
  if (ratios.empty()) return r;
  r.of_medians = *quantile(paired_a, 0.5) / *quantile(paired_b, 0.5);
  constexpr std::uint64_t kSeed = 1;
  r.median_interval = medianInterval(ratios, kSeed);
  r.of_medians_interval = bootstrapInterval(
      ratios.size(),
      [&](const std::vector<std::size_t>& idx) {
        return *quantile(gather(paired_a, idx), 0.5) / *quantile(gather(paired_b, idx), 0.5);
      },
      kSeed);
  return r;
}

}  // namespace earc::bench
