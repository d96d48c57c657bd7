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

}  // namespace

std::vector<Candidate> retrieveCandidates(ExperienceStore& store, const std::vector<const RobotModel*>& robots,
                                          const std::vector<std::vector<double>>& starts,
                                          const std::vector<std::vector<double>>& goals, std::size_t k) {
  const std::vector<RobotTraits> traits = traitsOfAll(robots);
  if (!hasExperienceClass(traits)) return {};
  std::vector<Canonical> forms{canonicalize(traits, starts, goals)};
  if (forms.front().symmetric) forms.push_back(swappedRoles(forms.front(), starts, goals));
  std::vector<Candidate> out;
  for (const Canonical& form : forms)
    for (Match& m : store.nearest(form.cls, form.key, k))
      out.push_back({m.experience.id, m.distance, form.fromCanonical(m.experience.paths)});
  // Two role assignments may both find one row: keep its nearer use.
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  std::vector<Candidate> unique;
  for (Candidate& c : out)
    if (std::none_of(unique.begin(), unique.end(), [&](const Candidate& u) { return u.id == c.id; }))
      unique.push_back(std::move(c));
  if (unique.size() > k) unique.resize(k);
  return unique;
}

std::optional<std::int64_t> learn(ExperienceStore& store, const std::vector<const RobotModel*>& robots,
                                  const std::vector<Path>& paths, double solve_time_s, Source source,
                                  double near_duplicate_eps) {
  const std::vector<RobotTraits> traits = traitsOfAll(robots);
  if (!hasExperienceClass(traits) || paths.size() != robots.size()) return std::nullopt;
  std::vector<std::vector<double>> starts, goals;
  for (const Path& p : paths) {
    if (p.empty()) return std::nullopt;
    starts.emplace_back(p.at(0), p.at(0) + p.dim());
    goals.emplace_back(p.back(), p.back() + p.dim());
  }
  Experience e = canonicalExperience(canonicalize(traits, starts, goals), paths);
  e.source = source;
  e.solve_time_s = solve_time_s;
  return store.insert(e, near_duplicate_eps);
}

}  // namespace earc::exp
