#include "stickrep/census.h"

#include <cmath>
#include <vector>

#include "stickrep/paper_reference.h"

namespace stickrep::map {

namespace {

struct Leaf {
  int cls = -1;  // CensusClass, or -1 for an edge in no table
};

struct Link {
  double angle_deg = 180.0;
  bool artificial = false;
};

int CensusClassOf(DoorClass leaf) {
  switch (leaf) {
    case DoorClass::k30:
      return kCensusDoor30;
    case DoorClass::k32:
      return kCensusDoor32;
    case DoorClass::k36:
      return kCensusDoor36;
    case DoorClass::k40:
      return kCensusDoor40;
    default:
      return -1;
  }
}

// A ring's edges with double doors expanded into leaves; links[j] joins leaf j to leaf j + 1
// (cyclically for a closed ring).
struct LeafChain {
  std::vector<Leaf> leaves;
  std::vector<Link> links;
};

// The class of leaf j, wrapping past the last leaf (cyclically, as links do on a closed ring).
int ClassAt(const LeafChain& chain, int j) {
  const int L = static_cast<int>(chain.leaves.size());
  return chain.leaves[j % L].cls;
}

// A doorway: its leaves joined at 180° nodes, and its row of Table 6.8.
void AddDoorEdge(const Edge& e, Census* c, LeafChain* chain) {
  const DoorClass cls = *e.door_class;
  const int leaves_here = IsDoubleDoor(cls) ? 2 : 1;
  const int row = CensusClassOf(LeafClass(cls));
  ++c->doors_by_class[static_cast<int>(cls)];
  c->door_leaves += leaves_here;
  for (int k = 0; k < leaves_here; ++k) {
    if (k > 0) chain->links.push_back(Link{180.0, false});
    chain->leaves.push_back(Leaf{row});
  }
  if (row >= 0) {
    c->door_census[row][0] += leaves_here;
    for (std::size_t p = 0; p < paper::kPatternWords.size(); ++p) {
      if (e.pattern == paper::kPatternWords[p]) c->door_census[row][p + 1] += leaves_here;
    }
  }
}

// A wall: one leaf, and its columns of Table 6.9.
void AddWallEdge(const Edge& e, Census* c, LeafChain* chain) {
  ++c->walls;
  chain->leaves.push_back(Leaf{kCensusWall});
  for (std::size_t t = 0; t < paper::kWallThresholdsIn.size(); ++t) {
    const double th = paper::kWallThresholdsIn[t];
    if (t == 0 ? e.metric_in > th : e.metric_in >= th) ++c->wall_census[t];
  }
}

// The ring's leaves and links; counts its edges (edge totals, Tables 6.8 and 6.9) on the way.
LeafChain ExpandLeaves(const Ring& ring, Census* c) {
  LeafChain chain;
  const int n = ring.EdgeCount();
  for (int i = 0; i < n; ++i) {
    const Edge& e = ring.edges[i];
    ++c->edges;
    c->total_metric_in += e.metric_in;
    if (e.IsDoor()) {
      AddDoorEdge(e, c, &chain);
    } else if (e.IsWall()) {
      AddWallEdge(e, c, &chain);
    } else {
      ++c->other_edges;
      chain.leaves.push_back(Leaf{-1});
    }
    if (i + 1 < n || ring.closed) {
      const Node& node = ring.nodes[(i + 1) % ring.NodeCount()];
      chain.links.push_back(Link{node.angle_deg, node.artificial});
    }
  }
  return chain;
}

// Tables 6.1–6.3: the ordered pair of leaves at every link, by the link's angle. Pairs
// across artificial nodes are not physical adjacencies and are not counted.
void CountPairs(const LeafChain& chain, Census* c) {
  for (int j = 0; j < static_cast<int>(chain.links.size()); ++j) {
    const Link& l = chain.links[j];
    if (l.artificial) {
      ++c->pairs_artificial;
      continue;
    }
    const int a = ClassAt(chain, j), b = ClassAt(chain, j + 1), bucket = AngleBucket(l.angle_deg);
    if (a < 0 || b < 0 || bucket < 0) {
      ++c->pairs_other;
      continue;
    }
    ++c->pairs[bucket][a][b];
    ++c->pairs_counted;
  }
}

// Whether the w - 1 links after leaf s exist, are physical and coplanar.
bool CoplanarRun(const LeafChain& chain, bool closed, int s, int w) {
  const int L = static_cast<int>(chain.leaves.size());
  if (closed ? L < w : s + w > L) return false;
  for (int k = 0; k < w - 1; ++k) {
    const Link& l = chain.links[(s + k) % L];
    if (l.artificial || AngleBucket(l.angle_deg) != 1) return false;
  }
  return true;
}

// Tables 6.4–6.7: sequences of three and four leaves along one plane.
void CountSequences(const LeafChain& chain, bool closed, Census* c) {
  const int L = static_cast<int>(chain.leaves.size());
  const bool door[5] = {true, true, true, true, false};
  for (int s = 0; s < L; ++s) {
    const int a = ClassAt(chain, s), b = ClassAt(chain, s + 1), d = ClassAt(chain, s + 2),
              e = ClassAt(chain, s + 3);
    if (a < 0 || b < 0 || d < 0) continue;
    if (CoplanarRun(chain, closed, s, 3)) {
      if (door[a] && b == kCensusWall && door[d]) ++c->door_wall_door[a][d];
      if (a == kCensusWall && door[b] && d == kCensusWall) ++c->wall_door_wall[b];
    }
    if (e >= 0 && CoplanarRun(chain, closed, s, 4)) {
      if (door[a] && b == kCensusWall && door[d] && e == kCensusWall) {
        ++c->door_wall_door_wall[a][d];
      }
      if (a == kCensusWall && door[b] && d == kCensusWall && door[e]) {
        ++c->wall_door_wall_door[b][e];
      }
    }
  }
}

}  // namespace

int AngleBucket(double angle_deg) {
  if (std::abs(angle_deg - 90.0) <= 45.0) return 0;
  if (std::abs(angle_deg - 180.0) < 45.0) return 1;
  if (std::abs(angle_deg - 270.0) <= 45.0) return 2;
  return -1;
}

Census ComputeCensus(const Map& map) {
  Census c;
  c.rings = map.RingCount();
  c.joins = static_cast<int>(map.joins().size());
  for (const Ring& ring : map.rings()) {
    if (ring.closed) ++c.closed_rings;
    for (const Node& n : ring.nodes) c.artificial_nodes += n.artificial ? 1 : 0;
    const LeafChain chain = ExpandLeaves(ring, &c);
    c.leaf_edges += static_cast<int>(chain.leaves.size());
    CountPairs(chain, &c);
    CountSequences(chain, ring.closed, &c);
  }
  if (c.edges > 0) c.mean_edge_metric_in = c.total_metric_in / c.edges;
  if (c.leaf_edges > 0) c.mean_leaf_metric_in = c.total_metric_in / c.leaf_edges;
  return c;
}

}  // namespace stickrep::map
