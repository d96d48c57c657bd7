#include "earc/experience/retrieval.hpp"

#include <algorithm>

#include "earc/experience/keys.hpp"

namespace earc::exp {

namespace {

std::vector<RobotTraits> traitsOfAll(const std::vector<const RobotModel*>& robots) {
  std::vector<RobotTraits> traits;
  traits.reserve(robots.size());
  for (const RobotModel* r : robots) traits.push_back(traitsOf(*r));
  return traits;
}

// The experience of a solved subproblem, or nothing when its robots form
// no class, the paths do not match them, or they leave the range the store
// holds (stateProblem: a scenario in units so coarse that a subproblem
// spans more than kMaxStoredPosition): not learned, and the plan, solved
// already, does not fail over it.
std::optional<Experience> experienceOf(const std::vector<const RobotModel*>& robots, const std::vector<Path>& paths,
                                       double solve_time_s, Source source) {
  const std::vector<RobotTraits> traits = traitsOfAll(robots);
  if (!hasExperienceClass(traits) || paths.size() != robots.size()) return std::nullopt;
  std::vector<std::vector<double>> starts, goals;
  for (std::size_t r = 0; r < paths.size(); ++r) {
    const Path& p = paths[r];
    if (p.empty() || p.dim() != robots[r]->dim()) return std::nullopt;
    starts.emplace_back(p.at(0), p.at(0) + p.dim());
    goals.emplace_back(p.back(), p.back() + p.dim());
  }
  Experience e = canonicalExperience(canonicalize(traits, starts, goals), paths);
  if (stateProblem(e.cls, e.paths)) return std::nullopt;
  e.source = source;
  e.solve_time_s = solve_time_s;
  return e;
}

}  // namespace

// All robots move together, as in the coupled solver's time stamping;
// paths that already fit come back unchanged. kMaxFittedStates leaves room
// for a resolution ratio of hundreds (docs/performance-log.md).
std::vector<Path> fitResolution(const std::vector<const RobotModel*>& robots, const std::vector<Path>& paths) {
  const std::size_t n = paths.empty() ? 0 : paths.front().size();
  std::vector<int> steps(n > 0 ? n - 1 : 0);
  bool fits = true;
  std::size_t states = n > 0 ? 1 : 0;
  for (std::size_t t = 0; t + 1 < n; ++t) {
    int k = 0;
    for (std::size_t r = 0; r < robots.size(); ++r)
      k = std::max(k, robots[r]->stepsBetween(paths[r].at(t), paths[r].at(t + 1)));
    steps[t] = k;
    fits = fits && k <= 1;
    states += static_cast<std::size_t>(std::max(1, k));
  }
  if (fits) return paths;
  // Counted before anything is split: one state of a made-up row a million
  // units from the others is 2.8e7 steps of 0.05 there and as many back,
  // gigabytes before a single check.
  if (states > kMaxFittedStates)
    throw NoStepCountError("fitResolution: " + std::to_string(states) + " states at this resolution, more than " +
                           std::to_string(kMaxFittedStates));
  std::vector<Path> out;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    out.emplace_back(robots[r]->dim());
    out[r].push(paths[r].at(0));
  }
  std::vector<double> q;
  for (std::size_t t = 0; t + 1 < n; ++t) {
    const int k = std::max(1, steps[t]);  // a step where all wait stays one step
    for (int j = 1; j <= k; ++j)
      for (std::size_t r = 0; r < robots.size(); ++r) {
        if (j == k) {
          out[r].push(paths[r].at(t + 1));
          continue;
        }
        q.resize(static_cast<std::size_t>(robots[r]->dim()));
        robots[r]->interpolate(paths[r].at(t), paths[r].at(t + 1), static_cast<double>(j) / k, q.data());
        out[r].push(q);
      }
  }
  return out;
}

// Each path starts near its robot's start and ends near its goal, not
// exactly: the caller connects them. A symmetric arm pair is searched under
// both role assignments, merged; after a skip a row found under one can
// come back under the other. Coarser rows come back split (fitResolution);
// one it refuses (NoStepCountError) is left out. skip: the next candidates
// after a first call with k = skip, without reading the skipped rows.
std::vector<Candidate> retrieveCandidates(ExperienceStore& store, const std::vector<const RobotModel*>& robots,
                                          const std::vector<std::vector<double>>& starts,
                                          const std::vector<std::vector<double>>& goals, std::size_t k,
                                          std::size_t skip, std::vector<std::int64_t>* unusable) {
  const std::vector<RobotTraits> traits = traitsOfAll(robots);
  if (!hasExperienceClass(traits)) return {};
  std::vector<Canonical> forms{canonicalize(traits, starts, goals)};
  if (forms.front().symmetric) forms.push_back(swappedRoles(forms.front(), starts, goals));
  std::vector<Candidate> out;
  std::vector<std::int64_t> unfit;
  for (const Canonical& form : forms)
    for (Match& m : store.nearest(form.cls, form.key, k, skip)) {
      // One row the robots cannot follow at their resolution leaves the
      // others to be tried.
      try {
        out.push_back({m.experience.id, m.distance, fitResolution(robots, form.fromCanonical(m.experience.paths))});
      } catch (const NoStepCountError&) {
        if (std::find(unfit.begin(), unfit.end(), m.experience.id) == unfit.end()) unfit.push_back(m.experience.id);
      }
    }
  // Two role assignments may both find one row: keep its nearer use.
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  std::vector<Candidate> unique;
  for (Candidate& c : out)
    if (std::none_of(unique.begin(), unique.end(), [&](const Candidate& u) { return u.id == c.id; }))
      unique.push_back(std::move(c));
  const std::size_t wanted = k - std::min(k, skip);
  if (unique.size() > wanted) unique.resize(wanted);
  if (unusable) *unusable = std::move(unfit);
  return unique;
}

std::optional<std::int64_t> learn(ExperienceStore& store, const std::vector<const RobotModel*>& robots,
                                  const std::vector<Path>& paths, double solve_time_s, Source source,
                                  double near_duplicate_eps) {
  auto e = experienceOf(robots, paths, solve_time_s, source);
  if (!e) return std::nullopt;
  return store.insert(*e, near_duplicate_eps);
}

std::size_t learnAll(ExperienceStore& store, const std::vector<Solved>& solved, Source source,
                     double near_duplicate_eps) {
  std::vector<Experience> batch;
  for (const Solved& s : solved)
    if (auto e = experienceOf(s.robots, s.paths, s.solve_time_s, source)) batch.push_back(std::move(*e));
  if (batch.empty()) return 0;
  std::size_t stored = 0;
  for (const auto& id : store.insertAll(batch, near_duplicate_eps)) stored += id.has_value();
  return stored;
}

}  // namespace earc::exp
