#include "earc/planning/roadmap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "earc/util/random.hpp"

namespace earc {

namespace {

// Rejection sampling gives up after this many tries per requested sample
// (a workspace that is almost all obstacle would otherwise spin forever).
constexpr int kMaxTriesPerSample = 60;

}  // namespace

Roadmap::Roadmap(const CollisionWorld& world, const RobotModel& model, int neighbors, std::uint64_t seed,
                 const Deadline& deadline)
    : world_(world), model_(model), dim_(model.dim()), neighbors_(neighbors), rng_(seed),
      index_(model.isMobile() ? 4 : model.dim()), poll_(deadline, kWorkPerClockRead) {
  model_.samplingBounds(world_.workspace(), lo_, hi_);
}

Roadmap::Roadmap(const CollisionWorld& world, const RobotModel& model, const Snapshot& snapshot,
                 const Deadline& deadline)
    : world_(world), model_(model), dim_(model.dim()), neighbors_(snapshot.neighbors), rng_(snapshot.rng),
      configs_(snapshot.configs), adjacency_(snapshot.adjacency), edge_ends_(snapshot.edge_ends),
      edge_state_(snapshot.edge_state), dropped_(snapshot.dropped), candidates_(snapshot.candidates),
      index_(snapshot.index), edge_checks_(snapshot.edge_checks), poll_(deadline, kWorkPerClockRead) {
  model_.samplingBounds(world_.workspace(), lo_, hi_);
}

Roadmap::Snapshot Roadmap::snapshot() const {
  return {neighbors_, rng_, configs_, adjacency_, edge_ends_, edge_state_, index_, edge_checks_, dropped_, candidates_};
}

void Roadmap::embed(const double* q, double* out) const {
  const Resolution& res = model_.resolution();
  if (model_.isMobile()) {
    // Scaled so that one time step of translation or of rotation is about
    // one unit: Euclidean distance here approximates the time metric.
    out[0] = q[0] / res.translation;
    out[1] = q[1] / res.translation;
    out[2] = std::cos(q[2]) / res.rotation;
    out[3] = std::sin(q[2]) / res.rotation;
  } else {
    for (int j = 0; j < dim_; ++j) out[j] = q[j] / res.joint;
  }
}

void Roadmap::grow(int samples, const ConfigBox* within) {
  const int first = size();
  const std::vector<double>& lo = within ? within->lo : lo_;
  const std::vector<double>& hi = within ? within->hi : hi_;
  std::vector<double> q(static_cast<std::size_t>(dim_));
  std::vector<double> e(static_cast<std::size_t>(index_.dim()));
  long tries = static_cast<long>(samples) * kMaxTriesPerSample;
  int added = 0;
  // A try places the robot's bodies and checks them, a connection searches
  // the index in dim_ coordinates: both about dim_ units of work.
  const auto work = static_cast<std::size_t>(dim_);
  while (added < samples && tries-- > 0) {
    if (poll_.expired(work)) break;
    for (int j = 0; j < dim_; ++j) q[static_cast<std::size_t>(j)] = uniform(rng_, lo[static_cast<std::size_t>(j)], hi[static_cast<std::size_t>(j)]);
    if (!world_.stateValid(model_, q.data())) continue;
    configs_.insert(configs_.end(), q.begin(), q.end());
    adjacency_.emplace_back();
    embed(q.data(), e.data());
    index_.add(e.data());
    ++added;
  }
  // At most k new edges per new vertex.
  const std::size_t edges = edge_ends_.size() + static_cast<std::size_t>(added) * static_cast<std::size_t>(neighbors_);
  edge_ends_.reserve(edges);
  edge_state_.reserve(edges);
  std::vector<std::size_t> near;
  std::vector<double> scratch;
  // A vertex has its k nearest and about as many again that have it among
  // theirs: room for 2k edges spares each list its regrowths.
  for (int v = first; v < size(); ++v) adjacency_[static_cast<std::size_t>(v)].reserve(2 * static_cast<std::size_t>(neighbors_));
  for (int v = first; v < size() && !poll_.expired(work); ++v) connect(v, near, scratch);
}

// Dropped vertices' edges are marked invalid without a check; a vertex that
// lost neighbours is joined to its k nearest of the rest (from the kept
// candidates where they suffice), as a roadmap sampled here would be.
int Roadmap::dropInvalidVertices() {
  const auto work = static_cast<std::size_t>(dim_);
  int count = 0;
  for (int v = 0; v < size() && !poll_.expired(work); ++v)
    if (!world_.stateValid(model_, config(v))) {
      if (dropped_.empty()) dropped_.resize(static_cast<std::size_t>(size()), false);
      dropped_[static_cast<std::size_t>(v)] = true;
      ++count;
      for (const Edge& e : adjacency_[static_cast<std::size_t>(v)]) edge_state_[static_cast<std::size_t>(e.id)] = -1;
    }
  // A vertex that lost neighbours is joined to its k nearest of the rest,
  // as a roadmap sampled in this world would have been.
  if (count > 0) {
    std::vector<std::size_t> near;
    std::vector<double> scratch;
    for (int v = 0; v < size() && !poll_.expired(work); ++v) {
      if (dropped(v)) continue;
      const auto& mine = adjacency_[static_cast<std::size_t>(v)];
      if (std::any_of(mine.begin(), mine.end(), [&](const Edge& e) { return dropped(e.to); })) connect(v, near, scratch);
    }
  }
  return count;
}

// Widened by four bounding radii for a mobile robot (whose box spans every
// heading), to take in the way out of a pocket, and by a tenth of each
// joint's range for an arm.
ConfigBox Roadmap::boxAround(const std::vector<double>& configs) const {
  const auto d = static_cast<std::size_t>(dim_);
  ConfigBox box{lo_, hi_};
  if (configs.size() < d) return box;
  // A doorway next to a pocket lies within four bounding radii of it.
  const std::size_t boxed = model_.isMobile() ? 2 : d;
  for (std::size_t j = 0; j < boxed; ++j) {
    double l = std::numeric_limits<double>::infinity(), h = -l;
    for (std::size_t i = j; i < configs.size(); i += d) {
      l = std::min(l, configs[i]);
      h = std::max(h, configs[i]);
    }
    const double margin = model_.isMobile() ? 4.0 * model_.boundingRadius() : 0.1 * (hi_[j] - lo_[j]);
    box.lo[j] = std::max(lo_[j], l - margin);
    box.hi[j] = std::min(hi_[j], h + margin);
  }
  return box;
}

double Roadmap::share(const ConfigBox& box) const {
  double s = 1.0;
  for (std::size_t j = 0; j < lo_.size(); ++j)
    if (hi_[j] > lo_[j]) s *= std::max(0.0, box.hi[j] - box.lo[j]) / (hi_[j] - lo_[j]);
  return s;
}

void Roadmap::growWithin(const ConfigBox& box) {
  const int most = std::max(64, size());
  grow(std::clamp(static_cast<int>(std::ceil(4.0 * size() * share(box))), 64, most), &box);
}

void Roadmap::connect(int v, std::vector<std::size_t>& near, std::vector<double>& scratch) {
  // The index holds v's embedding (vertices and points share numbers).
  // Dropped vertices are still in it: ask for more, take the k nearest of
  // the rest.
  const auto k = static_cast<std::size_t>(neighbors_);
  const std::size_t listed = 2 * k;  // candidates kept per vertex (keepCandidates)
  const auto at = static_cast<std::size_t>(v) * listed;
  if (keep_candidates_ && candidates_.size() == at) {
    // Building a free space's roadmap: the 2k nearest are kept for its
    // copies, the k nearest joined as always (the first k + 1 of an exact
    // search for more are those of the search for k + 1).
    index_.nearest(index_.point(static_cast<std::size_t>(v)), listed + 1, near, scratch);
    for (std::size_t u : near)
      if (u != static_cast<std::size_t>(v) && candidates_.size() < at + listed) candidates_.push_back(static_cast<int>(u));
    candidates_.resize(at + listed, -1);
    near.resize(std::min(near.size(), k + 1));
  } else if (droppedAny() && candidates_.size() >= at + listed &&
             std::count_if(candidates_.begin() + static_cast<std::ptrdiff_t>(at),
                           candidates_.begin() + static_cast<std::ptrdiff_t>(at + listed),
                           [&](int u) { return u >= 0 && !dropped(u); }) >= static_cast<std::ptrdiff_t>(k)) {
    // A copy's vertex that lost neighbours: its k nearest that are left,
    // from the list kept, without a search.
    near.assign(candidates_.begin() + static_cast<std::ptrdiff_t>(at),
                candidates_.begin() + static_cast<std::ptrdiff_t>(at + listed));
  } else {
    // Past the dropped neighbours already known (a new vertex of a grown
    // copy knows none: room for as many again).
    std::size_t want = k + 1;
    if (droppedAny()) {
      const auto& mine = adjacency_[static_cast<std::size_t>(v)];
      want += mine.empty() ? k : static_cast<std::size_t>(std::count_if(mine.begin(), mine.end(), [&](const Edge& e) {
        return dropped(e.to);
      }));
    }
    index_.nearest(index_.point(static_cast<std::size_t>(v)), want, near, scratch);
  }
  auto& mine = adjacency_[static_cast<std::size_t>(v)];
  std::size_t taken = 0;
  for (std::size_t u_raw : near) {
    int u = static_cast<int>(u_raw);
    if (u == v || u < 0) continue;
    if (droppedAny() && (dropped(u) || taken++ == k)) {
      if (taken > k) break;
      continue;
    }
    // Already joined when v was among u's nearest. Every edge of v is in
    // its own list, a few dozen at most: scanning it is cheaper than a
    // hash set of all edges.
    if (std::any_of(mine.begin(), mine.end(), [u](const Edge& ed) { return ed.to == u; })) continue;
    int steps = model_.stepsBetween(config(v), config(u));
    int id = static_cast<int>(edge_ends_.size());
    edge_ends_.emplace_back(v, u);
    edge_state_.push_back(0);
    mine.push_back({u, steps, id});
    adjacency_[static_cast<std::size_t>(u)].push_back({v, steps, id});
  }
}

bool Roadmap::edgeValid(int id) {
  auto& state = edge_state_[static_cast<std::size_t>(id)];
  if (state == 0) {
    auto [a, b] = edge_ends_[static_cast<std::size_t>(id)];
    ++edge_checks_;
    const std::optional<bool> valid = world_.motionValid(model_, config(a), config(b), poll_);
    if (!valid) return false;  // out of time: unknown
    state = *valid ? 1 : -1;
  }
  return state > 0;
}

std::vector<int> Roadmap::nearest(const double* q, int k) const {
  std::vector<double> e(static_cast<std::size_t>(index_.dim()));
  embed(q, e.data());
  std::vector<int> out;
  for (std::size_t i : index_.nearest(e.data(), static_cast<std::size_t>(k))) out.push_back(static_cast<int>(i));
  return out;
}

QueryGraph::QueryGraph(Roadmap& roadmap, const RobotModel& robot, const ConfigBox* region)
    : roadmap_(roadmap), robot_(robot), region_(region) {}

const double* QueryGraph::config(int v) const {
  const int n = roadmap_.size();
  return v < n ? roadmap_.config(v) : extra_[static_cast<std::size_t>(v - n)].q.data();
}

bool QueryGraph::allowed(int v) const {
  if (v >= roadmap_.size()) return true;
  if (roadmap_.dropped(v)) return false;
  return region_ == nullptr || region_->contains(roadmap_.config(v));
}

int QueryGraph::addEdge(int a, int b) {
  int key = -1 - static_cast<int>(extra_edge_ends_.size());
  extra_edge_ends_.emplace_back(a, b);
  extra_edge_state_.push_back(0);
  return key;
}

int QueryGraph::addVertex(const double* q, int k) {
  const int n = roadmap_.size();
  const int v = size();
  Extra x;
  x.q.assign(q, q + model().dim());
  extra_.push_back(std::move(x));
  auto link = [&](int u) {
    int steps = model().stepsBetween(config(v), config(u));
    int key = addEdge(v, u);
    extra_[static_cast<std::size_t>(v - n)].edges.push_back({u, steps, key});
    if (u < n)
      back_edges_[u].push_back({v, steps, key});
    else
      extra_[static_cast<std::size_t>(u - n)].edges.push_back({v, steps, key});
  };
  // Ask for more neighbours than needed when a region or dropped
  // vertices filter them.
  int want = region_ || roadmap_.droppedAny() ? 4 * k : k;
  int linked = 0;
  for (int u : roadmap_.nearest(q, want)) {
    if (!allowed(u)) continue;
    link(u);
    if (++linked >= k) break;
  }
  for (int u = n; u < v; ++u) link(u);
  return v;
}

bool QueryGraph::edgeValid(int key) {
  if (key >= 0) return roadmap_.edgeValid(key);
  auto idx = static_cast<std::size_t>(-1 - key);
  auto& state = extra_edge_state_[idx];
  if (state == 0) {
    auto [a, b] = extra_edge_ends_[idx];
    const std::optional<bool> valid = roadmap_.world().motionValid(model(), config(a), config(b), roadmap_.poll());
    if (!valid) return false;  // out of time: unknown
    state = *valid ? 1 : -1;
  }
  return state > 0;
}

std::optional<std::vector<int>> shortestPath(QueryGraph& graph, int from, int to, const Deadline& deadline,
                                             std::vector<int>* reached) {
  const int n = graph.size();
  const auto un = static_cast<std::size_t>(n);
  const RobotModel& model = graph.model();
  // Lazy weighted A*: the queue holds (vertex, parent edge) pairs, and an
  // edge is checked only when its pair comes first; an invalid one is
  // dropped and the vertex waits for its next way in. Each edge is thus
  // checked at most once and the search never starts over, where checking
  // a whole candidate path and repeating searched a warehouse's roadmap
  // about twenty times per robot while its edges were unknown.
  std::vector<double> h(un, -1.0);
  // Polled as it works: a whole map's roadmap can have 80,000 vertices.
  DeadlinePoll poll(deadline, kWorkPerClockRead);
  auto heuristic = [&](int v) {
    double& hv = h[static_cast<std::size_t>(v)];
    if (hv < 0) hv = model.distance(graph.config(v), graph.config(to));
    return hv;
  };
  // An edge left unchecked when the roadmap's deadline passed reads as
  // invalid without being marked so: the search then stops.
  auto cut = [&] { return deadline.expired() || graph.roadmap().poll().seenExpired(); };
  std::vector<int> parent(un, -1);
  std::vector<char> closed(un, 0);
  struct Item {
    double f, g;
    int v, from, key;
    bool operator>(const Item& o) const { return f != o.f ? f > o.f : g < o.g; }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  open.push({heuristic(from), 0.0, from, -1, 0});
  bool found = false;
  while (!open.empty()) {
    if (poll.expired(kWorkPerGraphPop)) return std::nullopt;
    const Item it = open.top();
    open.pop();
    if (closed[static_cast<std::size_t>(it.v)]) continue;
    if (it.from >= 0 && !graph.edgeValid(it.key)) {
      if (cut()) return std::nullopt;
      continue;
    }
    closed[static_cast<std::size_t>(it.v)] = 1;
    parent[static_cast<std::size_t>(it.v)] = it.from;
    if (it.v == to) {
      found = true;
      break;
    }
    graph.forEachEdge(it.v, [&](int u, int steps, int key) {
      if (closed[static_cast<std::size_t>(u)] || graph.knownInvalid(key)) return;
      // Every way in is queued: a cheaper one may yet prove invalid.
      const double cand = it.g + steps;
      open.push({cand + heuristic(u), cand, u, it.v, key});
    });
  }
  if (cut()) return std::nullopt;
  if (!found) {
    // The search ran out of ways: the vertices it closed are from's part.
    if (reached) {
      reached->clear();
      for (int v = 0; v < n; ++v)
        if (closed[static_cast<std::size_t>(v)]) reached->push_back(v);
    }
    return std::nullopt;
  }
  std::vector<int> path;
  for (int v = to; v >= 0; v = parent[static_cast<std::size_t>(v)]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

Path timeStamp(const RobotModel& model, const std::vector<std::vector<double>>& waypoints) {
  Path p(model.dim());
  if (waypoints.empty()) return p;
  p.push(waypoints.front().data());
  for (std::size_t w = 1; w < waypoints.size(); ++w) appendStraightMotion(model, waypoints[w - 1].data(), waypoints[w].data(), p);
  return p;
}

void appendStraightMotion(const RobotModel& model, const double* a, const double* b, Path& out) {
  const int n = model.stepsBetween(a, b);
  if (n <= 0) return;
  std::vector<double> q(static_cast<std::size_t>(model.dim()));
  for (int k = 1; k < n; ++k) {
    model.interpolate(a, b, static_cast<double>(k) / n, q.data());
    out.push(q.data());
  }
  out.push(b);
}

std::shared_ptr<const RoadmapCache::Entry> RoadmapCache::find(const std::string& key) {
  for (auto it = entries_.begin(); it != entries_.end(); ++it)
    if (it->first == key) {
      entries_.splice(entries_.begin(), entries_, it);
      ++hits_;
      return entries_.front().second;
    }
  ++misses_;
  return nullptr;
}

void RoadmapCache::put(const std::string& key, Roadmap::Snapshot snapshot, std::uint64_t work) {
  auto entry = std::make_shared<Entry>();
  const Roadmap::Snapshot& s = snapshot;
  std::size_t bytes = key.size() + s.configs.size() * sizeof(double) + s.edge_ends.size() * sizeof(s.edge_ends[0]) +
                      s.edge_state.size() + s.index.size() * static_cast<std::size_t>(s.index.dim()) * sizeof(double);
  for (const auto& edges : s.adjacency) bytes += sizeof(edges) + edges.size() * sizeof(Roadmap::Edge);
  entry->snapshot = std::move(snapshot);
  entry->work = work;
  entry->bytes = bytes;
  if (bytes > capacity_) return;
  std::erase_if(entries_, [&](const auto& e) {
    if (e.first != key) return false;
    bytes_ -= e.second->bytes;
    return true;
  });
  while (!entries_.empty() && bytes_ + bytes > capacity_) {
    bytes_ -= entries_.back().second->bytes;
    entries_.pop_back();
  }
  entries_.emplace_front(key, std::move(entry));
  bytes_ += bytes;
}

}  // namespace earc
