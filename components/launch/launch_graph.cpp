#include "launch/launch_graph.h"

#include <filesystem>
#include <set>

#include "common/input_error.h"

namespace stickrep::launch {

const char* ToString(RestartPolicy::When when) {
  switch (when) {
    case RestartPolicy::When::kNever: return "never";
    case RestartPolicy::When::kOnFailure: return "on-failure";
    case RestartPolicy::When::kAlways: return "always";
  }
  return "?";
}

namespace {

RestartPolicy::When ParseWhen(const StrictYaml& node, const std::string& key,
                              const std::string& text) {
  for (const auto when : {RestartPolicy::When::kNever, RestartPolicy::When::kOnFailure,
                          RestartPolicy::When::kAlways}) {
    if (text == ToString(when)) return when;
  }
  node.Fail(key, "'" + text + "' is not one of: never, on-failure, always");
}

}  // namespace

RestartPolicy LoadRestartPolicy(const StrictYaml& node, const std::string& key,
                                RestartPolicy p) {
  const StrictYaml r = node.Child(key);
  if (r.IsScalar()) {
    p.when = ParseWhen(node, key, r.As<std::string>());
    return p;
  }
  if (!r.IsMap()) node.Fail(key, "expected a policy name or a mapping with `policy`");
  p.when = ParseWhen(r, "policy", r.Get<std::string>("policy"));
  p.backoff_initial_s = r.GetOr<double>("backoff_initial_s", p.backoff_initial_s);
  if (!(p.backoff_initial_s >= 0.05 && p.backoff_initial_s <= 60.0)) {
    r.Fail("backoff_initial_s", "must be within [0.05, 60] s");
  }
  p.backoff_max_s = r.GetOr<double>("backoff_max_s", p.backoff_max_s);
  if (!(p.backoff_max_s >= p.backoff_initial_s && p.backoff_max_s <= 600.0)) {
    r.Fail("backoff_max_s", "must be within [backoff_initial_s, 600] s");
  }
  p.max_restarts = r.GetOr<int>("max_restarts", p.max_restarts);
  if (p.max_restarts < 0) r.Fail("max_restarts", "must not be negative (0: no limit)");
  r.Finish();
  return p;
}

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
  g.handshake_timeout_s = l.GetOr<double>("handshake_timeout_s", g.handshake_timeout_s);
  if (g.handshake_timeout_s != 0.0 &&
      (g.handshake_timeout_s < 5.0 || g.handshake_timeout_s > 600.0)) {
    l.Fail("handshake_timeout_s", "must be 0 (never) or within [5, 600] s");
  }
  if (l.Has("restart")) g.restart = LoadRestartPolicy(l, "restart", g.restart);
  if (l.Has("parameters")) {
    const StrictYaml params = l.Child("parameters");
    for (const std::string& key : params.Keys()) {
      if (key == "graph_dir" || key == "config_dir" || key == "security_dir") {
        params.Fail(key, "a built-in placeholder cannot be a parameter");
      }
      g.parameters[key] = params.Get<std::string>(key);
      try {
        SubstitutePlaceholders(g.parameters[key], {{"graph_dir", ""}, {"config_dir", ""}});
      } catch (const InputError& e) {
        params.Fail(key, e.reason() + " (a parameter may use only those two)");
      }
    }
    params.Finish();
  }
  std::map<std::string, std::string> known = g.parameters;
  known["graph_dir"] = known["config_dir"] = known["security_dir"] = "";
  const auto check = [&](const StrictYaml& node, const std::string& key, const std::string& arg) {
    try {
      SubstitutePlaceholders(arg, known);
    } catch (const InputError& e) {
      node.Fail(key, e.reason());
    }
  };
  if (l.Has("common_args")) {
    for (const StrictYaml& a : l.Sequence("common_args")) {
      g.common_args.push_back(a.As<std::string>());
      check(l, "common_args", g.common_args.back());
    }
  }
  std::set<std::string> names;
  for (const StrictYaml& p : l.Sequence("processes")) {
    ProcessSpec spec;
    spec.name = p.Get<std::string>("name");
    spec.executable = p.Get<std::string>("executable");
    if (p.Has("args")) {
      for (const StrictYaml& a : p.Sequence("args")) {
        spec.args.push_back(a.As<std::string>());
        check(p, "args", spec.args.back());
      }
    } else {
      p.GetOr<std::string>("args", "");
    }
    spec.use_common_args = p.GetOr<bool>("use_common_args", true);
    if (p.Has("secure_args")) {
      for (const StrictYaml& a : p.Sequence("secure_args")) {
        spec.secure_args.push_back(a.As<std::string>());
        check(p, "secure_args", spec.secure_args.back());
      }
    }
    spec.restart = p.Has("restart") ? LoadRestartPolicy(p, "restart", g.restart) : g.restart;
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

std::string SubstitutePlaceholders(const std::string& arg,
                                   const std::map<std::string, std::string>& values) {
  std::string out;
  size_t pos = 0;
  while (pos < arg.size()) {
    const size_t open = arg.find('{', pos);
    const size_t close = open == std::string::npos ? open : arg.find('}', open);
    if (close == std::string::npos) {
      out += arg.substr(pos);
      break;
    }
    const std::string name = arg.substr(open + 1, close - open - 1);
    const auto it = values.find(name);
    if (it == values.end()) {
      throw InputError("", 0, "", "'{" + name + "}' in '" + arg +
                                      "' is neither {graph_dir}, {config_dir}, {security_dir} "
                                      "nor a parameter of the graph");
    }
    out += arg.substr(pos, open - pos) + it->second;
    pos = close + 1;
  }
  return out;
}

std::map<std::string, std::string> PlaceholderValues(const LaunchGraph& graph,
                                                     const std::string& config_dir,
                                                     const std::vector<std::string>& overrides,
                                                     const std::string& security_dir) {
  std::map<std::string, std::string> values = graph.parameters;
  for (const std::string& o : overrides) {
    const auto eq = o.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError("--set", 0, o, "expected NAME=VALUE");
    }
    const std::string name = o.substr(0, eq);
    if (values.count(name) == 0) {
      std::string known;
      for (const auto& [k, v] : graph.parameters) known += (known.empty() ? "" : ", ") + k;
      throw InputError(graph.file, 0, "launch.parameters." + name,
                       "--set names no parameter of this graph (it has: " +
                           (known.empty() ? "none" : known) + ")");
    }
    values[name] = o.substr(eq + 1);
  }
  // A parameter's value may itself name {graph_dir} or {config_dir}.
  const std::map<std::string, std::string> dirs = {
      {"graph_dir", std::filesystem::path(graph.file).parent_path().string()},
      {"config_dir", config_dir}};
  for (auto& [name, value] : values) value = SubstitutePlaceholders(value, dirs);
  values.insert(dirs.begin(), dirs.end());
  values["security_dir"] = security_dir;
  return values;
}

}  // namespace stickrep::launch
