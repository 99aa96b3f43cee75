#include "launch/launch_graph.h"

#include <set>

namespace stickrep::launch {

LaunchGraph LaunchGraph::Load(const StrictYaml& root) {
  LaunchGraph g;
  g.file = root.file();
  const StrictYaml l = root.Child("launch");
  g.name = l.Get<std::string>("name");
  g.until_exit_of = l.GetOr<std::string>("until_exit_of", "");
  g.max_duration_s = l.GetOr<double>("max_duration_s", 0.0);
  if (g.max_duration_s < 0.0) l.Fail("max_duration_s", "must not be negative");
  g.start_spacing_s = l.GetOr<double>("start_spacing_s", 0.0);
  if (g.start_spacing_s < 0.0 || g.start_spacing_s > 10.0) {
    l.Fail("start_spacing_s", "must be within [0, 10] s");
  }
  std::set<std::string> names;
  for (const StrictYaml& p : l.Sequence("processes")) {
    ProcessSpec spec;
    spec.name = p.Get<std::string>("name");
    spec.executable = p.Get<std::string>("executable");
    if (p.Has("args")) {
      for (const StrictYaml& a : p.Sequence("args")) spec.args.push_back(a.As<std::string>());
    } else {
      p.GetOr<std::string>("args", "");
    }
    if (!names.insert(spec.name).second) p.Fail("name", "process '" + spec.name + "' twice");
    p.Finish();
    g.processes.push_back(std::move(spec));
  }
  if (g.processes.empty()) l.Fail("processes", "a graph needs at least one process");
  if (!g.until_exit_of.empty() && names.count(g.until_exit_of) == 0) {
    l.Fail("until_exit_of", "no process named '" + g.until_exit_of + "'");
  }
  l.Finish();
  root.Finish();
  return g;
}

LaunchGraph LaunchGraph::LoadFile(const std::string& path) {
  return Load(StrictYaml::LoadFile(path));
}

std::string SubstitutePlaceholders(const std::string& arg, const std::string& graph_dir,
                                   const std::string& config_dir) {
  std::string out = arg;
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{graph_dir}", graph_dir},
                                   {"{config_dir}", config_dir}}) {
    for (auto pos = out.find(key); pos != std::string::npos; pos = out.find(key, pos)) {
      out.replace(pos, key.size(), value);
      pos += value.size();
    }
  }
  return out;
}

}  // namespace stickrep::launch
