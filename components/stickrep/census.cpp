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

    // Expand double doors into leaves; links[j] joins leaf j to leaf j + 1 (cyclically for a
    // closed ring).
    std::vector<Leaf> leaves;
    std::vector<Link> links;
    const int n = ring.EdgeCount();
    for (int i = 0; i < n; ++i) {
      const Edge& e = ring.edges[i];
      ++c.edges;
      c.total_metric_in += e.metric_in;
      if (e.IsDoor()) {
        const DoorClass cls = *e.door_class;
        const int leaves_here = IsDoubleDoor(cls) ? 2 : 1;
        const int row = CensusClassOf(LeafClass(cls));
        ++c.doors_by_class[static_cast<int>(cls)];
        c.door_leaves += leaves_here;
        for (int k = 0; k < leaves_here; ++k) {
          if (k > 0) links.push_back(Link{180.0, false});
          leaves.push_back(Leaf{row});
        }
        if (row >= 0) {
          c.door_census[row][0] += leaves_here;
          for (std::size_t p = 0; p < paper::kPatternWords.size(); ++p) {
            if (e.pattern == paper::kPatternWords[p]) c.door_census[row][p + 1] += leaves_here;
          }
        }
      } else if (e.IsWall()) {
        ++c.walls;
        leaves.push_back(Leaf{kCensusWall});
        for (std::size_t t = 0; t < paper::kWallThresholdsIn.size(); ++t) {
          const double th = paper::kWallThresholdsIn[t];
          if (t == 0 ? e.metric_in > th : e.metric_in >= th) ++c.wall_census[t];
        }
      } else {
        ++c.other_edges;
        leaves.push_back(Leaf{-1});
      }
      if (i + 1 < n || ring.closed) {
        const Node& node = ring.nodes[(i + 1) % ring.NodeCount()];
        links.push_back(Link{node.angle_deg, node.artificial});
      }
    }
    const int L = static_cast<int>(leaves.size());
    c.leaf_edges += L;
    auto leaf = [&](int j) { return leaves[j % L].cls; };
    // Whether the w - 1 links after leaf s exist, are physical and coplanar.
    auto coplanar_run = [&](int s, int w) {
      if (ring.closed ? L < w : s + w > L) return false;
      for (int k = 0; k < w - 1; ++k) {
        const Link& l = links[(s + k) % L];
        if (l.artificial || AngleBucket(l.angle_deg) != 1) return false;
      }
      return true;
    };
    for (int j = 0; j < static_cast<int>(links.size()); ++j) {
      const Link& l = links[j];
      if (l.artificial) {
        ++c.pairs_artificial;
        continue;
      }
      const int a = leaf(j), b = leaf(j + 1), bucket = AngleBucket(l.angle_deg);
      if (a < 0 || b < 0 || bucket < 0) {
        ++c.pairs_other;
        continue;
      }
      ++c.pairs[bucket][a][b];
      ++c.pairs_counted;
    }
    const bool door[5] = {true, true, true, true, false};
    for (int s = 0; s < L; ++s) {
      const int a = leaf(s), b = leaf(s + 1), d = leaf(s + 2), e = leaf(s + 3);
      if (a < 0 || b < 0 || d < 0) continue;
      if (coplanar_run(s, 3)) {
        if (door[a] && b == kCensusWall && door[d]) ++c.door_wall_door[a][d];
        if (a == kCensusWall && door[b] && d == kCensusWall) ++c.wall_door_wall[b];
      }
      if (e >= 0 && coplanar_run(s, 4)) {
        if (door[a] && b == kCensusWall && door[d] && e == kCensusWall) {
          ++c.door_wall_door_wall[a][d];
        }
        if (a == kCensusWall && door[b] && d == kCensusWall && door[e]) {
          ++c.wall_door_wall_door[b][e];
        }
      }
    }
  }
  if (c.edges > 0) c.mean_edge_metric_in = c.total_metric_in / c.edges;
  if (c.leaf_edges > 0) c.mean_leaf_metric_in = c.total_metric_in / c.leaf_edges;
  return c;
}

}  // namespace stickrep::map
