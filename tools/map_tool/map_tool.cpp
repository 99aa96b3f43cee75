#include "map_tool/map_tool.h"

#include <chrono>
#include <ostream>
#include <stdexcept>

#include "common/input_error.h"
#include "map_tool/ambiguity_report.h"
#include "stickrep/census.h"
#include "map_tool/census_report.h"
#include "map_tool/floor_plan.h"
#include "map_tool/map_generators.h"
#include "stickrep/map_io.h"
#include "plot/map_render.h"

namespace stickrep::map::tool {

namespace {

// Runs `body`, turning a bad map into exit code 2 and any other failure into 1.
template <typename F>
int Guard(std::ostream& err, F&& body) {
  try {
    return body();
  } catch (const InputError& e) {
    err << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int Validate(const std::vector<std::string>& paths, std::ostream& out, std::ostream& err) {
  int worst = 0;
  for (const std::string& path : paths) {
    const int rc = Guard(err, [&] {
      const Map map = LoadMap(path);
      out << path << ": ok (" << map.info().name << ", " << map.RingCount() << " rings, "
          << map.EdgeCount() << " edges, " << map.joins().size() << " joins)\n";
      return 0;
    });
    worst = std::max(worst, rc);
  }
  return worst;
}

int Census(const std::string& path, bool json, std::optional<bool> compare, std::ostream& out,
           std::ostream& err) {
  return Guard(err, [&] {
    const Map map = LoadMap(path);
    const map::Census census = ComputeCensus(map);
    const bool cmp = compare.value_or(map.info().name == "engineering_building_3f");
    if (json) {
      out << CensusJson(map, census, cmp).dump(2) << "\n";
    } else {
      out << FormatCensusText(map, census, cmp);
    }
    return 0;
  });
}

int Ambiguity(const std::string& path, const AmbiguityCommand& command, std::ostream& out,
              std::ostream& err) {
  return Guard(err, [&] {
    const Map map = LoadMap(path);
    const auto t0 = std::chrono::steady_clock::now();
    const AmbiguityResult result = AnalyseAmbiguity(map, command.analysis);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    AmbiguityReportOptions report;
    report.worst = command.worst;
    report.seconds = seconds;
    if (command.json) {
      out << AmbiguityJson(map, command.analysis, result, report).dump(2) << "\n";
    } else {
      out << FormatAmbiguityText(map, command.analysis, result, report);
    }
    if (!command.png.empty()) {
      WriteAmbiguityHistogramPng(map, result, command.png);
      if (!command.json) out << "  histogram written to " << command.png << "\n";
    }
    return 0;
  });
}

int Render(const std::string& path, const std::string& png, std::ostream& out, std::ostream& err) {
  return Guard(err, [&] {
    const Map map = LoadMap(path);
    RenderMapPng(map, png);
    out << "wrote " << png << "\n";
    return 0;
  });
}

int Floor(const std::string& source, const std::string& out_path, std::ostream& out,
          std::ostream& err) {
  return Guard(err, [&] {
    const Map map = LoadFloorPlan(source);
    SaveMap(map, out_path);
    int doors = 0, openings = 0;
    for (const Ring& ring : map.rings()) {
      for (const Edge& e : ring.edges) {
        doors += e.IsDoor() ? 1 : 0;
        openings += e.IsOpening() ? 1 : 0;
      }
    }
    out << "built " << map.info().name << " from " << source << " -> " << out_path << " ("
        << map.RingCount() << " corridor outlines, " << map.EdgeCount() << " edges: " << doors
        << " doors, " << openings << " openings; " << map.obstacles().size() << " obstacles)\n";
    return 0;
  });
}

int Generate(const std::string& domain, std::optional<std::uint64_t> seed,
             const std::string& out_path, std::ostream& out, std::ostream& err) {
  return Guard(err, [&] {
    std::uint64_t s = 0;
    bool known = false;
    for (const DomainInfo& d : Domains()) {
      if (d.name == domain) {
        s = d.seed;
        known = true;
      }
    }
    if (!known) GenerateDomain(domain, 0);  // throws with the list of domains
    if (seed) s = *seed;
    const Map map = GenerateDomain(domain, s);
    SaveMap(map, out_path);
    out << "generated " << domain << " with seed " << s << " -> " << out_path << " ("
        << map.RingCount() << " rings, " << map.EdgeCount() << " edges)\n";
    return 0;
  });
}

}  // namespace stickrep::map::tool
