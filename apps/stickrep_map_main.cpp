// stickrep-map: validate, census, ambiguity analysis, render, generate StickRep maps and
// build them from floor plan sources.
#include <CLI/CLI.hpp>
#include <iostream>
#include <optional>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "map_tool/map_tool.h"

int main(int argc, char** argv) {
  namespace tool = stickrep::map::tool;
  CLI::App app{
      "StickRep map tool: validate, census (Tables 6.1-6.9), ambiguity (Figure 6.1), "
      "render and generate maps"};
  app.require_subcommand(1);

  std::vector<std::string> paths;
  auto* validate = app.add_subcommand("validate", "Load and validate map files");
  validate->add_option("MAP", paths, "Map files")->required();

  std::string map_path;
  bool json = false;
  bool compare = false, no_compare = false;
  auto* census = app.add_subcommand("census", "Census in the layout of Tables 6.1-6.9");
  census->add_option("MAP", map_path, "Map file")->required();
  census->add_flag("--json", json, "JSON output");
  census->add_flag("--compare", compare, "Print the paper's numbers beside ours");
  census->add_flag("--no-compare", no_compare, "Do not print the paper's numbers");

  tool::AmbiguityCommand amb;
  double tolerance_pct = 0.0;
  bool no_angles = false;
  auto* ambiguity = app.add_subcommand(
      "ambiguity", "Edges needed before the sensed sequence matches one place (Figure 6.1)");
  ambiguity->add_option("MAP", map_path, "Map file")->required();
  ambiguity->add_flag("--json", amb.json, "JSON output");
  ambiguity->add_option("--png", amb.png, "Write a histogram PNG");
  ambiguity->add_option("--worst", amb.worst, "How many worst starts to list")
      ->check(CLI::Range(0, 100000));
  bool whole_first_edge = false;
  ambiguity->add_flag("--whole-first-edge", whole_first_edge,
                      "Sense the first edge whole (default: a first wall's length is unknown)");
  ambiguity->add_flag("--no-angles", no_angles, "Do not compare adjacency angles");
  ambiguity->add_option("--tolerance-pct", tolerance_pct, "Metric tolerance in percent")
      ->check(CLI::Range(0.0, 100.0));

  std::string png;
  auto* render = app.add_subcommand("render", "Draw the map to scale");
  render->add_option("MAP", map_path, "Map file")->required();
  render->add_option("--png", png, "Output PNG")->required();

  std::string domain, out_path;
  std::uint64_t seed = 0;
  auto* generate = app.add_subcommand("generate", "Generate one of the five domains of §6.8");
  generate
      ->add_option("DOMAIN", domain,
                   "engineering_building_3f, wells_hall_7f, "
                   "wells_hall_7f_modified, regular_polygon_46, storefront")
      ->required();
  auto* seed_opt = generate->add_option("--seed", seed, "Seed (default: the committed map's)");
  generate->add_option("--out", out_path, "Output map file")->required();

  std::string floor_source;
  auto* floor = app.add_subcommand(
      "floor", "Build a map (format 2) from a floor plan source (maps/README.md)");
  floor->add_option("SOURCE", floor_source, "Floor plan source (.floor.yaml)")->required();
  floor->add_option("--out", out_path, "Output map file")->required();

  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;

  if (*validate) return tool::Validate(paths, std::cout, std::cerr);
  if (*census) {
    std::optional<bool> cmp;
    if (compare) cmp = true;
    if (no_compare) cmp = false;
    return tool::Census(map_path, json, cmp, std::cout, std::cerr);
  }
  if (*ambiguity) {
    amb.analysis.tolerance.metric_rel = tolerance_pct / 100.0;
    amb.analysis.use_angles = !no_angles;
    amb.analysis.partial_first_edge = !whole_first_edge;
    return tool::Ambiguity(map_path, amb, std::cout, std::cerr);
  }
  if (*render) return tool::Render(map_path, png, std::cout, std::cerr);
  if (*floor) return tool::Floor(floor_source, out_path, std::cout, std::cerr);
  if (*generate) {
    std::optional<std::uint64_t> s;
    if (*seed_opt) s = seed;
    return tool::Generate(domain, s, out_path, std::cout, std::cerr);
  }
  return 1;
}
